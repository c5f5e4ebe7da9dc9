// The probe's layout-driven part: every quantity of the frame's layout decoded at the pixel, and
// every position the layout allows (from each camera depth, and stored), with the difference to
// the stored one. Works the same for gblens's frames and imported G-buffers.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderer/core/decode.h"
#include "views/analysis/probe.h"
#include "views/analysis/probe_internal.h"
#include "views/analysis/visualize.h"

namespace gb {

namespace {

std::string spaceName(Space s) {
  switch (s) {
    case Space::View: return "view space";
    case Space::World: return "world space";
    case Space::CameraRelative: return "camera-relative";
  }
  return "?";
}

std::string encodingText(const Quantity& q) {
  switch (q.kind) {
    case QuantityKind::Normal:
      return std::string(name(q.normal)) + " (" + spaceName(q.space) + (q.normalized ? "" : ", not normalised") + ")";
    case QuantityKind::Depth: return q.ofSun ? "sun depth" : name(q.depth);
    case QuantityKind::Position: return "stored (" + spaceName(q.space) + ")";
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Radiance:
    case QuantityKind::Display: return q.color == ColorEncoding::Srgb ? "srgb" : "linear";
    default:
      if (q.scale != 1.0 || q.bias != 0.0) {
        char b[96];
        std::snprintf(b, sizeof(b), "x %.9g + %.9g", q.scale, q.bias);
        return b;
      }
      return "";
  }
}

// An integer quantity's note: the id's name, or the stencil bits that are set.
std::string integerNote(const Quantity& q, uint32_t v) {
  if (q.kind == QuantityKind::Id) {
    auto it = q.idNames.find(v);
    return it == q.idNames.end() ? "" : it->second;
  }
  std::string bits;
  if (q.kind == QuantityKind::Stencil)
    for (auto& [bitName, mask] : q.stencilBits)
      if (v & mask) bits += (bits.empty() ? "" : ", ") + bitName;
  return bits;
}

// The quantity as its view decodes it (values in the layout's units and space), with notes.
void decodeOne(const FrameSnapshot& f, const ViewDef& v, uint32_t x, uint32_t y, ProbeQuantity& p) {
  const Quantity& q = f.layout.quantities[size_t(v.quantity)];
  std::optional<std::array<double, 4>> value = viewValue(f, v, x, y);
  if (!value) {
    p.note = v.visual == Visual::Depth ? "no surface (background)" : "no surface";
    return;
  }
  const uint32_t n = v.visual == Visual::Color ? uint32_t(std::min<size_t>(q.channels.size(), 4)) : v.components;
  p.values.assign(value->begin(), value->begin() + n);
  if (v.visual == Visual::Normal && (*value)[3] > 0.0) p.note = "stored length error " + std::to_string(std::abs((*value)[3] - 1.0));
  if (v.visual == Visual::Depth && !q.ofSun) p.eyeDepth = decodeEyeDepth(f, q, x, y);
  if (v.integer) p.note = integerNote(q, uint32_t((*value)[0]));
}

}  // namespace

void decodeQuantities(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  for (const ViewDef& v : layoutViews(f.layout)) {
    const Quantity& q = f.layout.quantities[size_t(v.quantity)];
    if (q.kind == QuantityKind::Depth && q.ofSun) continue;  // the shadow-map lookup shows it
    ProbeQuantity p;
    p.name = q.name;
    p.kind = name(q.kind);
    p.target = f.layout.targets[q.target].name;
    p.encoding = encodingText(q);
    p.space = !v.space.empty() ? v.space : !v.unit.empty() ? v.unit : p.kind;
    p.present = holds(f, q, x, y);
    if (p.present) decodeOne(f, v, x, y, p);
    d.quantities.push_back(p);
  }
}

void reconstructAll(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  const Quantity* stored = f.layout.find(QuantityKind::Position);
  std::optional<glm::dvec3> storedEye;
  if (stored && holds(f, *stored, x, y)) storedEye = decodePosition(f, *stored, x, y);
  const std::string worldSpace = "world (layout: " + upAxisText(f.layout.camera) + "-up)";
  for (const Quantity& q : f.layout.quantities) {
    const bool depth = q.kind == QuantityKind::Depth && !q.ofSun;
    if (!depth && q.kind != QuantityKind::Position) continue;
    ProbeReconstruction r;
    r.quantity = q.name;
    r.method = q.kind == QuantityKind::Position ? "stored"
               : q.depth == DepthEncoding::Eye  ? "eye depth"
               : q.depth == DepthEncoding::Hardware ? "hardware depth" : "radial distance";
    r.worldSpace = worldSpace;
    std::optional<glm::dvec3> eye;
    if (holds(f, q, x, y)) eye = decodePosition(f, q, x, y);
    if (eye) {
      r.valid = true;
      r.eye = *eye;
      r.world = spaceFromEye(f, Space::World, *eye, true);
      if (storedEye && &q != stored) {
        r.hasStored = true;
        r.toStored = glm::length(*eye - *storedEye);
        // In ulps of the stored format, at the largest coordinate it stores (in its own space).
        const glm::dvec3 s = spaceFromEye(f, stored->space, *storedEye, true);
        const LayoutTarget& st = f.layout.targets[stored->target];
        r.toStoredUlps = r.toStored / storageUlp(st.format.type, st.format.encoding, std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)}));
        r.ulpOf = name(st.format.type);
      }
    }
    d.reconstructions.push_back(r);
  }
}

}  // namespace gb
