// gblens.compare and its Result: compare() of two frames (views/analysis/compare.h) with the CLI's
// settings as keyword arguments; the figures as Python values, the per-pixel errors as numpy arrays,
// the report page, JUnit and the images.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "app/python/docstrings.h"
#include "app/python/python.h"
#include "views/analysis/compare.h"
#include "views/report/report.h"

namespace gb::python {

namespace {

struct Result {
  FramePtr a, b;
  CompareReport report;
};
using ResultPtr = std::shared_ptr<Result>;

// A threshold argument: a number (every group) or {key: number} ("" : every group), as the CLI's
// repeated VALUE / KEY=VALUE.
std::vector<std::string> settingTexts(const py::object& v) {
  std::vector<std::string> out;
  if (v.is_none()) return out;
  if (py::isinstance<py::dict>(v)) {
    for (auto [key, value] : v.cast<py::dict>()) {
      const std::string k = py::str(key), number = py::str(value);
      out.push_back(k.empty() ? number : k + "=" + number);
    }
    return out;
  }
  out.push_back(py::str(v));
  return out;
}

// compare's flags and the keyword arguments that stand for them.
const std::vector<std::pair<std::string, std::string>> kFlags = {
    {"--failpercent", "failpercent"}, {"--fail-flip", "fail_flip"}, {"--fail", "fail"}, {"--hardfail", "hardfail"},
    {"--warnpercent", "warnpercent"}, {"--warn-flip", "warn_flip"}, {"--warn", "warn"}, {"--mask", "mask"},
    {"--exclude", "exclude"}, {"--flip-ppd", "flip_ppd"}};

ResultPtr compareFrames(const py::object& a, const py::object& b, const py::object& fail_, const py::object& failPercent,
                        const py::object& hardFail, const py::object& warn, const py::object& warnPercent,
                        const py::object& maskSpec, const std::vector<std::string>& exclude, bool flip,
                        const py::object& failFlip, const py::object& warnFlip, const py::object& flipPpd) {
  auto r = std::make_shared<Result>();
  r->a = frameOf(a);
  r->b = frameOf(b);
  CompareSettings s;
  std::string error;
  for (auto& [param, value] : {std::pair{"fail", &fail_}, {"failpercent", &failPercent}, {"hardfail", &hardFail},
                               {"warn", &warn}, {"warnpercent", &warnPercent}})
    for (const std::string& text : settingTexts(*value))
      if (!s.thresholds.add(param, text, error)) failArgument(keywordMessage(error, kFlags));
  for (auto& [flag, value] : {std::pair{"--fail-flip", &failFlip}, {"--warn-flip", &warnFlip}})
    for (const std::string& text : settingTexts(*value))
      if (!s.flip.add(flag, text, error)) failArgument(keywordMessage(error, kFlags));
  if (!flipPpd.is_none()) {
    s.flip.ppd = flipPpd.cast<double>();
    if (!(s.flip.ppd > 0.0) || !std::isfinite(s.flip.ppd)) failArgument("flip_ppd=" + std::string(py::str(flipPpd)) + ": expected a positive number");
  }
  s.flipOn = flip;
  s.mask = maskSpec.is_none() ? "" : std::string(py::str(maskSpec));
  s.exclude = exclude;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = compare(r->a->capture, r->b->capture, s, r->report, error);
  }
  if (!ok) fail(keywordMessage(error, kFlags));
  return r;
}

py::array errors(const ResultPtr& r, const std::string& key) {
  for (const GroupResult& g : r->report.groups)
    if (g.group.key == key) return view(py::dtype("float32"), {py::ssize_t(g.height), py::ssize_t(g.width)}, g.errors.data(), r);
  for (const FlipResult& f : r->report.flips)
    if ("flip." + f.target == key) return view(py::dtype("float32"), {py::ssize_t(f.height), py::ssize_t(f.width)}, f.errors.data(), r);
  std::string keys;
  for (const GroupResult& g : r->report.groups) keys += " " + g.group.key;
  for (const FlipResult& f : r->report.flips) keys += " flip." + f.target;
  throw QuantityError("key=\"" + key + "\": no compared group of that key (keys:" + keys + ")");
}

}  // namespace

void bindCompare(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<Result, ResultPtr>(m, "Result", doc::kResult)
      .def_property_readonly("exit_code", [](const ResultPtr& r) { return r->report.exitCode; }, doc::kExitCode)
      .def_property_readonly("passed", [](const ResultPtr& r) { return r->report.exitCode <= kCompareWarn; }, doc::kPassed)
      .def_property_readonly("result", [](const ResultPtr& r) { return toPython(r->report.json()["result"]); }, doc::kResultName)
      .def_property_readonly("json", [](const ResultPtr& r) { return toPython(r->report.json()); }, doc::kJson)
      .def_property_readonly("groups", [](const ResultPtr& r) {
        py::dict out;
        const nlohmann::json j = r->report.json();
        for (const nlohmann::json& g : j["groups"]) out[py::str(g["key"].get<std::string>())] = toPython(g);
        return out;
      }, doc::kGroups)
      .def_property_readonly("flip", [](const ResultPtr& r) { return toPython(r->report.json()["flip"]); }, doc::kFlip)
      .def_property_readonly("text", [](const ResultPtr& r) { return r->report.text(); }, doc::kText)
      .def_property_readonly("mask", [](const ResultPtr& r) -> py::object {
        const CompareMask& m = r->report.mask;
        if (m.empty()) return py::none();
        return view(py::dtype("uint8"), {py::ssize_t(m.height), py::ssize_t(m.width)}, m.bits.data(), r);
      }, doc::kResultMask)
      .def("errors", &errors, "key"_a, doc::kErrors)
      .def("report", [](const ResultPtr& r, const std::filesystem::path& dir) {
        std::string error;
        bool ok;
        {
          py::gil_scoped_release release;
          ok = writeReport(r->a->capture, r->b->capture, r->report, dir.string(), error);
        }
        if (!ok) fail(error);
      }, "dir"_a, doc::kReport)
      .def("junit", [](const ResultPtr& r, const std::filesystem::path& file, const std::string& name) {
        std::string error;
        if (!writeJunit({{name, &r->report}}, file.string(), error)) fail(error);
      }, "file"_a, "name"_a = "", doc::kJunit)
      .def("write_images", [](const ResultPtr& r, const std::filesystem::path& dir) {
        std::string error;
        if (!writeCompareImages(r->report, dir.string(), error)) fail(error);
      }, "dir"_a, doc::kWriteImages)
      .def("__repr__", [](const ResultPtr& r) {
        return "<gblens.Result " + r->report.json()["result"].get<std::string>() + " (exit " + std::to_string(r->report.exitCode) + ")>";
      });
  m.def("compare", &compareFrames, "a"_a, "b"_a, py::kw_only(), "fail"_a = py::none(), "failpercent"_a = py::none(),
        "hardfail"_a = py::none(), "warn"_a = py::none(), "warnpercent"_a = py::none(), "mask"_a = py::none(),
        "exclude"_a = std::vector<std::string>{}, "flip"_a = true, "fail_flip"_a = py::none(), "warn_flip"_a = py::none(),
        "flip_ppd"_a = py::none(), doc::kCompare);
}

}  // namespace gb::python
