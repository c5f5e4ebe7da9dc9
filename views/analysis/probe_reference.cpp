// The probe's reference column (probe_reference.h): one pixel-centre ray of the reference, shaded
// with the scene's lights in double, and the G-buffer's decoded values measured against it.
#include "views/analysis/probe_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gb {

namespace {

double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = glm::dot(glm::normalize(a), glm::normalize(b));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

// The stored primitive id of the dossier's pixel, or -1 when the frame has none.
int64_t storedPrimitiveId(const FrameSnapshot& f, const PixelDossier& d) {
  const TargetImage& id = f.target(Target::PrimitiveId);
  return id.contains(d.x, d.y) ? int64_t(id.raw(d.x, d.y, 0)) : -1;
}

void compare(const FrameSnapshot& f, const PixelDossier& d, ReferencePixel& r) {
  const reference::Surface& s = r.surface;
  if (!d.geometry || !s.hit) {
    r.note = d.geometry ? "the G-buffer has a surface here, the reference's ray misses: a silhouette"
                        : s.hit ? "the reference's ray meets a surface the G-buffer does not have: a silhouette"
                                : "sky in both";
    return;
  }
  const int64_t id = storedPrimitiveId(f, d);
  if (id >= 0 && uint64_t(id) != s.primitiveId) {
    r.note = "a different triangle (primitive_id " + std::to_string(id) + ", reference " + std::to_string(s.primitiveId) +
             "): a silhouette, not compared";
    return;
  }
  r.compared = true;
  if (d.hasNormal && !d.unlit) r.normalDeg = angleDeg(d.normal, s.normal);
  if (d.hasEyeDepth) r.eyeDepthRelative = std::abs(d.eyeDepth - s.eyeDepth) / s.eyeDepth;
  const ProbePosition& used = d.positionSource == "hardware_depth" ? d.fromHardwareDepth : d.fromEyeDepth;
  if (used.valid) r.positionRelative = glm::length(used.eye - s.eye) / s.eyeDepth;
  if (s.sunVisible >= 0) r.shadowDiffers = (d.shadow >= 0.5) != (s.sunVisible == 1);
  if (d.hasHdr)
    for (int c = 0; c < 3; ++c)
      r.hdrRelative = std::max(r.hdrRelative, std::abs(d.hdr[c] - r.hdr[c]) / std::max(std::abs(r.hdr[c]), 1e-6));
  if (id < 0) r.note = "no primitive_id target: the triangle is not checked to be the same";
  if (f.options.fairies) r.note += std::string(r.note.empty() ? "" : "; ") + "fairy sprites are in the stored hdr, not in the reference";
}

std::string v3Text(const glm::dvec3& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
  return b;
}

}  // namespace

ReferencePixel referencePixel(const reference::RayScene& rays, const FrameSnapshot& f, const PixelDossier& d) {
  ReferencePixel r;
  r.surface = reference::surfaceAtPixel(rays, f.camera, d.x, d.y);
  const reference::Surface& s = r.surface;
  if (s.hit) {
    const std::vector<reference::Light> lights = reference::eyeLights(rays.scene(), f.camera, f.options.time);
    r.hdr = reference::shadeOne(reference::shadingInput(s), lights, reference::sunOf(rays.scene(), f.camera));
  }
  compare(f, d, r);
  return r;
}

nlohmann::json referenceJson(const ReferencePixel& r) {
  auto vec = [](const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  const reference::Surface& s = r.surface;
  nlohmann::json j = {{"hit", s.hit}, {"compared", r.compared}, {"note", r.note}};
  if (s.hit)
    j.update({{"primitive_id", s.primitiveId}, {"normal", vec(s.normal)},  {"eye_position", vec(s.eye)},
              {"world_position", vec(s.world)}, {"eye_depth", s.eyeDepth}, {"albedo", vec(s.albedo)},
              {"specular", s.specular},         {"sun_visible", s.sunVisible}, {"hdr", vec(r.hdr)}});
  if (r.compared)
    j["error"] = {{"normal_deg", r.normalDeg},
                  {"eye_depth_relative", r.eyeDepthRelative},
                  {"position_relative", r.positionRelative},
                  {"shadow_differs", r.shadowDiffers},
                  {"hdr_relative", r.hdrRelative}};
  return j;
}

std::string referenceText(const ReferencePixel& r) {
  const reference::Surface& s = r.surface;
  std::string o = "\nreference (ray traced, double):\n";
  if (s.hit) {
    char b[320];
    std::snprintf(b, sizeof b, "  normal %s  eye depth %.9g\n  position eye %s world %s\n", v3Text(s.normal).c_str(),
                  s.eyeDepth, v3Text(s.eye).c_str(), v3Text(s.world).c_str());
    o += b;
    std::snprintf(b, sizeof b, "  albedo %s  specular %.6g  sun %s  primitive_id %u\n  hdr %s\n", v3Text(s.albedo).c_str(),
                  s.specular, s.sunVisible < 0 ? "not evaluated" : s.sunVisible ? "reached" : "blocked", s.primitiveId,
                  v3Text(r.hdr).c_str());
    o += b;
  } else {
    o += "  no surface (sky)\n";
  }
  if (r.compared) {
    char b[256];
    std::snprintf(b, sizeof b,
                  "  G-buffer vs reference: normal %.3g deg, eye depth %.3g relative, position %.3g relative, shadow %s, "
                  "hdr %.3g relative\n",
                  r.normalDeg, r.eyeDepthRelative, r.positionRelative, r.shadowDiffers ? "DIFFERS" : "agrees", r.hdrRelative);
    o += b;
  }
  if (!r.note.empty()) o += "  " + r.note + "\n";
  return o;
}

}  // namespace gb
