// The probe's layout-driven part: every quantity of the frame's layout decoded at the pixel, and
// every position the layout allows (from each camera depth, and stored), with the difference to
// the stored one. Works the same for gblens's frames and imported G-buffers.
#include <cmath>
#include <cstdio>

#include "renderer/core/decode.h"
#include "views/analysis/probe.h"
#include "views/analysis/probe_internal.h"

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

void decodeOne(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y, ProbeQuantity& p) {
  switch (q.kind) {
    case QuantityKind::Normal: {
      NormalSample n = decodeNormal(f, q, x, y);
      p.values = {n.unit.x, n.unit.y, n.unit.z};
      const double length = glm::length(n.stored);
      if (length > 0.0) p.note = "stored length error " + std::to_string(std::abs(length - 1.0));
      return;
    }
    case QuantityKind::Depth: {
      std::optional<double> z = decodeEyeDepth(f, q, x, y);
      if (z) p.values = {*z};
      else p.note = "no surface (background)";
      return;
    }
    case QuantityKind::Position: {
      std::optional<glm::dvec3> e = decodePosition(f, q, x, y);
      if (e) p.values = {e->x, e->y, e->z};
      else p.note = "no surface";
      return;
    }
    case QuantityKind::Motion: {
      glm::dvec2 m = decodeMotion(f, q, x, y);
      p.values = {m.x, m.y};
      return;
    }
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: {
      const uint32_t v = decodeInteger(f, q, x, y);
      p.values = {double(v)};
      p.note = integerNote(q, v);
      return;
    }
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Radiance:
    case QuantityKind::Display: {
      glm::dvec4 c = decodeColor(f, q, x, y);
      for (size_t k = 0; k < q.channels.size() && k < 4; ++k) p.values.push_back(c[int(k)]);
      return;
    }
    default: {
      std::array<double, 4> v = storedValues(f, q, x, y);
      for (size_t k = 0; k < q.channels.size() && k < 4; ++k) p.values.push_back(v[k] * q.scale + q.bias);
    }
  }
}

double floatUlp(double v) {
  float fv = std::abs(float(v));
  return double(std::nextafter(fv, INFINITY)) - double(fv);
}

}  // namespace

void decodeQuantities(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  for (const Quantity& q : f.layout.quantities) {
    if (q.kind == QuantityKind::Depth && q.ofSun) continue;  // the shadow-map lookup shows it
    ProbeQuantity p;
    p.name = q.name;
    p.kind = name(q.kind);
    p.target = f.layout.targets[q.target].name;
    p.encoding = encodingText(q);
    p.present = holds(f, q, x, y);
    if (p.present) decodeOne(f, q, x, y, p);
    d.quantities.push_back(p);
  }
}

void reconstructAll(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  const Quantity* stored = f.layout.find(QuantityKind::Position);
  std::optional<glm::dvec3> storedEye;
  if (stored && holds(f, *stored, x, y)) storedEye = decodePosition(f, *stored, x, y);
  for (const Quantity& q : f.layout.quantities) {
    const bool depth = q.kind == QuantityKind::Depth && !q.ofSun;
    if (!depth && q.kind != QuantityKind::Position) continue;
    ProbeReconstruction r;
    r.quantity = q.name;
    r.method = q.kind == QuantityKind::Position ? "stored"
               : q.depth == DepthEncoding::Eye  ? "eye depth"
               : q.depth == DepthEncoding::Hardware ? "hardware depth" : "radial distance";
    std::optional<glm::dvec3> eye;
    if (holds(f, q, x, y)) eye = decodePosition(f, q, x, y);
    if (eye) {
      r.valid = true;
      r.eye = *eye;
      r.world = glm::dvec3(f.camera.worldFromEye * glm::dvec4(*eye, 1.0));
      if (storedEye && &q != stored) {
        r.hasStored = true;
        r.toStored = glm::length(*eye - *storedEye);
        const glm::dvec3 w = glm::dvec3(f.camera.worldFromEye * glm::dvec4(*storedEye, 1.0));
        const glm::dvec3 s = stored->space == Space::View ? *storedEye : w;
        r.toStoredUlps = r.toStored / floatUlp(std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)}));
      }
    }
    d.reconstructions.push_back(r);
  }
}

}  // namespace gb
