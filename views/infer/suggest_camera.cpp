// The camera search of import --suggest-layout (see suggest_camera.h): candidates by the shape of
// their numbers, hypotheses by conventions, and the stored positions as the judge.
#include "views/infer/suggest_camera.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "views/import/import.h"

namespace gb {

namespace {

struct Candidate {
  size_t buffer = 0;
  uint64_t offset = 0;  // from the start of the bound range
  bool rowMajor = false;
  glm::dmat4 m{1.0};
  std::string member;   // the reflected member at that offset ("" : none)
};

bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r]) || std::abs(m[c][r]) > 1e12) return false;
  return true;
}

// Zero within float rounding of the matrix's largest entry.
bool zero(double v, double scale) { return std::abs(v) <= 1e-6 * scale; }

double largest(const glm::dmat4& m) {
  double s = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) s = std::max(s, std::abs(m[c][r]));
  return s;
}

// glm: m[column][row]. Clip w from z alone (perspective) or a constant (orthographic), x and y
// scaled without mixing; a depth term in both.
bool perspectiveShape(const glm::dmat4& m) {
  const double s = largest(m);
  return s > 0.0 && zero(m[0][1], s) && zero(m[1][0], s) && zero(m[0][3], s) && zero(m[1][3], s) && zero(m[3][3], s) &&
         zero(m[3][0], s) && zero(m[3][1], s) && !zero(m[2][3], s) && !zero(m[3][2], s) && !zero(m[0][0], s) &&
         !zero(m[1][1], s);
}

bool orthographicShape(const glm::dmat4& m) {
  const double s = largest(m);
  return s > 0.0 && zero(m[0][1], s) && zero(m[1][0], s) && zero(m[0][2], s) && zero(m[1][2], s) && zero(m[2][0], s) &&
         zero(m[2][1], s) && zero(m[0][3], s) && zero(m[1][3], s) && zero(m[2][3], s) && !zero(m[3][3], s) &&
         !zero(m[0][0], s) && !zero(m[1][1], s) && !zero(m[2][2], s);
}

// A view matrix: rotation (or a mirror) and translation, bottom row 0 0 0 1.
bool rigidShape(const glm::dmat4& m) {
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || std::abs(m[3][3] - 1.0) > 1e-6) return false;
  const glm::dmat3 r(m);
  const glm::dmat3 e = glm::transpose(r) * r;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      if (std::abs(e[c][k] - (c == k ? 1.0 : 0.0)) > 1e-4) return false;
  return true;
}

bool same(const glm::dmat4& a, const glm::dmat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (a[c][r] != b[c][r]) return false;
  return true;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

struct Candidates {
  std::vector<Candidate> projections, views;
  std::vector<Candidate> combined;  // clip_from_world: a perspective projection times a view
};

// A clip_from_world (view * projection, an engine's only camera matrix): neither shape above, and it
// splits into a rigid view and a perspective projection.
bool combinedShape(const glm::dmat4& m, bool clipYUp) {
  if (perspectiveShape(m) || orthographicShape(m) || rigidShape(m)) return false;
  glm::dmat4 view, proj;
  return splitClipFromWorld(m, clipYUp, view, proj) && perspectiveShape(proj);
}

Candidates findCandidates(const std::vector<RdcBinding>& buffers, bool clipYUp) {
  Candidates out;
  for (size_t b = 0; b < buffers.size(); ++b) {
    const std::vector<uint8_t>& d = buffers[b].data;
    std::map<uint64_t, std::string> members;
    for (const RdcBinding::Member& m : buffers[b].members) members[m.offset] = m.name;
    for (size_t o = 0; o + 64 <= d.size(); o += 4)
      for (bool rowMajor : {false, true}) {
        const glm::dmat4 m = matrixFromFloats(d, o, rowMajor);
        if (!finite(m)) continue;
        auto it = members.find(o);
        Candidate c{b, o, rowMajor, m, it == members.end() || it->second.rfind("_child", 0) == 0 ? "" : it->second};
        if ((perspectiveShape(m) || orthographicShape(m)) && out.projections.size() < 256) out.projections.push_back(c);
        if (out.combined.size() < 256 && combinedShape(m, clipYUp) &&
            std::none_of(out.combined.begin(), out.combined.end(), [&](const Candidate& v) { return same(v.m, m); }))
          out.combined.push_back(c);
        // Keep one of each distinct view matrix (per-object arrays repeat them).
        if (rigidShape(m) && out.views.size() < 1024 &&
            std::none_of(out.views.begin(), out.views.end(), [&](const Candidate& v) { return same(v.m, m); }))
          out.views.push_back(c);
      }
  }
  return out;
}

// A camera hypothesis: projection, view (null: identity), conventions.
struct Hypothesis {
  const Candidate* projection = nullptr;
  const Candidate* view = nullptr;
  bool inverseView = false;  // the view candidate is world_from_view
  bool combined = false;     // `projection` is a clip_from_world, split into both
  bool leftHanded = false;
  Space space = Space::View;
  LayoutCamera layout;
  Camera camera;
  double pixelError = INFINITY, depthError = 0.0;
  size_t checked = 0;
  int prior = 0;
};

// The median distance (pixels) of stored positions projected through the hypothesis from their pixel
// centres, and the median depth difference; false when the hypothesis is no camera at all.
bool score(Hypothesis& h, const CameraEvidence& e, size_t maxSamples) {
  std::vector<double> px, dz;
  const glm::dmat3 toWorld = worldFromLayoutWorld(h.layout);
  const size_t step = std::max<size_t>(1, e.samples.size() / std::max<size_t>(maxSamples, 1));
  for (size_t i = 0; i < e.samples.size(); i += step) {
    const CameraEvidence::Sample& s = e.samples[i];
    if (!s.hasPosition) continue;
    glm::dvec3 eye = h.space == Space::View ? glm::dvec3(s.position.x, s.position.y, h.leftHanded ? -s.position.z : s.position.z)
                                            : glm::dvec3(h.camera.eyeFromWorld * glm::dvec4(toWorld * s.position, 1.0));
    const glm::dvec4 clip = h.camera.clipFromEye * glm::dvec4(eye, 1.0);
    if (!(clip.w > 0.0)) {
      px.push_back(1e9);
      continue;
    }
    const glm::dvec2 pixel((clip.x / clip.w * 0.5 + 0.5) * e.width - 0.5, (clip.y / clip.w * 0.5 + 0.5) * e.height - 0.5);
    const double off = glm::length(pixel - glm::dvec2(s.x, s.y));
    px.push_back(std::isfinite(off) ? off : 1e9);
    if (!std::isnan(s.depth)) dz.push_back(std::abs(clip.z / clip.w - s.depth));
  }
  h.checked = px.size();
  if (px.empty()) return false;
  auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  h.pixelError = median(px);
  h.depthError = dz.empty() ? 0.0 : median(dz);
  return true;
}

// Without positions to judge by: the eye depth the hardware depth gives must be positive and
// within the projection's near and far planes at every sampled surface.
bool depthsFit(const Hypothesis& h, const CameraEvidence& e) {
  size_t n = 0;
  for (const CameraEvidence::Sample& s : e.samples) {
    if (std::isnan(s.depth)) continue;
    const double z = -eyeFromHardwareDepth(h.camera, s.x, s.y, s.depth).z;
    const double lo = std::min(h.camera.znear, h.camera.zfar), hi = std::max(h.camera.znear, h.camera.zfar);
    if (!(z > 0.0) || z < lo * (1 - 1e-4) || z > hi * (1 + 1e-4)) return false;
    ++n;
  }
  return n > 0;
}

// Names and places that make a candidate the likelier one when no stored value can tell.
int projectionPrior(const Candidate& p) {
  const std::string m = lower(p.member);
  int prior = 0;
  if (m.find("proj") != std::string::npos) prior += 4;
  if (m.find("view") != std::string::npos || m.find("inv") != std::string::npos) prior -= 2;
  const double w = std::abs(p.m[2][3]) + std::abs(p.m[3][3]);
  if (w == 1.0) prior += 2;  // glm, D3DX and Blender write exactly 1 there
  return prior;
}

int viewPrior(const Candidate& v, const Candidate& p, bool inverse) {
  const std::string m = lower(v.member);
  int prior = 0;
  const bool named = m.find("view") != std::string::npos && m.find("proj") == std::string::npos;
  const bool namedInverse = m.find("inv") != std::string::npos || m.find("world_from_view") != std::string::npos ||
                            m.find("camera") != std::string::npos;
  if (named) prior += 4;
  if (m.find("model") != std::string::npos || m.find("object") != std::string::npos) prior -= 4;
  if (namedInverse == inverse && !m.empty()) prior += 1;
  if (!inverse) prior += 1;  // shaders multiply by view_from_world; the inverse is stored less often
  if (v.buffer == p.buffer && v.rowMajor == p.rowMajor) prior += 2;
  if (v.buffer == p.buffer && (v.offset + 64 == p.offset || p.offset + 64 == v.offset)) prior += 2;
  if (glm::length(glm::dvec3(v.m[3])) > 0.0) prior += 1;  // an identity or a rotation about the origin: rarely a camera
  return prior;
}

bool makeCamera(Hypothesis& h, const CameraEvidence& e) {
  LayoutCamera& c = h.layout;
  c = LayoutCamera{};
  c.present = true;
  c.clipFromView = h.projection->m;
  if (h.view) c.viewFromWorld = h.inverseView ? glm::inverse(h.view->m) : h.view->m;
  c.leftHanded = h.leftHanded;
  c.convention = !e.clipYUp ? LayoutCamera::Convention::Vulkan
                 : e.clipDepthGl ? LayoutCamera::Convention::Gl
                                 : LayoutCamera::Convention::D3d;
  if (h.combined && !splitClipFromWorld(h.projection->m, e.clipYUp, c.viewFromWorld, c.clipFromView)) return false;
  std::string error;
  return settleWorldHandedness(c, error) && importCamera(c, e.width, e.height, h.camera, error);
}

const char* conventionName(LayoutCamera::Convention c) {
  static const char* n[] = {"vulkan", "d3d", "gl"};
  return n[size_t(c)];
}

std::string where(const std::vector<RdcBinding>& buffers, const Candidate& c) {
  const RdcBinding& b = buffers[c.buffer];
  std::string text = "\"" + b.name + "\" byte " + std::to_string(b.offset + c.offset);
  if (!c.member.empty()) text += " (" + c.member + ")";
  return text + (c.rowMajor ? " row-major" : "");
}

// The draft's camera block for the chosen hypothesis.
// Where the camera's matrices are, as the layout names them: a capture's buffer (offsets from its
// start), or a running application's binding (offsets from the bound range's start).
nlohmann::json matricesAt(const std::vector<RdcBinding>& buffers, const Candidate& p, const Candidate* view,
                          bool inverse, const std::string& source, int livePass) {
  const RdcBinding& b = buffers[p.buffer];
  const uint64_t base = source == "live" ? 0 : b.offset;
  nlohmann::json m = nlohmann::json::object();
  if (view) m[inverse ? "world_from_view" : "view_from_world"] = {{"offset", base + view->offset}};
  m[view ? "clip_from_view" : "clip_from_world"] = {{"offset", base + p.offset}};
  if (source != "live") {
    m["buffer"] = b.autoName || b.name.empty() ? "#" + std::to_string(b.id) : b.name;
    return {{"renderdoc", m}};
  }
  nlohmann::json pick = {{"pass", livePass}};
  if (b.kind == "push_constants")
    pick["push_constants"] = true;
  else
    pick.update({{"set", b.set}, {"binding", b.binding}, {"index", b.index}});
  m["live"] = pick;
  return m;
}

nlohmann::json cameraJson(const std::vector<RdcBinding>& buffers, const Hypothesis& h, Axis up, const std::string& source,
                          int livePass) {
  const LayoutCamera& c = h.layout;
  nlohmann::json j = {{"convention", conventionName(c.convention)},
                      {"view_handedness", c.leftHanded ? "left" : "right"},
                      {"up", name(up)},
                      {"projection", orthographic(h.camera) ? "orthographic" : "perspective"}};
  const Candidate& p = *h.projection;
  if (h.combined || (h.view && h.view->buffer == p.buffer && h.view->rowMajor == p.rowMajor)) {
    j["matrix_order"] = p.rowMajor ? "row_major" : "column_major";
    j.update(matricesAt(buffers, p, h.combined ? nullptr : h.view, h.inverseView, source, livePass));
    return j;
  }
  // Matrices the renderdoc block cannot name together (two buffers, two orders, no view): their values.
  auto values = [](const glm::dmat4& m) {
    nlohmann::json a = nlohmann::json::array();
    for (int col = 0; col < 4; ++col)
      for (int r = 0; r < 4; ++r) a.push_back(m[col][r]);
    return a;
  };
  j["matrix_order"] = "column_major";
  j["view_from_world"] = values(c.viewFromWorld);
  j["clip_from_view"] = values(c.clipFromView);
  return j;
}

}  // namespace

Axis guessUpAxis(const LayoutCamera& c, const Camera& converted, double& alignment) {
  // gblens's eye: +Y is up the image when clip y = -eye y (the converted projection's p11 < 0).
  const double sign = converted.clipFromEye[1][1] < 0.0 ? 1.0 : -1.0;
  const glm::dmat3 layoutWorldFromEye = layoutWorldFromWorld(c) * glm::dmat3(converted.worldFromEye);
  glm::dvec3 up = glm::normalize(layoutWorldFromEye * glm::dvec3(0.0, sign, 0.0));
  const glm::dvec3 back = glm::normalize(layoutWorldFromEye * glm::dvec3(0.0, 0.0, 1.0));
  auto best = [](const glm::dvec3& v, double& a) {
    int axis = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(v[i]) > std::abs(v[axis])) axis = i;
    a = std::abs(v[axis]);
    return Axis(2 * axis + (v[axis] < 0.0 ? 1 : 0));
  };
  Axis axis = best(up, alignment);
  if (alignment < 0.5) axis = best(back, alignment);  // looking straight down: up is toward the camera
  return axis;
}

double fitPositions(const LayoutCamera& c, const CameraEvidence& e, Space& space) {
  Hypothesis h;
  h.layout = c;
  h.leftHanded = c.leftHanded;
  std::string error;
  if (!settleWorldHandedness(h.layout, error) || !importCamera(h.layout, e.width, e.height, h.camera, error))
    return INFINITY;
  Hypothesis world = h;
  world.space = Space::World;
  if (!score(h, e, 4096) || !score(world, e, 4096)) return INFINITY;
  space = world.pixelError < h.pixelError ? Space::World : Space::View;
  return std::min(world.pixelError, h.pixelError);
}

namespace {

// Every projection, both handednesses where its shape does not tell, then with every view matrix
// (and its inverse): scored by the stored positions (view space, and world space through the view
// matrix), or by the depth's fit alone. Sorted, the best first.
std::vector<Hypothesis> rankHypotheses(const Candidates& cands, const CameraEvidence& e, bool positions) {
  // Without positions or depths (a linear depth only, say) nothing here judges: the priors rank, and
  // the caller judges the few best by the normals (views/infer).
  const bool depths = std::any_of(e.samples.begin(), e.samples.end(), [](const auto& s) { return !std::isnan(s.depth); });
  std::vector<Hypothesis> tried;
  for (const Candidate& p : cands.projections) {
    const bool persp = perspectiveShape(p.m);
    for (bool left : {false, true}) {
      if (persp && left != (p.m[2][3] > 0.0)) continue;
      Hypothesis h;
      h.projection = &p;
      h.leftHanded = left;
      h.prior = projectionPrior(p);
      if (!makeCamera(h, e)) continue;
      if (positions ? score(h, e, 256) : !depths || depthsFit(h, e)) tried.push_back(h);
    }
  }
  std::vector<Hypothesis> withViews;
  for (const Hypothesis& base : tried)
    for (const Candidate& v : cands.views)
      for (bool inverse : {false, true}) {
        Hypothesis h = base;
        h.view = &v;
        h.inverseView = inverse;
        h.prior = base.prior + viewPrior(v, *base.projection, inverse);
        if (!makeCamera(h, e)) continue;
        if (positions) {
          h.space = Space::World;
          Hypothesis asView = h;
          asView.space = Space::View;
          score(asView, e, 256);
          score(h, e, 64);
          if (asView.pixelError <= h.pixelError) h = asView;
        }
        withViews.push_back(h);
      }
  for (const Candidate& m : cands.combined) {  // clip_from_world alone: view and projection at once
    Hypothesis h;
    h.projection = &m;
    h.combined = true;
    h.prior = projectionPrior(m) + 1;
    if (!makeCamera(h, e)) continue;
    if (positions) {
      h.space = Space::World;
      score(h, e, 256);
    } else if (depths && !depthsFit(h, e)) {
      continue;
    }
    withViews.push_back(h);
  }
  std::vector<Hypothesis>& pool = withViews.empty() ? tried : withViews;
  // The best fit wins; the priors break ties (and decide alone without positions).
  auto better = [](const Hypothesis& a, const Hypothesis& b) {
    const double ea = a.pixelError, eb = b.pixelError;
    if (std::abs(ea - eb) > 1e-3 * std::max(1.0, std::min(ea, eb))) return ea < eb;
    return a.prior > b.prior;
  };
  if (positions) {
    std::sort(pool.begin(), pool.end(), better);
    for (size_t i = 0; i < pool.size() && i < 8; ++i) score(pool[i], e, 100000);  // the best few on every sample
    std::sort(pool.begin(), pool.begin() + long(std::min<size_t>(pool.size(), 8)), better);
  } else {
    std::stable_sort(pool.begin(), pool.end(), [](const Hypothesis& a, const Hypothesis& b) { return a.prior > b.prior; });
  }
  return pool;
}

// The draft's note: what was chosen, what checked it, what else fits.
std::string guessNote(const std::vector<RdcBinding>& buffers, const std::vector<Hypothesis>& pool, bool positions,
                      bool checked, Axis up, double alignment) {
  const Hypothesis& best = pool[0];
  std::ostringstream why;
  why << (orthographic(best.camera) ? "orthographic" : "perspective") << " projection at " << where(buffers, *best.projection);
  if (best.combined) why << " (clip_from_world: view and projection together, split; the view's handedness is not in it)";
  else if (best.view) why << ", " << (best.inverseView ? "world_from_view" : "view_from_world") << " at " << where(buffers, *best.view);
  else why << ", no view matrix found (identity)";
  if (positions)
    why << "; stored positions in " << (best.space == Space::View ? "view" : "world") << " space land "
        << best.pixelError << " px (median of " << best.checked << ") from their pixels"
        << (checked ? "" : ": too far, so the camera is NOT confirmed")
        << (best.space == Space::View && best.view ? "; the view matrix only turns world space: nothing stored checked it" : "");
  else
    why << "; not checked: the G-buffer stores no positions (the stored depth fits its near and far planes)";
  why << "; up " << name(up) << " from the image's up direction (" << alignment << " along it)";
  const auto other = std::find_if(pool.begin() + 1, pool.end(), [&](const Hypothesis& h) {
    return h.projection != best.projection || h.view != best.view;
  });
  if (other != pool.end() && (!positions || other->pixelError <= 10 * std::max(best.pixelError, 1e-3))) {
    why << "; also fitting: " << where(buffers, *other->projection);
    if (other->view) why << " with " << where(buffers, *other->view);
  }
  return why.str();
}

}  // namespace

std::vector<FoundCamera> searchCameras(const std::vector<RdcBinding>& buffers, const CameraEvidence& e,
                                       const std::string& source, int livePass, size_t wanted) {
  std::vector<FoundCamera> found;
  const Candidates cands = findCandidates(buffers, e.clipYUp);
  const bool positions = std::any_of(e.samples.begin(), e.samples.end(), [](const auto& s) { return s.hasPosition; });
  std::ostringstream log;
  log << cands.projections.size() << " projection-shaped, " << cands.views.size() << " view-shaped and "
      << cands.combined.size() << " clip_from_world-shaped matrices in " << buffers.size() << " bound buffers";
  const std::vector<Hypothesis> pool = rankHypotheses(cands, e, positions);
  if (pool.empty()) {
    FoundCamera out;
    out.summary.push_back(log.str());
    out.summary.push_back(cands.projections.empty() && cands.combined.empty()
                              ? "no projection found: give the camera yourself (docs/layout-format.md, \"camera\")"
                              : "no projection fits the stored depth: give the camera yourself");
    found.push_back(out);
    return found;
  }
  for (size_t i = 0; i < pool.size() && found.size() < wanted; ++i) {
    const Hypothesis& best = pool[i];
    if (std::any_of(pool.begin(), pool.begin() + long(i), [&](const Hypothesis& h) {
          return h.projection == best.projection && h.view == best.view && h.inverseView == best.inverseView;
        }))
      continue;
    FoundCamera out;
    out.summary.push_back(log.str());
    double alignment = 0.0;
    const Axis up = guessUpAxis(best.layout, best.camera, alignment);
    out.found = true;
    out.layout = best.layout;
    out.layout.up = up;
    out.converted = best.camera;
    // The world as the layout states it (its up axis): the converted camera turns that world.
    std::string unused;
    if (!importCamera(out.layout, e.width, e.height, out.converted, unused)) out.converted = best.camera;
    out.positionsChecked = positions && best.pixelError < e.pixelBound;
    out.positionSpace = best.space;
    out.pixelError = best.pixelError;
    out.camera = cameraJson(buffers, best, up, source, livePass);
    std::vector<Hypothesis> rest(pool.begin() + long(i), pool.end());
    out.camera["guess"] = guessNote(buffers, rest, positions, out.positionsChecked, up, alignment);
    out.summary.push_back("camera: " + out.camera["guess"].get<std::string>());
    found.push_back(std::move(out));
  }
  return found;
}

FoundCamera searchCamera(const std::vector<RdcBinding>& buffers, const CameraEvidence& e, const std::string& source,
                         int livePass) {
  return searchCameras(buffers, e, source, livePass, 1)[0];
}

}  // namespace gb
