// Draft layouts (see suggest.h): what both sources share once the texels are read: where the
// surfaces are, the camera's evidence, and what the camera then tells about the quantities.
#include "views/infer/suggest.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"

namespace gb {

namespace {

bool isRenderDocCapture(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".rdc";
}

nlohmann::json* quantityJson(nlohmann::json& draft, const std::string& name) {
  for (nlohmann::json& t : draft["targets"])
    for (nlohmann::json& q : t["quantities"])
      if (q.value("name", "") == name) return &q;
  return nullptr;
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

// A position target's 4th channel that holds eye depth / k for one k everywhere (a linear depth
// stored as a fraction of the far plane, say): the scalar becomes a depth quantity.
void linearDepthInW(nlohmann::json& draft, const FrameSnapshot& f, const SurfaceMask& s, const Quantity& position,
                    const std::function<glm::dvec3(const glm::dvec3&)>& toEye, std::vector<std::string>& summary) {
  const Layout& l = f.layout;
  const Quantity* w = nullptr;
  for (const Quantity* q : l.quantitiesOf(position.target))
    if (q->kind == QuantityKind::Scalar && q->channels.size() == 1) w = q;
  if (!w) return;
  std::vector<double> ratio;
  std::map<double, size_t> background;
  for (uint32_t y = 0; y < f.camera.height; ++y)
    for (uint32_t x = 0; x < f.camera.width; ++x) {
      if (!holds(f, position, x, y)) continue;
      const double v = storedValues(f, *w, x, y)[0];
      if (!s.surface(x, y)) {
        ++background[v];
        continue;
      }
      const std::array<double, 4> p = storedValues(f, position, x, y);
      const double z = -toEye({p[0], p[1], p[2]}).z;
      if (v > 0.0 && z > 0.0) ratio.push_back(z / v);
    }
  if (ratio.size() < 16) return;
  std::sort(ratio.begin(), ratio.end());
  const double k = ratio[ratio.size() / 2], spread = (ratio[ratio.size() * 99 / 100] - ratio[ratio.size() / 100]) / k;
  if (!(spread < 1e-4)) return;
  std::string name = "eye_depth";
  for (int i = 2; quantityJson(draft, name); ++i) name = "eye_depth" + std::to_string(i);
  nlohmann::json* q = quantityJson(draft, w->name);
  *q = {{"quantity", "depth"}, {"name", name}, {"channels", w->channels}, {"encoding", "eye"},
        {"scale", std::stod(number(k))}};
  std::string note = "eye depth of the positions / " + number(k) + " at every surface texel (spread " + number(spread) + ")";
  if (!background.empty()) {
    auto most = std::max_element(background.begin(), background.end(), [](auto& a, auto& b) { return a.second < b.second; });
    (*q)["background"] = most->first;
    note += "; " + number(most->first) + " where nothing was drawn";
  }
  (*q)["guess"] = note;
  summary.push_back("depth: " + name + " holds " + note);
}

}  // namespace

bool suggestLayout(const SuggestRequest& r, Suggestion& out, std::string& error) {
  if (r.inputs.empty()) {
    error = "--suggest-layout: give a RenderDoc capture (.rdc) or image files";
    return false;
  }
  if (r.inputs.size() == 1 && isRenderDocCapture(r.inputs[0])) return suggestFromRenderDoc(r, out, error);
  if ((r.event || !r.pass.empty())) {
    error = std::string(r.event ? "--event" : "--pass") + ": applies to a RenderDoc capture (.rdc)";
    return false;
  }
  return suggestFromImages(r, out, error);
}

bool draftFrame(const nlohmann::json& draft, const FrameSnapshot& raw, FrameSnapshot& frame, std::string& error) {
  Layout l;
  if (!parseLayout(draft, "draft", l, error)) return false;
  frame = FrameSnapshot{};
  frame.setLayout(l);
  frame.images = raw.images;
  frame.absences = raw.absences;
  frame.camera = raw.camera;
  return true;
}

SurfaceMask surfaceOf(const FrameSnapshot& f) {
  SurfaceMask m;
  const Quantity* depth = surfaceDepth(f.layout);
  if (!depth || !layoutImage(f, depth->target)) return m;
  const TargetImage& ti = *layoutImage(f, depth->target);
  m.width = ti.image.width;
  m.height = ti.image.height;
  m.at.assign(size_t(m.width) * m.height, 0);
  // Hardware depth: the clear value (0 or 1, whichever is stored more) is no surface.
  size_t zeros = 0, ones = 0;
  for (uint32_t y = 0; y < m.height; ++y)
    for (uint32_t x = 0; x < m.width; ++x) {
      const double v = storedValues(f, *depth, x, y)[0];
      zeros += v == 0.0, ones += v == 1.0;
    }
  const double clear = ones >= zeros ? 1.0 : 0.0;
  for (uint32_t y = 0; y < m.height; ++y)
    for (uint32_t x = 0; x < m.width; ++x) {
      const double v = storedValues(f, *depth, x, y)[0];
      const bool drawn = depth->depth == DepthEncoding::Hardware
                             ? v != clear
                             : std::isfinite(v) && v > 0.0 && v < 1e9 && !(depth->background && v == *depth->background);
      m.at[size_t(y) * m.width + x] = drawn;
    }
  return m;
}

CameraEvidence evidenceOf(const FrameSnapshot& f, const SurfaceMask& s) {
  CameraEvidence e;
  e.width = f.camera.width;
  e.height = f.camera.height;
  const Quantity* position = f.layout.find(QuantityKind::Position);
  const Quantity* depth = surfaceDepth(f.layout);
  if (depth && depth->depth != DepthEncoding::Hardware) depth = nullptr;
  const uint32_t step = std::max(1u, uint32_t(std::sqrt(double(e.width) * e.height / 4096.0)));
  for (uint32_t y = step / 2; y < e.height; y += step)
    for (uint32_t x = step / 2; x < e.width; x += step) {
      if (!s.surface(x, y)) continue;
      CameraEvidence::Sample sample;
      sample.x = x, sample.y = y;
      if (position && holds(f, *position, x, y)) {
        const std::array<double, 4> p = storedValues(f, *position, x, y);
        sample.position = {p[0], p[1], p[2]};
        sample.hasPosition = std::isfinite(p[0] + p[1] + p[2]);
      }
      if (depth && holds(f, *depth, x, y)) sample.depth = storedValues(f, *depth, x, y)[0];
      if (sample.hasPosition || !std::isnan(sample.depth)) e.samples.push_back(sample);
    }
  return e;
}

void refineWithCamera(nlohmann::json& draft, const FrameSnapshot& drafted, const SurfaceMask& s, const LayoutCamera& camera,
                      const Camera& converted, bool positionsChecked, Space positionSpace,
                      std::vector<std::string>& summary) {
  FrameSnapshot f = drafted;  // with the camera found: depths rebuild positions through it
  f.camera = converted;
  f.layout.camera = camera;
  const Layout& l = f.layout;
  const glm::dmat3 toWorld = worldFromLayoutWorld(camera);
  auto eyeOf = [&](Space space, const glm::dvec3& v, bool point) {
    if (space == Space::View) return camera.leftHanded ? glm::dvec3(v.x, v.y, -v.z) : v;
    const glm::dvec3 w = toWorld * v;
    return point ? glm::dvec3(converted.eyeFromWorld * glm::dvec4(w, 1.0)) : glm::dmat3(converted.eyeFromWorld) * w;
  };
  if (const Quantity* p = l.find(QuantityKind::Position)) {
    nlohmann::json* q = quantityJson(draft, p->name);
    if (positionsChecked) {
      (*q)["space"] = positionSpace == Space::View ? "view" : "world";
      (*q)["guess"] = (*q)["guess"].get<std::string>() + "; " + (*q)["space"].get<std::string>() +
                      " space: projected through the camera found they land on their own pixels";
    }
    linearDepthInW(draft, f, s, *p, [&](const glm::dvec3& v) { return eyeOf(positionSpace, v, true); }, summary);
  }
  const Quantity* depth = surfaceDepth(l);
  for (const Quantity& n : l.quantities) {
    if (n.kind != QuantityKind::Normal || !depth) continue;
    // A normal is perpendicular to its surface: to the steps between the eye positions of a pixel
    // and its neighbours (rebuilt from depth with the camera). In the space the normals are stored
    // in, the median |cos| is small; in the other, it is not.
    std::vector<double> cosines[2];
    for (uint32_t y = 0; y + 1 < converted.height; ++y)
      for (uint32_t x = 0; x + 1 < converted.width; ++x) {
        if (!s.surface(x, y) || !s.surface(x + 1, y) || !s.surface(x, y + 1) || !holds(f, n, x, y)) continue;
        const std::optional<glm::dvec3> p = decodePosition(f, *depth, x, y), px = decodePosition(f, *depth, x + 1, y),
                                        py = decodePosition(f, *depth, x, y + 1);
        if (!p || !px || !py) continue;
        const glm::dvec3 dx = *px - *p, dy = *py - *p;
        const double step = -p->z * 0.05;  // a depth jump: another surface
        if (glm::length(dx) > step || glm::length(dy) > step || glm::length(dx) == 0.0 || glm::length(dy) == 0.0) continue;
        const glm::dvec3 v = decodeNormal(f, n, x, y).stored;
        for (int world = 0; world < 2; ++world) {
          const glm::dvec3 e = eyeOf(world ? Space::World : Space::View, v, false);
          if (glm::length(e) == 0.0) continue;
          const glm::dvec3 u = glm::normalize(e);
          cosines[world].push_back(std::abs(glm::dot(u, glm::normalize(dx))) + std::abs(glm::dot(u, glm::normalize(dy))));
        }
      }
    if (cosines[0].size() < 16 || cosines[1].size() < 16) continue;
    double median[2];
    for (int i = 0; i < 2; ++i) {
      std::nth_element(cosines[i].begin(), cosines[i].begin() + long(cosines[i].size() / 2), cosines[i].end());
      median[i] = cosines[i][cosines[i].size() / 2] / 2.0;
    }
    const bool world = median[1] < median[0];
    nlohmann::json* q = quantityJson(draft, n.name);
    (*q)["space"] = world ? "world" : "view";
    (*q)["guess"] = (*q)["guess"].get<std::string>() + "; " + (world ? "world" : "view") +
                    " space: perpendicular to the surface rebuilt from depth (median |cos| " + number(median[world]) +
                    "; " + number(median[!world]) + " as " + (world ? "view" : "world") + " space)";
  }
}

}  // namespace gb
