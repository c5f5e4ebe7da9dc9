// The camera for the drafting (infer_internal.h): a sidecar when one is given; else the search of the
// buffers bound at the G-buffer pass (suggest_camera.h), judged by the stored positions; else, when
// the frame stores positions, the camera those positions fit (pinhole.h) as matrices of this frame.
#include <algorithm>
#include <cmath>

#include "renderer/core/camera.h"
#include "views/import/import.h"
#include "views/infer/infer_internal.h"
#include "views/infer/suggest_camera.h"

namespace gb::infer {

namespace {

nlohmann::json values(const glm::dmat4& m) {
  nlohmann::json a = nlohmann::json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(m[c][r]);
  return a;
}

// The depth row of a projection (clip z = a * z + b for the eye z) the stored hardware depth fits
// (depth * w = clip z, w = -z: least squares); false without a hardware depth.
bool fitDepthRow(const State& s, const std::function<std::optional<glm::dvec3>(uint32_t, uint32_t)>& eyeOf, double& a,
                 double& b) {
  if (!s.hardware || !s.image(s.hardware->target)) return false;
  double sxx = 0, sx = 0, sy = 0, sxy = 0, n = 0;
  for (const glm::uvec2& p : s.pixels) {
    const double h = s.image(s.hardware->target)->value(p.x, p.y, 0);
    const std::optional<glm::dvec3> e = eyeOf(p.x, p.y);
    if (!e || (s.hardware->background && h == *s.hardware->background)) continue;
    const double z = e->z, y = h * -z;  // y = a z + b
    sxx += z * z, sx += z, sy += y, sxy += z * y, n += 1;
  }
  const double det = n * sxx - sx * sx;
  if (n < 16 || !(std::abs(det) > 0.0)) return false;
  a = (n * sxy - sx * sy) / det;
  b = (sy - a * sx) / n;
  return true;
}

// The camera the stored positions fit, as matrices of this frame (perspective fits only).
bool cameraFromFit(State& s) {
  const PinholeFit& f = s.positions.fit;
  if (f.orthographic || !f.ok) return false;
  const glm::dmat3 flip(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);  // right, down, forward -> gblens's eye
  glm::dmat3 E = flip * f.eyeFromPoints;
  if (s.positions.space == Space::View)  // the view's own axes: exactly a signed permutation
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) E[c][r] = std::abs(E[c][r]) > 0.5 ? (E[c][r] > 0 ? 1.0 : -1.0) : 0.0;
  LayoutCamera lc;
  lc.present = true;
  glm::dmat4 eyeFromPositions(E);
  if (s.positions.space == Space::World) eyeFromPositions[3] = glm::dvec4(-(E * f.eye), 1.0);
  glm::dmat4 P(0.0);
  const double W = s.width, H = s.height;
  P[0][0] = 2.0 * f.fx / W, P[2][0] = 1.0 - 2.0 * f.cx / W;  // no skew: a fit's is rounding
  P[1][1] = -2.0 * f.fy / H, P[2][1] = 1.0 - 2.0 * f.cy / H;
  P[2][3] = -1.0;
  const CpuImage* img = s.image(size_t(s.positions.target));
  auto eyeOf = [&](uint32_t x, uint32_t y) -> std::optional<glm::dvec3> {
    const glm::dvec3 p(channelValues(*img, x, y, s.positions.channels));
    return glm::dvec3(eyeFromPositions * glm::dvec4(p, 1.0));
  };
  double a = 0.0, b = 0.0;
  std::string depthNote;
  if (fitDepthRow(s, eyeOf, a, b)) {
    depthNote = "its depth row fitted to the stored hardware depth";
  } else {
    double lo = INFINITY, hi = 0.0;
    for (const glm::uvec2& p : s.pixels) {
      const double d = -eyeOf(p.x, p.y)->z;
      if (d > 0.0) lo = std::min(lo, d), hi = std::max(hi, d);
    }
    const double n = 0.5 * lo, fa = 2.0 * hi;
    a = fa / (n - fa), b = n * fa / (n - fa);
    depthNote = "near and far not in the evidence (no hardware depth): " + numText(n) + " and " + numText(fa);
  }
  P[2][2] = a, P[3][2] = b;
  if (s.positions.space == Space::View) {  // the positions' own axes are the view's
    lc.viewFromWorld = glm::dmat4(1.0);
    lc.clipFromView = P * glm::dmat4(E);
    lc.leftHanded = lc.clipFromView[2][3] > 0.0;
  } else {
    lc.viewFromWorld = eyeFromPositions;
    lc.clipFromView = P;
  }
  std::string error;
  if (!settleWorldHandedness(lc, error) || !importCamera(lc, s.width, s.height, s.cam.camera, error)) {
    s.summary.push_back("camera: the camera the stored positions fit does not import (" + error + ")");
    return false;
  }
  double alignment = 0.0;
  lc.up = guessUpAxis(lc, s.cam.camera, alignment);
  if (!importCamera(lc, s.width, s.height, s.cam.camera, error)) return false;  // its world as the layout states it
  s.cam.present = true;
  s.cam.layout = lc;
  s.cam.checked = true;
  s.cam.from = "the stored positions";
  Guess g;
  g.quantity = "camera";
  g.confidence = 1.0;
  g.evidence = "no bound buffer holds it: the camera the stored positions fit (" + numText(f.medianPx) +
               " px median reprojection), this frame's matrices only; " + depthNote;
  s.cam.block = {{"matrix_order", "column_major"}, {"convention", "vulkan"},
                 {"view_handedness", lc.leftHanded ? "left" : "right"}, {"up", name(lc.up)},
                 {"view_from_world", values(lc.viewFromWorld)}, {"clip_from_view", values(lc.clipFromView)},
                 {"guess", g.json()}};
  s.summary.push_back("camera: " + g.evidence);
  return true;
}

CameraEvidence evidence(const State& s) {
  CameraEvidence e;
  e.width = s.width, e.height = s.height;
  e.clipYUp = s.in.clipYUp, e.clipDepthGl = s.in.clipDepthGl;
  const size_t step = std::max<size_t>(1, s.pixels.size() / 4096);
  for (size_t i = 0; i < s.pixels.size(); i += step) {
    const glm::uvec2 p = s.pixels[i];
    CameraEvidence::Sample sample;
    sample.x = p.x, sample.y = p.y;
    if (s.positions.target >= 0) {
      sample.position = glm::dvec3(channelValues(*s.image(size_t(s.positions.target)), p.x, p.y, s.positions.channels));
      sample.hasPosition = std::isfinite(sample.position.x + sample.position.y + sample.position.z);
    }
    if (s.hardware && s.image(s.hardware->target)) sample.depth = s.image(s.hardware->target)->value(p.x, p.y, 0);
    if (sample.hasPosition || !std::isnan(sample.depth)) e.samples.push_back(sample);
  }
  return e;
}

// Without stored positions the buffers' cameras are ranked by names and places only. With a hardware
// depth and a stored normal, the surface each camera rebuilds judges them: the camera under which
// some stored vector lies along the rebuilt surface's normal wins (within 2 % of each other, the
// ranking decides: a previous frame's matrix or a copy rebuilds nearly the same surface).
bool judgeByNormals(State& s, CameraEvidence e, FoundCamera& chosen) {
  if (!s.hardware || s.positions.target >= 0) return false;
  std::vector<FoundCamera> cams = searchCameras(s.in.buffers, e, s.in.bufferSource, s.in.livePass, 8);
  if (!s.in.clipYKnown) {
    e.clipYUp = !e.clipYUp;
    for (FoundCamera& c : searchCameras(s.in.buffers, e, s.in.bufferSource, s.in.livePass, 8)) cams.push_back(std::move(c));
  }
  double best = INFINITY, next = INFINITY;
  int at = -1;
  for (size_t k = 0; k < cams.size(); ++k) {
    if (!cams[k].found) continue;
    const double score =
        bestNormalMedian(s, referencesFromDepth(s, *s.hardware, cams[k].layout, cams[k].converted, "the hardware depth"));
    if (score < best * 0.98) next = std::min(next, best), best = score, at = int(k);
    else next = std::min(next, score);
  }
  if (at < 0 || !(best <= 30.0)) return false;
  chosen = std::move(cams[size_t(at)]);
  chosen.camera["guess"] = chosen.camera["guess"].get<std::string>() + "; chosen among the buffers' cameras by the normals: " +
                           "the surface it and the hardware depth rebuild lies along a stored normal (score " + numText(best) +
                           "°; the next camera " + numText(next) + "°)";
  return true;
}

}  // namespace

void decideCamera(State& s) {
  if (s.in.given) {
    s.cam.present = true;
    s.cam.layout = *s.in.given;
    s.cam.camera = s.in.givenConverted;
    s.cam.from = s.in.givenNote;
    s.cam.block = {{"sidecar", "camera.json"}, {"guess", s.in.givenNote}};
    if (s.positions.target >= 0) {
      Space space = Space::View;
      const double px = fitPositions(s.cam.layout, evidence(s), space);
      s.cam.checked = px < 0.5;
      s.cam.block["guess"] = s.in.givenNote + "; stored positions land " + numText(px) + " px from their pixels" +
                             (s.cam.checked ? "" : ": NOT confirmed");
    }
    s.summary.push_back("camera: " + s.cam.block["guess"].get<std::string>());
    return;
  }
  if (!s.in.buffers.empty()) {
    CameraEvidence e = evidence(s);
    FoundCamera found = searchCamera(s.in.buffers, e, s.in.bufferSource, s.in.livePass);
    if (!s.in.clipYKnown && !found.positionsChecked && s.positions.target >= 0) {  // a negative viewport flips clip y
      CameraEvidence flippedEvidence = e;
      flippedEvidence.clipYUp = !e.clipYUp;
      FoundCamera flipped = searchCamera(s.in.buffers, flippedEvidence, s.in.bufferSource, s.in.livePass);
      if (flipped.found && (!found.found || flipped.pixelError < found.pixelError)) found = std::move(flipped);
    }
    FoundCamera judged;
    if (judgeByNormals(s, e, judged)) found = std::move(judged);
    s.summary.insert(s.summary.end(), found.summary.begin(), found.summary.end());
    const bool positions = s.positions.target >= 0;
    if (found.found && (!positions || found.positionsChecked)) {
      s.cam.present = true;
      s.cam.layout = found.layout;
      s.cam.camera = found.converted;
      s.cam.block = found.camera;
      s.cam.checked = found.positionsChecked;
      s.cam.from = "the bound buffers";
      return;
    }
    if (found.found)
      s.summary.push_back("camera: the bound buffers hold none that maps the stored positions onto their pixels (best " +
                          numText(found.pixelError) + " px)");
  }
  if (s.positions.target >= 0 && s.in.bufferSource == "live") {  // a later frame's camera is not this one's
    s.summary.push_back("camera: the stored positions fit a camera (" + numText(s.positions.fit.medianPx) +
                        " px), but no bound buffer holds it: a running application's camera must be read each frame "
                        "(give camera.live, docs/layout-format.md)");
    return;
  }
  if (s.positions.target >= 0 && !cameraFromFit(s))
    s.summary.push_back("camera: none found, and the stored positions fit no perspective camera (" +
                        std::string(s.positions.fit.orthographic ? "a parallel projection" : "degenerate") +
                        "): give it (docs/layout-format.md, \"camera\")");
  if (!s.cam.present && s.positions.target < 0)
    s.summary.push_back("camera: none found (no bound buffer holds one and nothing stored fixes it): what needs it is left "
                        "as stored values; give the camera (docs/layout-format.md, \"camera\")");
}

}  // namespace gb::infer
