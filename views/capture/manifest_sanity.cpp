// What a manifest says checked against itself and its images, after every field's type and range
// (manifest_check.cpp): the frame's size is its targets', the camera's matrices are each other's
// inverses and a projection gblens knows, and lights, sun and sky hold values a 32-bit float renderer
// can use. A manifest edited by hand (or by an attacker) is refused here, by every reader and the writer.
#include <algorithm>
#include <cmath>

#include "renderer/core/json_read.h"
#include "renderer/core/layout_json.h"
#include "renderer/core/targets.h"
#include "views/capture/manifest_check.h"

namespace gb {

namespace {

// The largest magnitude of a light's, the sun's or the sky's number: what the renderer's 32-bit
// floats hold (a light at -1e308 would be uploaded as -inf).
constexpr double kMaxMagnitude = 3.4028234663852886e38;
// How far a product of two matrices may lie from what it should be, relative to the products of
// the magnitudes that made each element: float-rounded matrices (a camera read from a uniform
// buffer) stay within 1e-6, an edited entry lies orders of magnitude beyond.
constexpr double kMatrixTolerance = 1e-5;

// Whether a * b equals `expected` elementwise within kMatrixTolerance of |a| * |b|.
bool productIs(const glm::dmat4& a, const glm::dmat4& b, const glm::dmat4& expected) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      double value = 0.0, scale = 0.0;
      for (int k = 0; k < 4; ++k) {
        value += a[k][r] * b[c][k];
        scale += std::abs(a[k][r] * b[c][k]);
      }
      if (!(std::abs(value - expected[c][r]) <= kMatrixTolerance * scale + 1e-12)) return false;
    }
  return true;
}

void checkCamera(const JsonIn& m, const Camera& c) {
  const JsonIn cam = m.has("camera") ? m["camera"] : m["view"];
  if (!(c.yfov >= 0.0 && c.yfov < M_PI)) cam["yfov"].fail("expected 0 (orthographic) up to pi radians");
  if (!(c.aspect > 0.0)) cam["aspect"].fail("expected a positive aspect");
  if (!(c.znear < c.zfar)) cam["zfar"].fail("not beyond znear");
  if (c.yfov > 0.0 && !(c.znear > 0.0)) cam["znear"].fail("expected a positive distance (a perspective)");
  if (projectionOf(c.clipFromEye) == Projection::Other)
    cam["clipFromEye"].fail("neither a perspective nor an orthographic projection");
  const glm::dmat4 identity(1.0);
  if (!productIs(c.clipFromEye, c.eyeFromClip, identity))
    cam["eyeFromClip"].fail("not the inverse of clipFromEye (or clipFromEye is singular)");
  if (!productIs(c.eyeFromWorld, c.worldFromEye, identity))
    cam["worldFromEye"].fail("not the inverse of eyeFromWorld (or eyeFromWorld is singular)");
  if (!productIs(c.clipFromEye, c.eyeFromWorld, c.clipFromWorld))
    cam["clipFromWorld"].fail("not clipFromEye * eyeFromWorld");
}

// The frame's size: the camera's, and every size the manifest repeats (size, options.size).
void checkFrameSize(const JsonIn& m, const FrameSnapshot& f) {
  const std::string frame = std::to_string(f.camera.width) + "x" + std::to_string(f.camera.height);
  if (uint64_t(f.camera.width) * f.camera.height > kMaxCaptureTexels)
    (m.has("camera") ? m["camera"] : m["view"]).fail(frame + " is more than a capture holds");
  if (m.has("size") && (m["size"].size() != 2 || m["size"][size_t(0)].u32() != f.camera.width ||
                        m["size"][size_t(1)].u32() != f.camera.height))
    m["size"].fail(jsonBrief(m["size"].json()) + " is not the camera's " + frame);
  if (m.has("options") && m["options"].has("size") &&
      (f.options.width != f.camera.width || f.options.height != f.camera.height))
    m["options"]["size"].fail(jsonBrief(m["options"]["size"].json()) + " is not the camera's " + frame);
}

// A target's size: its layout's, else the frame's (gblens's shadow map: options.shadow_map_size
// square, when the options say it).
void checkTargetSizes(const JsonIn& m, const FrameSnapshot& f, const std::vector<ManifestTarget>& targets) {
  const bool native = gblensLayout(f.layout);
  for (size_t k = 0; k < targets.size(); ++k) {
    const ManifestTarget& t = targets[k];
    const LayoutTarget& lt = f.layout.targets[size_t(t.index)];
    uint32_t w = f.camera.width, h = f.camera.height;
    std::string whose = "the camera's";
    if (lt.width) {
      w = lt.width, h = lt.height, whose = "its layout's";
    } else if (native) {
      Target nt;
      if (parseTarget(lt.name, nt) && targetInfo(nt).size == SizeRule::ShadowMap) {
        if (!m.has("options") || !m["options"].has("shadow_map_size")) continue;
        w = h = f.options.shadowMapSize, whose = "options.shadow_map_size's";
      }
    }
    if (t.image.width != w || t.image.height != h)
      m["targets"][k].fail("\"" + lt.name + "\" is " + std::to_string(t.image.width) + "x" + std::to_string(t.image.height) +
                           ", not " + whose + " " + std::to_string(w) + "x" + std::to_string(h));
  }
}

// Each of `keys` the object holds (a field its source did not state is absent), within lo and a float's range.
void checkMagnitudes(const JsonIn& j, const char* const* keys, size_t count, double lo) {
  for (size_t k = 0; k < count; ++k) {
    if (!j.has(keys[k])) continue;
    const JsonIn v = j[keys[k]];
    const std::vector<double> values = v.json().is_array() ? std::vector<double>{v.vec3().x, v.vec3().y, v.vec3().z}
                                                           : std::vector<double>{v.number()};
    for (double x : values)
      if (!(x >= lo && std::abs(x) <= kMaxMagnitude))
        v.fail(jsonBrief(v.json()) + " is outside " + (lo < 0.0 ? "-3.4e38.." : "0..") + "3.4e38 (a 32-bit float's range)");
  }
}

void checkLights(const JsonIn& m, const JsonIn& lights, const FrameSnapshot& f) {
  const JsonIn list = lights["lights"];
  static const char* const position[] = {"eye_position", "color"};
  static const char* const radius[] = {"radius"};
  for (size_t i = 0; i < list.size(); ++i) {
    checkMagnitudes(list[i], position, 2, -INFINITY);
    checkMagnitudes(list[i], radius, 1, 0.0);
  }
  static const char* const sun[] = {"to_sun", "color"};
  if (m.has("sun")) checkMagnitudes(m["sun"], sun, 2, -INFINITY);
  if (f.sun.enabled && !(glm::length(f.sun.toSun) > 1e-9)) m["sun"]["to_sun"].fail("expected a direction, got a zero vector");
  static const char* const sky[] = {"zenith", "horizon", "ground", "ambient"};
  if (m.has("sky")) checkMagnitudes(m["sky"], sky, 4, -INFINITY);
  if (m.has("lights")) {  // the summary repeats lights.json's counts
    const JsonIn summary = m["lights"];
    if (summary.has("count") && uint64_t(summary["count"].integer(0, INT64_MAX)) != f.eyeLights.size())
      summary["count"].fail("lights.json holds " + std::to_string(f.eyeLights.size()) + " lights");
    if (summary.has("visible") && uint64_t(summary["visible"].integer(0, INT64_MAX)) != f.visibleLights.size())
      summary["visible"].fail("lights.json lists " + std::to_string(f.visibleLights.size()) + " visible");
  }
}

}  // namespace

void checkManifestConsistency(const JsonIn& m, const JsonIn& lights, const FrameSnapshot& f,
                              const std::vector<ManifestTarget>& targets) {
  checkFrameSize(m, f);
  checkTargetSizes(m, f, targets);
  checkCamera(m, f.camera);
  checkLights(m, lights, f);
}

}  // namespace gb
