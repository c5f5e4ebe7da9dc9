// Layouts back to JSON (what capture manifests embed), option parameters, and the layouts carried
// in the binary: gblens's own (assets/layouts/gblens.json, resolved per options) and the others.
#include <mutex>

#include "renderer/core/assert.h"
#include "renderer/core/assets.h"
#include "renderer/core/layout_json.h"

namespace gb {

using json = nlohmann::json;

LayoutParameters layoutParameters(const RenderOptions& o) {
  LayoutParameters p;
  for (const OptionInfo& info : optionTable()) p[info.name] = getOption(o, info.name);
  return p;
}

static json matrix(const glm::dmat4& m) {
  json a = json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(m[c][r]);
  return a;
}

static json quantityJson(const Quantity& q) {
  json j = {{"quantity", name(q.kind)}, {"name", q.name}, {"channels", q.channels}};
  switch (q.kind) {
    case QuantityKind::Normal: {
      j["encoding"] = name(q.normal);
      if (q.normal == NormalEncoding::Octahedral12) j["bits"] = 12;
      j["space"] = q.space == Space::World ? "world" : "view";
      if (!q.normalized) j["normalized"] = false;
      break;
    }
    case QuantityKind::Depth:
      j["encoding"] = name(q.depth);
      if (q.background) j["background"] = *q.background;
      if (q.ofSun) j["of"] = "sun";
      if (q.scale != 1.0) j["scale"] = q.scale;
      if (q.bias != 0.0) j["bias"] = q.bias;
      break;
    case QuantityKind::Position:
      j["space"] = q.space == Space::View ? "view" : q.space == Space::World ? "world" : "camera_relative";
      break;
    case QuantityKind::Motion:
      j["units"] = q.units == MotionUnits::Pixels ? "pixels" : q.units == MotionUnits::Ndc ? "ndc" : "uv";
      j["direction"] = q.toPrevious ? "to_previous" : "to_next";
      if (q.motionYUp) j["y"] = "up";
      if (q.jitterIncluded) j["jitter"] = "included";
      break;
    case QuantityKind::Id:
      if (!q.idNames.empty()) {
        json names = json::object();
        for (auto& [id, n] : q.idNames) names[std::to_string(id)] = n;
        j["names"] = names;
      }
      break;
    case QuantityKind::Stencil:
      if (!q.stencilBits.empty()) j["bits"] = q.stencilBits;
      break;
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Radiance:
    case QuantityKind::Display:
      if (q.color == ColorEncoding::Srgb) j["encoding"] = "srgb";
      break;
    default:
      if (q.scale != 1.0) j["scale"] = q.scale;
      if (q.bias != 0.0) j["bias"] = q.bias;
      if (!q.unit.empty()) j["unit"] = q.unit;
      break;
  }
  if (!q.historyOf.empty()) {
    j["history_of"] = q.historyOf;
    j["history_space"] = q.historyCurrent ? "current" : "previous";
  }
  if (!q.guess.is_null()) j["guess"] = q.guess;
  if (!q.check.empty()) j["check"] = q.check;
  return j;
}

json livePickJson(const TargetSource::LivePick& p) {
  json l = json::object();
  if (!p.pass.empty()) l["pass"] = p.pass;
  if (p.passIndex >= 0) l["pass"] = p.passIndex;
  if (!p.name.empty()) l["name"] = p.name;
  if (p.color >= 0) l["color"] = p.color;
  if (p.depth) l["depth"] = true;
  if (!p.format.empty()) l["format"] = p.format;
  if (p.subpass >= 0) l["subpass"] = p.subpass;
  if (p.attachment >= 0) l["attachment"] = p.attachment;
  if (p.storageSet >= 0) l["storage"] = {{"set", p.storageSet}, {"binding", p.storageBinding}};
  return l;
}

static json sourceJson(const TargetSource& s) {
  json j = json::object();
  if (s.kind == TargetSource::Kind::RenderDoc) return {{"renderdoc", s.resource}};
  if (s.kind == TargetSource::Kind::Live) return {{"live", livePickJson(s.live)}};
  if (!s.path.empty()) j["file"] = s.path;
  if (s.kind == TargetSource::Kind::Raw) j["raw"] = true;
  if (s.offset) j["offset"] = s.offset;
  if (s.rowStride) j["row_stride"] = s.rowStride;
  if (!s.part.empty()) j["part"] = s.part;
  if (!s.channels.empty()) j["channels"] = s.channels;
  return j;
}

json layoutCameraJson(const LayoutCamera& c) {
  static const char* conventions[] = {"vulkan", "d3d", "gl"};
  json j = {{"matrix_order", "column_major"},
            {"convention", conventions[size_t(c.convention)]},
            {"view_handedness", c.leftHanded ? "left" : "right"},
            {"up", name(c.up)},
            {"image_origin", c.bottomOrigin ? "bottom" : "top"}};
  if (c.statedWorldLeftHanded) j["world_handedness"] = *c.statedWorldLeftHanded ? "left" : "right";
  if (c.statedOrthographic) j["projection"] = *c.statedOrthographic ? "orthographic" : "perspective";
  if (!c.sidecar.empty()) j["sidecar"] = c.sidecar;
  if (c.jitter) j["jitter"] = {c.jitter->x, c.jitter->y};
  if (c.time) j["time"] = *c.time;
  if (!c.from.empty()) j["from"] = c.from;
  if (!c.guess.is_null()) j["guess"] = c.guess;
  if (c.width) j["size"] = {c.width, c.height};
  if (c.renderdoc) {
    j["matrix_order"] = c.renderdoc->rowMajor ? "row_major" : "column_major";
    if (c.renderdoc->combined)
      j["renderdoc"] = {{"buffer", c.renderdoc->buffer}, {"clip_from_world", {{"offset", c.renderdoc->clipOffset}}}};
    else
      j["renderdoc"] = {{"buffer", c.renderdoc->buffer},
                        {c.renderdoc->worldFromView ? "world_from_view" : "view_from_world", {{"offset", c.renderdoc->viewOffset}}},
                        {"clip_from_view", {{"offset", c.renderdoc->clipOffset}}}};
  }
  if (c.live) {
    const LayoutCamera::LiveBinding& b = *c.live;
    json live = {{"pass", b.passIndex >= 0 ? json(b.passIndex) : json(b.pass)}};
    if (b.pushConstants)
      live["push_constants"] = true;
    else
      live["set"] = b.set, live["binding"] = b.binding, live["index"] = b.index;
    j["live"] = live;
    j["matrix_order"] = b.matrices.rowMajor ? "row_major" : "column_major";
    if (b.matrices.combined) {
      j["clip_from_world"] = {{"offset", b.matrices.clipOffset}};
    } else {
      j[b.matrices.worldFromView ? "world_from_view" : "view_from_world"] = {{"offset", b.matrices.viewOffset}};
      j["clip_from_view"] = {{"offset", b.matrices.clipOffset}};
    }
  }
  if (c.sidecar.empty() && !c.renderdoc && !c.live) {
    j["view_from_world"] = matrix(c.viewFromWorld);
    j["clip_from_view"] = matrix(c.clipFromView);
    // What the matrices say, for people reading a manifest (parseLayoutCamera checks them again).
    j["world_handedness"] = c.worldLeftHanded ? "left" : "right";
    j["projection"] = c.clipFromView[2][3] == 0.0 ? "orthographic" : "perspective";
  }
  return j;
}

static json lightsJson(const LayoutLights& l) {
  json points = json::array();
  for (const PointLightDesc& p : l.points)
    points.push_back({{"position", {p.center.x, p.center.y, p.center.z}},
                      {"radius", p.radius},
                      {"color", {p.color.r, p.color.g, p.color.b}},
                      {"intensity", p.intensity}});
  json j = {{"model", l.model}, {"points", points}, {"ambient", {l.ambient.r, l.ambient.g, l.ambient.b}}};
  if (l.sun.enabled)
    j["sun"] = {{"direction", {l.sun.toSun.x, l.sun.toSun.y, l.sun.toSun.z}},
                {"color", {l.sun.color.r, l.sun.color.g, l.sun.color.b}}};
  return j;
}

json layoutJson(const Layout& l) {
  json targets = json::array();
  for (uint32_t t = 0; t < l.targets.size(); ++t) {
    const LayoutTarget& lt = l.targets[t];
    json j = {{"name", lt.name}, {"format", lt.format.name}, {"channels", lt.channels}};
    if (!lt.formatChoices.empty()) {
      j["format"] = json::array();
      for (const StorageFormat& f : lt.formatChoices) j["format"].push_back(f.name);
    }
    if (!lt.guess.is_null()) j["guess"] = lt.guess;
    if (lt.width) j["size"] = {lt.width, lt.height};
    if (lt.source.kind != TargetSource::Kind::None) j["source"] = sourceJson(lt.source);
    json qs = json::array();
    for (const Quantity* q : l.quantitiesOf(t)) qs.push_back(quantityJson(*q));
    j["quantities"] = qs;
    targets.push_back(j);
  }
  json j = {{"format", "gblens-layout"}, {"version", 1}, {"name", l.name}, {"targets", targets}};
  if (l.width) j["size"] = {l.width, l.height};
  if (l.camera.present) j["camera"] = layoutCameraJson(l.camera);
  if (l.lights.present) j["lights"] = lightsJson(l.lights);
  if (!l.check.empty()) j["check"] = l.check;
  return j;
}

const Layout& nativeLayout(const RenderOptions& o) {
  static std::mutex mutex;
  static std::map<LayoutParameters, Layout> cache;
  const LayoutParameters params = layoutParameters(o);
  std::lock_guard lock(mutex);
  auto it = cache.find(params);
  if (it != cache.end()) return it->second;
  const std::string* text = assetText("layouts/gblens.json");
  GB_ASSERT(text);
  json j = json::parse(*text);
  std::string error;
  Layout l;
  if (!resolveLayoutParameters(j, params, "assets/layouts/gblens.json", error) ||
      !parseLayout(j, "assets/layouts/gblens.json", l, error)) {
    std::fprintf(stderr, "gblens: %s\n", error.c_str());
    GB_ASSERT(!"the built-in layout of gblens's own frame does not load");
  }
  return cache.emplace(params, std::move(l)).first->second;
}

bool gblensLayout(const Layout& layout) { return layout.name == nativeLayout(RenderOptions{}).name; }

}  // namespace gb
