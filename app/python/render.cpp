// gblens.render and gblens.error: the headless renderer (renderer/session.h) from Python, options by
// their option-table names (the CLI's flags with _ for -), and one frame's error against the reference.
#include <pybind11/stl.h>

#include <functional>
#include <optional>

#include "app/python/docstrings.h"
#include "app/python/python.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/scene/builtin.h"
#include "renderer/scene/scene.h"
#include "renderer/frame/session.h"
#include "views/analysis/accuracy.h"
#include "views/capture/report.h"

namespace gb::python {

namespace {

// Keyword options -> RenderOptions, as the CLI parses its flags (True/False: on/off, (w, h): WxH).
RenderOptions optionsFrom(const py::kwargs& kwargs) {
  RenderOptions o;
  std::string error;
  for (auto [key, value] : kwargs) {
    const std::string name = py::str(key);
    std::string text = py::str(value);
    if (py::isinstance<py::bool_>(value)) text = value.cast<bool>() ? "on" : "off";
    else if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {  // size=(w, h)
      std::vector<std::string> v;
      for (const py::handle& item : value) v.push_back(py::str(item));
      text = v.size() == 2 ? v[0] + "x" + v[1] : text;
    }
    if (!findOption(name)) failArgument(name + "=: no option of that name (gblens --help lists them; - as _)");
    if (!setOption(o, name, text, error)) failArgument(name + "=" + text + ": " + error);
  }
  return o;
}

Scene sceneFrom(const std::string& source, const RenderOptions& o) {
  Scene scene;
  try {
    scene = loadScene(source, o.lights);
  } catch (const SceneError& e) {
    fail(e.message);
  }
  for (const std::string& w : scene.warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
  if (size_t(o.camera) >= scene.cameras.size())
    failArgument("camera=" + std::to_string(o.camera) + ": " + source + " has " + std::to_string(scene.cameras.size()) + " camera(s)");
  return scene;
}

// The targets named (None: every available one), parsed before the device starts.
std::optional<std::vector<Target>> targetsNamed(const py::object& names) {
  if (names.is_none()) return std::nullopt;
  std::vector<Target> out;
  for (const py::handle& n : names) {
    Target t;
    const std::string name = py::str(n);
    if (!parseTarget(name, t)) failArgument("targets: unknown target \"" + name + "\"");
    out.push_back(t);
  }
  return out;
}

// What `gblens capture` reads back: every available target, or the ones named, each computed
// under the options as the device runs them (`ran`: --gbuffer auto resolved).
std::vector<Target> targetsFrom(const std::optional<std::vector<Target>>& named, const RenderOptions& ran,
                                const Scene& scene) {
  if (!named) return availableTargets(ran, scene.sun.enabled);
  for (Target t : *named)
    if (Absent why = targetAbsence(t, ran, scene.sun.enabled); why != Absent::No)
      failArgument(std::string("targets: ") + targetName(t) + ": " + absentText(why));
  return *named;
}

// A headless session on `scene` for `work` (without the GIL); an output too large for the device and
// any validation message (a gblens bug) raise.
void withSession(const Scene& scene, const std::string& device, const RenderOptions& o,
                 const std::function<void(HeadlessSession&)>& work) {
  std::string tooLarge;
  int validation = 0;
  {
    py::gil_scoped_release release;
    HeadlessSession session(scene, {device, false, true});
    tooLarge = session.tooLarge(o);
    if (tooLarge.empty()) {
      work(session);
      validation = session.reportValidation();
    }
  }
  if (!tooLarge.empty()) fail(tooLarge);
  if (validation) fail(std::to_string(validation) + " Vulkan validation message(s) while rendering (a gblens bug)");
}

FramePtr render(const std::string& source, const py::object& targetNames, const std::string& device, bool coverage,
                const py::kwargs& kwargs) {
  RenderOptions o = optionsFrom(kwargs);
  o.coverage = coverage;
  const Scene scene = sceneFrom(source, o);
  const std::optional<std::vector<Target>> named = targetsNamed(targetNames);
  auto h = std::make_shared<FrameHandle>();
  withSession(scene, device, o, [&](HeadlessSession& session) {
    const std::vector<Target> wanted = targetsFrom(named, session.frameOptions(o), scene);
    h->meta.stats = session.render(o, captureRequest(wanted, o));
    h->capture.frame = session.snapshot(wanted);
    for (Absent& a : h->capture.frame.absences)
      if (a == Absent::NotReadBack) a = Absent::NotRequested;
    h->meta.device = session.deviceName();
    h->meta.driver = session.driverName();
  });
  h->meta.scene = source;
  h->meta.sceneSha256 = sceneContentSha256(scene);
  h->meta.commandLine = "python: gblens.render(" + source + ")";
  h->capture.dir = "render " + source;
  h->capture.manifest = {{"scene", {{"source", source}, {"content_sha256", h->meta.sceneSha256}}},
                         {"device", h->meta.device}, {"driver", h->meta.driver},
                         {"options", optionsJson(h->capture.frame.options)}};
  return h;
}

py::object error(const std::string& source, const std::string& device, double band, const py::kwargs& kwargs) {
  const RenderOptions o = optionsFrom(kwargs);
  const Scene scene = sceneFrom(source, o);
  nlohmann::json j;
  withSession(scene, device, o, [&](HeadlessSession& session) {
    ReferenceCache cache(scene);
    auto frames = [&](const RenderOptions& ro, const std::vector<Target>& t) { return session.renderSnapshot(ro, t); };
    const FrameError e = measureFrame(frames, o, cache, band).error;
    j = {{"scene", scene.source}, {"device", session.deviceName()}, {"options", optionsJson(o)},
         {"shadow_band_texels", band}, {"error", errorJson(e)}};
  });
  return toPython(j);
}

}  // namespace

void bindRender(py::module_& m) {
  using namespace pybind11::literals;
  m.def("render", &render, "scene"_a = "builtin:temple", py::kw_only(), "targets"_a = py::none(), "device"_a = "",
        "coverage"_a = true, doc::kRender);
  m.def("error", &error, "scene"_a = "builtin:temple", py::kw_only(), "device"_a = "", "band"_a = kShadowBandTexels, doc::kError);
}

}  // namespace gb::python
