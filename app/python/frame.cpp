// gblens.open and gblens.Frame: a capture folder or an import as a frame; its stored targets as numpy
// arrays over the frame's own memory, its quantities decoded (views/analysis/decoded_image.h) in the
// layout's units and space, positions, masks, the probe, region statistics, check, save.
#include <algorithm>
#include <filesystem>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "views/analysis/check.h"
#include "views/analysis/compare.h"
#include "views/analysis/decoded_image.h"
#include "views/analysis/probe.h"
#include "views/analysis/view_table.h"
#include "views/analysis/region_stats.h"
#include "views/import/import_renderdoc.h"
#include "app/python/docstrings.h"
#include "app/python/python.h"

namespace gb::python {

namespace {

py::dtype dtypeOf(PixelType t) {
  switch (t) {
    case PixelType::U8: return py::dtype("uint8");
    case PixelType::I8: return py::dtype("int8");
    case PixelType::U16: return py::dtype("uint16");
    case PixelType::I16: return py::dtype("int16");
    case PixelType::U32: return py::dtype("uint32");
    case PixelType::F16: return py::dtype("float16");
    case PixelType::F32: return py::dtype("float32");
  }
  return py::dtype("uint8");
}

const FrameSnapshot& frameOfHandle(const FramePtr& h) { return h->capture.frame; }

// A quantity's view by name (case, '_', '-' and spaces ignored, as --target and --view find them).
ViewDef findQuantity(const FrameSnapshot& f, const std::string& name) {
  const std::vector<ViewDef> views = layoutViews(f.layout);
  const int i = findView(views, name);
  if (i < 0) throw QuantityError("\"" + name + "\": no quantity of that name (quantities: " + viewNameList(views) + ")");
  return views[size_t(i)];
}

// Why the frame has no values of view `v` (its target is not in it).
std::string missingReason(const FrameSnapshot& f, const ViewDef& v) {
  return "the frame does not hold target " + f.layout.targets[v.target].name + " (" + absentText(f.absences[v.target]) + ")";
}

py::array quantityArray(const FramePtr& h, const std::string& name) {
  Decoded d = decodeQuantity(h, name);
  return adopt(std::move(d.values), std::move(d.shape));
}

// Positions from the first camera depth ("depth"), the stored position ("stored") or a depth quantity
// named, in eye space or the layout's world axes.
py::array position(const FramePtr& h, const std::string& source, const std::string& space) {
  const FrameSnapshot& f = frameOfHandle(h);
  if (space != "world" && space != "eye") failArgument("space=\"" + space + "\": world or eye");
  const Quantity* q = source == "depth" ? surfaceDepth(f.layout) : source == "stored" ? f.layout.find(QuantityKind::Position) : nullptr;
  if (source != "depth" && source != "stored") {
    q = &f.layout.quantities[size_t(findQuantity(f, source).quantity)];
    if (q->kind != QuantityKind::Depth || q->ofSun) failArgument("source=\"" + source + "\": depth, stored or a camera depth's name");
  }
  if (!q) failArgument("source=\"" + source + "\": the layout has no " + std::string(source == "depth" ? "camera depth" : "stored position"));
  if (!layoutImage(f, q->target)) fail("position: the frame does not hold target " + f.layout.targets[q->target].name);
  const TargetImage& ti = *layoutImage(f, q->target);
  std::vector<double> out(size_t(ti.image.width) * ti.image.height * 3);
  {
    py::gil_scoped_release release;
    for (uint32_t y = 0; y < ti.image.height; ++y)
      for (uint32_t x = 0; x < ti.image.width; ++x) {
        const std::optional<glm::dvec3> e = decodePosition(f, *q, x + ti.x0, y + ti.y0);
        const glm::dvec3 p = !e ? glm::dvec3(NAN) : space == "eye" ? *e : spaceFromEye(f, Space::World, *e, true);
        double* o = &out[(size_t(y) * ti.image.width + x) * 3];
        o[0] = p.x, o[1] = p.y, o[2] = p.z;
      }
  }
  return adopt(std::move(out), {py::ssize_t(ti.image.height), py::ssize_t(ti.image.width), 3});
}

py::array mask(const FramePtr& h, const std::string& name) {
  const FrameSnapshot& f = frameOfHandle(h);
  std::vector<uint8_t> out(size_t(f.camera.width) * f.camera.height);
  if (name == "surface") {
    for (uint32_t y = 0; y < f.camera.height; ++y)
      for (uint32_t x = 0; x < f.camera.width; ++x) out[size_t(y) * f.camera.width + x] = hasSurface(f, x, y);
  } else {  // compare's masks, of this frame alone
    CompareMask m;
    std::string error;
    if (!buildCompareMask(h->capture, h->capture, name, m, error)) failArgument("name=" + name + ": " + error);
    for (size_t i = 0; i < out.size(); ++i) out[i] = m.bits[i] != 0;
  }
  py::array a = adopt(std::move(out), {py::ssize_t(f.camera.height), py::ssize_t(f.camera.width)});
  return a.attr("view")("bool");
}

py::dict targets(const FramePtr& h) {
  py::dict out;
  const FrameSnapshot& f = frameOfHandle(h);
  for (size_t t = 0; t < f.images.size(); ++t) {
    const CpuImage& img = f.images[t].image;
    if (!f.images[t].present()) continue;
    out[py::str(f.layout.targets[t].name)] =
        view(dtypeOf(img.type), {py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(img.channelCount())},
             img.data.data(), h);
  }
  return out;
}

py::dict camera(const FramePtr& h) {
  const FrameSnapshot& f = frameOfHandle(h);
  const Camera& c = f.camera;
  auto matrix = [](const glm::dmat4& m) {
    std::vector<double> rows(16);
    for (int r = 0; r < 4; ++r)
      for (int col = 0; col < 4; ++col) rows[size_t(r * 4 + col)] = m[col][r];  // glm is column-major
    return adopt(std::move(rows), {4, 4});
  };
  const glm::dmat3 lw = layoutWorldFromWorld(f.layout.camera);
  std::vector<double> rot(9);
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col) rot[size_t(r * 3 + col)] = lw[col][r];
  py::dict d;
  d["width"] = c.width, d["height"] = c.height, d["yfov"] = c.yfov, d["aspect"] = c.aspect;
  d["znear"] = c.znear, d["zfar"] = c.zfar, d["reversed_z"] = c.reversedZ;
  d["world_from_eye"] = matrix(c.worldFromEye), d["eye_from_world"] = matrix(c.eyeFromWorld);
  d["clip_from_eye"] = matrix(c.clipFromEye), d["eye_from_clip"] = matrix(c.eyeFromClip);
  d["clip_from_world"] = matrix(c.clipFromWorld);
  d["layout_world_from_world"] = adopt(std::move(rot), {3, 3});
  return d;
}

// gblens.open(path, layout=None, params={}, camera=None, size=None): the CLI's `import` without -o.
FramePtr importFrames(const std::vector<std::string>& inputs, const std::string& layout, const py::dict& params,
                      const std::string& cameraFile, const std::string& size) {
  RenderOptions options;
  std::string error;
  for (auto [key, value] : params) {
    std::string name = py::str(key);
    std::replace(name.begin(), name.end(), '-', '_');
    if (!findOption(name)) failArgument("params: \"" + std::string(py::str(key)) + "\" is no option of gblens --help (e.g. normal_format)");
    if (!setOption(options, name, py::str(value), error)) failArgument("params: " + name + ": " + error);
  }
  if (!size.empty() && !setOption(options, "size", size, error)) failArgument("size=" + size + ": " + error);
  ImportInput in;
  if (!loadImportLayout(layout, layoutParameters(options), in.layout, in.layoutDir, error)) fail(error);
  if (const std::string why = importCameraRefusal(in.layout); !why.empty()) fail(why);
  if (!size.empty()) in.layout.width = options.width, in.layout.height = options.height;
  in.cameraFile = cameraFile;
  const bool rdc = inputs.size() == 1 && std::filesystem::path(inputs[0]).extension() == ".rdc";
  if (rdc) {
    RenderDocImported read;
    if (!readRenderDocImport({inputs[0], 0, "", !cameraFile.empty(), {}}, in, read, error)) fail(error);
  } else {
    in.files = inputs;
  }
  auto h = std::make_shared<FrameHandle>();
  FrameSnapshot& frame = h->capture.frame;
  if (!importFrame(in, frame, error)) fail(error);
  const RenderOptions imported = frame.options;
  frame.options = options;
  frame.options.width = imported.width, frame.options.height = imported.height, frame.options.reversedZ = imported.reversedZ;
  h->meta.scene = "import:";
  for (const std::string& i : inputs) h->meta.scene += " " + i;
  h->capture.dir = h->meta.scene;
  h->capture.manifest = {{"scene", {{"source", h->meta.scene}}}, {"layout", layoutJson(frame.layout)}};
  return h;
}

FramePtr open(const py::object& path, const py::object& layout, const py::dict& params, const py::object& cameraFile,
              const py::object& size) {
  std::vector<std::string> inputs;
  if (py::isinstance<py::str>(path) || py::hasattr(path, "__fspath__")) inputs.push_back(py::str(path));
  else for (const py::handle& p : path) inputs.push_back(py::str(p));
  if (inputs.empty()) failArgument("path: no path given");
  if (layout.is_none()) {
    if (inputs.size() != 1) failArgument("path: several files are an import: give layout=");
    if (!params.empty() || !cameraFile.is_none() || !size.is_none()) failArgument("params, camera and size apply to an import (layout=)");
    return openCapture(inputs[0]);
  }
  return importFrames(inputs, py::str(layout), params, cameraFile.is_none() ? "" : std::string(py::str(cameraFile)),
                      size.is_none() ? "" : std::string(py::str(size)));
}

}  // namespace

Decoded decodeQuantity(const FramePtr& h, const std::string& name) {
  const FrameSnapshot& f = frameOfHandle(h);
  const ViewDef v = findQuantity(f, name);
  const TargetImage* ti = layoutImage(f, v.target);
  if (!ti) fail(name + ": " + missingReason(f, v));
  Decoded d;
  {
    py::gil_scoped_release release;
    d.values = decodedImage<double>(f, v);
  }
  // A scalar is (H, W), as numpy and OpenImageIO give one channel; vectors and colours (H, W, C).
  const py::ssize_t components = py::ssize_t(decodedComponents(f, v));
  d.shape = {py::ssize_t(ti->image.height), py::ssize_t(ti->image.width)};
  if (components != 1) d.shape.push_back(components);
  return d;
}

py::dtype dtypeOfPixels(PixelType t) { return dtypeOf(t); }

FramePtr openCapture(const std::string& dir) {
  auto h = std::make_shared<FrameHandle>();
  std::string error;
  {
    py::gil_scoped_release release;
    if (!loadCapture(dir, h->capture, error)) h.reset();
  }
  if (!h) fail(error);
  const nlohmann::json& m = h->capture.manifest;
  h->meta.device = m.value("device", ""), h->meta.driver = m.value("driver", "");
  h->meta.scene = m.value("scene", nlohmann::json::object()).value("source", "");
  h->meta.sceneSha256 = m.value("scene", nlohmann::json::object()).value("content_sha256", "");
  h->meta.commandLine = m.value("command", "");
  return h;
}

FramePtr frameOf(const py::object& o) {
  if (py::isinstance<FrameHandle>(o)) return o.cast<FramePtr>();
  return openCapture(py::str(o));
}

void bindFrame(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<FrameHandle, FramePtr>(m, "Frame", doc::kFrame)
      .def_property_readonly("path", [](const FramePtr& h) { return h->capture.dir; }, doc::kPath)
      .def_property_readonly("width", [](const FramePtr& h) { return h->capture.frame.camera.width; }, doc::kWidth)
      .def_property_readonly("height", [](const FramePtr& h) { return h->capture.frame.camera.height; }, doc::kHeight)
      .def_property_readonly("layout", [](const FramePtr& h) { return toPython(layoutJson(h->capture.frame.layout)); }, doc::kLayout)
      .def_property_readonly("manifest", [](const FramePtr& h) { return toPython(h->capture.manifest); }, doc::kManifest)
      .def_property_readonly("camera", &camera, doc::kCamera)
      .def_property_readonly("targets", &targets, doc::kTargets)
      .def_property_readonly("quantities", [](const FramePtr& h) {
        std::vector<std::string> names;
        for (const ViewDef& v : layoutViews(h->capture.frame.layout))
          if (layoutImage(h->capture.frame, v.target)) names.push_back(v.name);
        return names;
      }, doc::kQuantities)
      .def_property_readonly("missing_quantities", [](const FramePtr& h) {
        py::dict out;
        const FrameSnapshot& f = h->capture.frame;
        for (const ViewDef& v : layoutViews(f.layout))
          if (!layoutImage(f, v.target)) out[py::str(v.name)] = missingReason(f, v);
        return out;
      }, doc::kMissingQuantities)
      .def("quantity", &quantityArray, "name"_a, doc::kQuantity)
      .def("__getitem__", &quantityArray, "name"_a, doc::kGetItem)
      .def("position", &position, "source"_a = "depth", "space"_a = "world", doc::kPosition)
      .def("mask", &mask, "name"_a = "surface", doc::kMask)
      .def("probe", [](const FramePtr& h, int64_t x, int64_t y) {
        const Camera& c = h->capture.frame.camera;
        if (x < 0 || y < 0 || x >= int64_t(c.width) || y >= int64_t(c.height))
          failArgument("x=" + std::to_string(x) + ", y=" + std::to_string(y) + ": outside the " + std::to_string(c.width) +
                       "x" + std::to_string(c.height) + " frame (0 <= x < width, 0 <= y < height)");
        const PixelDossier d = probePixel(h->capture.frame, uint32_t(x), uint32_t(y));
        if (!d.error.empty()) fail(d.error);
        return toPython(dossierJson(d));
      }, "x"_a, "y"_a, doc::kProbe)
      .def("stats", [](const FramePtr& h, const py::object& rect, const std::string& target, int bins) {
        std::string text = py::str(rect), error;
        if (!py::isinstance<py::str>(rect)) {
          text.clear();
          for (const py::handle& v : rect) text += (text.empty() ? "" : ",") + std::string(py::str(v));
        }
        RegionRect r;
        const Camera& c = h->capture.frame.camera;
        if (!parseRegionRect(text, c.width, c.height, r, error)) failArgument("rect=" + error);
        if (!target.empty() && h->capture.frame.layout.findTarget(target) < 0) {
          std::string names;
          for (const LayoutTarget& t : h->capture.frame.layout.targets) names += (names.empty() ? "" : ", ") + t.name;
          failArgument("target=\"" + target + "\": not a target of this frame (targets: " + names + ")");
        }
        return toPython(regionStatsJson(regionStats(h->capture.frame, r, target, bins)));
      }, "rect"_a, "target"_a = "", "bins"_a = 32, doc::kStats)
      .def("check", [](const FramePtr& h, const py::object& rules) {
        // The policy as `check --policy RULE`: ["denormal=fault", ...] or {"Normal.out_of_range": "warn"}.
        std::vector<std::string> texts;
        if (py::isinstance<py::dict>(rules))
          for (auto [k, v] : rules.cast<py::dict>()) texts.push_back(std::string(py::str(k)) + "=" + std::string(py::str(v)));
        else if (!rules.is_none())
          for (const py::handle& r : rules) texts.push_back(py::str(r));
        CheckPolicy policy;
        std::string error;
        if (!checkPolicy(h->capture.frame.layout, texts, policy, error)) failArgument(keywordMessage(error, {{"--policy", "policy"}}));
        return toPython(checkJson(checkFrame(h->capture.frame, policy)));
      }, "policy"_a = py::none(), doc::kCheck)
      .def("save", [](const FramePtr& h, const std::filesystem::path& dir) {
        std::string error;
        if (!writeCapture(dir.string(), h->capture.frame, h->meta, error)) fail(error);
      }, "dir"_a, doc::kSave)
      .def("__repr__", [](const FramePtr& h) {
        const FrameSnapshot& f = h->capture.frame;
        return "<gblens.Frame " + std::to_string(f.camera.width) + "x" + std::to_string(f.camera.height) + ", layout " +
               f.layout.name + ", " + h->capture.dir + ">";
      });
  m.def("open", &open, "path"_a, "layout"_a = py::none(), "params"_a = py::dict(), "camera"_a = py::none(),
        "size"_a = py::none(), doc::kOpen);
}

}  // namespace gb::python
