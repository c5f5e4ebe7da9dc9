// gblens.open_sequence, gblens.Sequence, gblens.motion and gblens.flicker: a sequence folder
// (views/capture/sequence.h, docs/temporal.md) as frames loaded when asked and as arrays with a time
// axis first; the motion-vector check and the flicker statistics (views/analysis/temporal.h) as the
// CLI's JSON with their per-pixel maps as numpy arrays.
#include <cstring>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "app/python/python.h"
#include "app/python/sequence_docstrings.h"
#include "views/analysis/temporal.h"

namespace gb::python {

namespace {

struct SequenceHandle {
  Sequence seq;
};
using SequencePtr = std::shared_ptr<SequenceHandle>;

SequencePtr openSequence(const std::string& dir) {
  auto s = std::make_shared<SequenceHandle>();
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = loadSequence(dir, s->seq, error);
  }
  if (!ok) fail(error);
  return s;
}

// A Sequence, or a path opened as one (motion's and flicker's argument).
SequencePtr sequenceOf(const py::object& o) {
  if (py::isinstance<SequenceHandle>(o)) return o.cast<SequencePtr>();
  return openSequence(py::str(o));
}

// Frame `number` as `gblens.open("SEQ@N")` opens it: the same folder, the same messages.
FramePtr frameNumbered(const SequencePtr& s, int64_t number) { return openCapture(s->seq.dir + "@" + std::to_string(number)); }

FramePtr frameAt(const SequencePtr& s, int64_t index) {
  const int64_t n = int64_t(s->seq.frames.size());
  if (index < -n || index >= n)
    throw py::index_error("index " + std::to_string(index) + ": the sequence has " + std::to_string(n) + " frames (numbers " +
                          std::to_string(s->seq.frames.front().number) + ".." + std::to_string(s->seq.frames.back().number) +
                          "; seq.frame(number) takes a number)");
  return frameNumbered(s, s->seq.frames[size_t(index < 0 ? index + n : index)].number);
}

std::string sizeText(const std::vector<py::ssize_t>& shape) {
  std::string t;
  for (py::ssize_t d : shape) t += (t.empty() ? "(" : ", ") + std::to_string(d);
  return t + ")";
}

// seq.array(name, stored): every frame's `frame[name]` (or its stored target `name`), stacked on a time axis.
py::array stacked(const SequencePtr& s, const std::string& name, bool stored) {
  auto bytes = std::make_shared<std::vector<uint8_t>>();
  std::vector<py::ssize_t> frameShape;
  py::dtype dtype("float64");
  for (size_t i = 0; i < s->seq.frames.size(); ++i) {
    const FramePtr f = frameNumbered(s, s->seq.frames[i].number);
    const FrameSnapshot& F = f->capture.frame;
    std::vector<py::ssize_t> shape;
    const size_t before = bytes->size();
    if (!stored) {
      const Decoded d = decodeQuantity(f, name);  // QuantityError as frame[name]
      shape = d.shape;
      bytes->resize(before + d.values.size() * sizeof(double));
      std::memcpy(bytes->data() + before, d.values.data(), d.values.size() * sizeof(double));
    } else {
      const int t = F.layout.findTarget(name);
      if (t < 0) {
        std::string names;
        for (const LayoutTarget& lt : F.layout.targets) names += (names.empty() ? "" : ", ") + lt.name;
        failArgument("name=\"" + name + "\": not a target of " + s->seq.captureDir(i) + " (targets: " + names + ")");
      }
      if (!F.images[size_t(t)].present())
        fail(name + ": " + s->seq.captureDir(i) + " does not hold target " + name + " (" + absentText(F.absences[size_t(t)]) + ")");
      const CpuImage& img = F.images[size_t(t)].image;
      dtype = dtypeOfPixels(img.type);
      shape = {py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(img.channelCount())};
      bytes->insert(bytes->end(), img.data.begin(), img.data.end());
    }
    if (i == 0) {
      frameShape = shape;
      bytes->reserve(bytes->size() * s->seq.frames.size());
    } else if (shape != frameShape) {
      fail(s->seq.captureDir(i) + ": " + name + " is " + sizeText(shape) + ", frame " + std::to_string(s->seq.frames[0].number) +
           "'s is " + sizeText(frameShape));
    }
  }
  std::vector<py::ssize_t> shape{py::ssize_t(s->seq.frames.size())};
  shape.insert(shape.end(), frameShape.begin(), frameShape.end());
  const uint8_t* data = bytes->data();
  return view(dtype, std::move(shape), data, std::move(bytes));
}

// The engine's message with a CLI flag in it named as the keyword argument: an ArgumentError then.
[[noreturn]] void failKeyword(std::string message, const std::vector<std::pair<std::string, std::string>>& flags) {
  for (const auto& [flag, keyword] : flags)
    if (const size_t at = message.find(flag + " "); at != std::string::npos && (at == 0 || message[at - 1] == ' ')) {
      message.replace(at, flag.size() + 1, keyword + "=");
      failArgument(message);
    }
  fail(message);
}

// An engine image of one channel as (H, W), of several as (H, W, C); the report keeps its memory.
template <class Owner>
py::array imageArray(const CpuImage& img, const std::shared_ptr<Owner>& owner) {
  std::vector<py::ssize_t> shape{py::ssize_t(img.height), py::ssize_t(img.width)};
  if (img.channelCount() != 1) shape.push_back(py::ssize_t(img.channelCount()));
  return view(dtypeOfPixels(img.type), std::move(shape), img.data.data(), owner);
}

py::dict motion(const py::object& sequence, const py::object& motionName, const py::object& bound) {
  const SequencePtr s = sequenceOf(sequence);
  MotionSequenceOptions o;
  if (!motionName.is_none()) o.motion = py::str(motionName);
  if (!bound.is_none()) {
    o.inlierPixels = bound.cast<double>();
    if (!(o.inlierPixels >= 0.0 && o.inlierPixels <= 1000.0))
      failArgument("bound=" + std::string(py::str(bound)) + ": outside [0, 1000] (pixels; 0: derived from the frames' precision)");
  }
  auto r = std::make_shared<MotionReport>();
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = checkMotionSequence(s->seq, o, *r, error);
  }
  if (!ok) failKeyword(error, {{"--motion", "motion"}});
  py::dict out = toPython(motionReportJson(*r, s->seq.dir));
  py::list maps;
  for (const MotionPair& p : r->pairs) {
    py::dict m;
    m["previous"] = p.previous, m["current"] = p.current;
    m["error"] = imageArray(p.errorMap, r), m["class"] = imageArray(p.classMap, r);
    maps.append(m);
  }
  out["maps"] = maps;
  return out;
}

py::dict flicker(const py::object& sequence, const std::string& quantity, const py::object& reference, bool reproject) {
  const SequencePtr s = sequenceOf(sequence);
  FlickerOptions o;
  o.quantity = quantity, o.reproject = reproject;
  if (!reference.is_none()) o.reference = reference.cast<int64_t>();
  auto r = std::make_shared<FlickerReport>();
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = flickerSequence(s->seq, o, *r, error);
  }
  if (!ok) failKeyword(error, {{"--quantity", "quantity"}, {"--reference", "reference"}});
  py::dict out = toPython(flickerReportJson(*r));
  // The maps beside the JSON's keys (its "stddev" and "max_step" are the figures over the frame).
  py::dict maps;
  maps["stddev"] = imageArray(r->stddev, r), maps["max_step"] = imageArray(r->maxStep, r);
  // How many frames saw each point, as integers (the EXR holds them as floats for image tools).
  std::vector<uint32_t> seen(size_t(r->seen.width) * r->seen.height);
  const float* counts = reinterpret_cast<const float*>(r->seen.data.data());
  for (size_t i = 0; i < seen.size(); ++i) seen[i] = uint32_t(counts[i]);
  maps["seen"] = adopt(std::move(seen), {py::ssize_t(r->seen.height), py::ssize_t(r->seen.width)});
  out["maps"] = maps;
  return out;
}

py::object optional(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::object(py::none()); }

}  // namespace

void bindSequence(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<SequenceHandle, SequencePtr>(m, "Sequence", doc::kSequence)
      .def_property_readonly("path", [](const SequencePtr& s) { return s->seq.dir; }, doc::kSequencePath)
      .def_property_readonly("manifest", [](const SequencePtr& s) { return toPython(s->seq.manifest); }, doc::kSequenceManifest)
      .def_property_readonly("frames", [](const SequencePtr& s) {
        std::vector<int64_t> out;
        for (const SequenceFrame& f : s->seq.frames) out.push_back(f.number);
        return out;
      }, doc::kSequenceFrames)
      .def_property_readonly("times", [](const SequencePtr& s) {
        py::list out;
        for (const SequenceFrame& f : s->seq.frames) out.append(optional(f.time));
        return out;
      }, doc::kSequenceTimes)
      .def_property_readonly("jitters", [](const SequencePtr& s) {
        py::list out;
        for (const SequenceFrame& f : s->seq.frames)
          out.append(f.jitter ? py::object(py::make_tuple(f.jitter->x, f.jitter->y)) : py::object(py::none()));
        return out;
      }, doc::kSequenceJitters)
      .def("__len__", [](const SequencePtr& s) { return s->seq.frames.size(); })
      .def("__getitem__", [](const SequencePtr& s, const py::object& key) -> py::object {
        if (py::isinstance<py::str>(key)) return stacked(s, py::str(key), false);
        if (!py::hasattr(key, "__index__")) throw py::type_error("seq[key]: an index (int) or a quantity's name (str)");
        return py::cast(frameAt(s, key.attr("__index__")().cast<int64_t>()));
      }, "key"_a, doc::kSequenceGetItem)
      .def("frame", &frameNumbered, "number"_a, doc::kSequenceFrame)
      .def("array", &stacked, "name"_a, "stored"_a = false, doc::kSequenceArray)
      .def("__repr__", [](const SequencePtr& s) {
        const auto& f = s->seq.frames;
        return "<gblens.Sequence " + std::to_string(f.size()) + " frames (" + std::to_string(f.front().number) + ".." +
               std::to_string(f.back().number) + "), " + s->seq.dir + ">";
      });
  m.def("open_sequence", [](const py::object& path) { return openSequence(py::str(path)); }, "path"_a, doc::kOpenSequence);
  m.def("motion", &motion, "sequence"_a, "motion"_a = py::none(), "bound"_a = py::none(), doc::kMotion);
  m.def("flicker", &flicker, "sequence"_a, "quantity"_a, "reference"_a = py::none(), "reproject"_a = true, doc::kFlicker);
}

}  // namespace gb::python
