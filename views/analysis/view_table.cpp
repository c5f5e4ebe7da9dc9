// The views of a layout (see view_table.h): each quantity kind's visualisation and defaults.
#include "views/analysis/view_table.h"

#include <algorithm>

namespace gb {

using namespace gpu;

const char* name(Visual v) {
  static const char* const names[] = {"color", "normal", "depth", "position", "scalar", "vector", "id", "stencil", "motion", "count"};
  return names[int(v)];
}

namespace {

std::string spaceText(const Layout& l, Space s) {
  switch (s) {
    case Space::View: return l.camera.leftHanded ? "view (left-handed, looks down +Z)" : "view";
    case Space::World: return "world (layout: " + upAxisText(l.camera) + "-up)";
    case Space::CameraRelative: return "camera-relative world (layout: " + upAxisText(l.camera) + "-up)";
  }
  return "";
}

std::string depthText(const Quantity& q) {
  if (q.ofSun) return "light depth (the sun's shadow map)";
  switch (q.depth) {
    case DepthEncoding::Hardware: return "hardware depth";
    case DepthEncoding::Eye: return "eye depth";
    case DepthEncoding::Radial: return "radial distance";
  }
  return "";
}

// The visualisation and defaults of one quantity.
ViewDef viewOf(const Layout& l, const Quantity& q, int index) {
  ViewDef d;
  d.name = q.name;
  d.quantity = index;
  d.kind = q.kind;
  d.target = q.target;
  const uint32_t n = uint32_t(q.channels.size());
  auto names = [&](std::initializer_list<const char*> c) {
    d.componentNames.clear();
    for (const char* s : c)
      if (d.componentNames.size() < d.components) d.componentNames.push_back(s);
  };
  switch (q.kind) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Radiance:
    case QuantityKind::Display:
      d.visual = Visual::Color;
      d.components = std::min(n, 4u);
      d.hdr = q.kind == QuantityKind::Radiance || q.kind == QuantityKind::Emission;
      d.space = q.color == ColorEncoding::Srgb ? "linear (stored sRGB-encoded)" : "linear";
      names({"R", "G", "B", "A"});
      break;
    case QuantityKind::Specular:
    case QuantityKind::Roughness:
    case QuantityKind::Metallic:
    case QuantityKind::Occlusion:
    case QuantityKind::Shadow:
      // Their range is [0, 1], but real values often sit in a corner of it (a specular of 0.04): the
      // data's range by default, labelled as such; [0, 1] is one click away.
      d.visual = Visual::Scalar;
      d.channels = 0x1;
      d.autoRange = true;
      break;
    case QuantityKind::Scalar:
      d.visual = Visual::Scalar;
      d.channels = 0x1;
      d.autoRange = true;
      d.negativeSuspicious = false;
      d.unit = q.unit;
      break;
    case QuantityKind::Vector:
      d.visual = Visual::Vector;
      d.components = std::min(n, 4u);
      d.channels = d.components >= 3 ? 0x7 : (1u << d.components) - 1;
      d.autoRange = true;
      d.negativeSuspicious = false;
      d.unit = q.unit;
      names({"X", "Y", "Z", "W"});
      break;
    case QuantityKind::Normal:
      d.visual = Visual::Normal;
      d.components = 3;
      d.black = -1.0f;
      d.negativeSuspicious = false;
      d.surfaceOnly = true;
      d.space = spaceText(l, q.space);
      names({"X", "Y", "Z"});
      break;
    case QuantityKind::Depth:
      d.visual = Visual::Depth;
      d.channels = 0x1;
      d.autoRange = true;
      d.sun = q.ofSun;
      d.space = d.unit = depthText(q);
      d.background = q.background;
      d.predicate = q.background                       ? kRangeNotValue
                    : q.ofSun                            ? kRangeBelowOne
                    : q.depth == DepthEncoding::Hardware ? kRangeNotFar
                                                         : kRangePositive;
      break;
    case QuantityKind::Position:
      d.visual = Visual::Position;
      d.components = 3;
      d.autoRange = true;
      d.negativeSuspicious = false;
      d.surfaceOnly = true;
      d.space = spaceText(l, q.space);
      names({"X", "Y", "Z"});
      break;
    case QuantityKind::Motion:
      d.visual = Visual::Motion;
      d.components = 2;
      d.channels = 0x3;
      d.autoRange = true;
      d.negativeSuspicious = false;
      d.unit = q.units == MotionUnits::Pixels ? "pixels" : q.units == MotionUnits::Ndc ? "ndc" : "uv";
      d.space = q.toPrevious ? "toward the previous frame" : "toward the next frame";
      names({"X", "Y"});
      break;
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count:
      d.visual = q.kind == QuantityKind::Id ? Visual::Id : q.kind == QuantityKind::Stencil ? Visual::Stencil : Visual::Count;
      d.channels = 0x1;
      d.integer = true;
      d.negativeSuspicious = false;
      d.autoRange = q.kind == QuantityKind::Count;
      d.black = 0.0f;
      d.white = q.kind == QuantityKind::Stencil ? 255.0f : 1.0f;
      break;
  }
  if (d.componentNames.empty()) d.componentNames = {q.name};
  return d;
}

// The view shown first: display colour, else radiance, else the first colour quantity, else the first.
size_t firstView(const std::vector<ViewDef>& views) {
  for (QuantityKind k : {QuantityKind::Display, QuantityKind::Radiance})
    for (size_t i = 0; i < views.size(); ++i)
      if (views[i].kind == k) return i;
  for (size_t i = 0; i < views.size(); ++i)
    if (views[i].visual == Visual::Color) return i;
  return 0;
}

}  // namespace

std::vector<ViewDef> layoutViews(const Layout& l) {
  std::vector<ViewDef> views;
  for (size_t i = 0; i < l.quantities.size(); ++i) views.push_back(viewOf(l, l.quantities[i], int(i)));
  if (views.empty()) return views;
  std::rotate(views.begin(), views.begin() + long(firstView(views)), views.begin() + long(firstView(views)) + 1);
  for (size_t i = 0; i < views.size() && i < 9; ++i) views[i].key = i == 0 ? "0" : std::to_string(i + 1);
  return views;
}

int findView(const std::vector<ViewDef>& views, const std::string& name) {
  const std::string key = nameKey(name);
  for (size_t i = 0; i < views.size(); ++i)
    if (nameKey(views[i].name) == key) return int(i);
  return -1;
}

std::string viewNameList(const std::vector<ViewDef>& views) {
  std::string out;
  for (const ViewDef& v : views) out += (out.empty() ? "" : ", ") + v.name;
  return out;
}

std::string viewUnit(const ViewDef& def, const std::string& method) {
  if (def.kind == QuantityKind::Count && def.name == "CoverageMasked") {
    if (method == "deferred") return "point-light fragment shader runs";
    if (method == "tiled") return "lights in the pixel's 16x16 tile list";
    if (method == "clustered") return "lights in the pixel's cluster list";
    if (method == "forward") return "lights looped over per fragment";
  }
  if (def.kind == QuantityKind::Count && def.name == "CoverageFull") return "light volumes over the pixel (no depth or stencil test)";
  return def.unit;
}

std::string componentLabel(const ViewDef& def, int c) {
  if (c < 0 || size_t(c) >= def.componentNames.size()) return "";
  return def.components == 1 ? def.name : def.name + "." + def.componentNames[size_t(c)];
}

}  // namespace gb
