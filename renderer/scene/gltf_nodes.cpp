// Nodes: the scene's node trees become instances (world transforms in double), cameras and
// KHR_lights_punctual lights; then bounds, an automatic camera and near/far planes from them.
// Light mapping (gblens point lights have a window falloff, not 1/d^2): see docs/gltf.md.
#include <algorithm>
#include <cmath>

#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

struct Placed {
  int index;  // camera or light index
  size_t node;
  glm::dmat4 world;
};

glm::dmat4 localMatrix(const Doc& doc, size_t i) {
  const tinygltf::Node& n = doc.model.nodes[i];
  if (n.matrix.size() == 16) {
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c * 4 + r)];  // column-major, as glTF
    return m;
  }
  glm::dmat4 t(1.0), r(1.0), s(1.0);
  if (n.translation.size() == 3) t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  if (n.rotation.size() == 4) {
    glm::dvec4 q(n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3]);  // x, y, z, w
    double len = glm::length(q);
    if (!(len > 1e-12)) fail(doc, named("node", i, n.name), "rotation is a zero quaternion");
    q /= len;
    double x = q.x, y = q.y, z = q.z, w = q.w;
    r[0] = glm::dvec4(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0);
    r[1] = glm::dvec4(2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0);
    r[2] = glm::dvec4(2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0);
  }
  if (n.scale.size() == 3) s[0][0] = n.scale[0], s[1][1] = n.scale[1], s[2][2] = n.scale[2];
  return t * r * s;
}

bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// A camera's node transform as a rotation + translation (cameras look down -Z, +Y up, as
// gb::CameraDesc): scale, shear and mirroring removed, degenerate axes replaced, so the view
// matrix is always invertible.
glm::dmat4 rigid(const glm::dmat4& world) {
  glm::dvec3 back(world[2]), up(world[1]);
  back = glm::length(back) > 1e-300 ? glm::normalize(back) : glm::dvec3(0, 0, 1);
  up -= back * glm::dot(back, up);
  if (!(glm::length(up) > 1e-12 * (1.0 + glm::length(glm::dvec3(world[1])))))
    up = std::abs(back.y) < 0.9 ? glm::dvec3(0, 1, 0) - back * back.y : glm::dvec3(1, 0, 0) - back * back.x;
  up = glm::normalize(up);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(glm::cross(up, back), 0.0);
  m[1] = glm::dvec4(up, 0.0);
  m[2] = glm::dvec4(back, 0.0);
  m[3] = world[3];
  return m;
}

// Distance from `eye` to the farthest corner of the bounds.
double farthest(const Bounds& b, const glm::dvec3& eye) {
  double d = 0.0;
  for (int c = 0; c < 8; ++c)
    d = std::max(d, glm::length(glm::dvec3(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y,
                                           c & 4 ? b.max.z : b.min.z) - eye));
  return d;
}

CameraDesc camera(const Doc& doc, const Placed& p, const Bounds& bounds) {
  const tinygltf::Camera& c = doc.model.cameras[size_t(p.index)];
  CameraDesc d;
  d.name = c.name.empty() ? "camera " + std::to_string(p.index) : c.name;
  d.worldFromEye = rigid(p.world);
  d.aspect = 0.0;  // the output's aspect (glTF viewers ignore aspectRatio too: no stretched images)
  const glm::dvec3 eye(d.worldFromEye[3]);
  if (c.type == "perspective") {
    d.yfov = c.perspective.yfov;
    d.znear = c.perspective.znear;
    // No zfar: an infinite projection in glTF; here far from the bounds.
    d.zfar = c.perspective.zfar > 0.0 ? c.perspective.zfar : std::max(farthest(bounds, eye) * 1.05, d.znear * 2.0);
  } else {
    // gblens projects in perspective only: an orthographic camera becomes a distant, narrow one
    // that sees the same box (parallel lines converge by at most a few percent).
    double ymag = std::abs(c.orthographic.ymag), back = 20.0 * std::max(ymag, 1e-6);
    d.yfov = 2.0 * std::atan(ymag / back);
    d.worldFromEye[3] = glm::dvec4(eye + glm::dvec3(d.worldFromEye[2]) * back, 1.0);
    d.znear = back + c.orthographic.znear;
    d.zfar = back + c.orthographic.zfar;
    warn(doc, d.name + ": orthographic camera approximated by a distant perspective camera");
  }
  return d;
}

// KHR_lights_punctual -> sun and point lights (see docs/gltf.md for the mapping).
void addLights(const Doc& doc, const std::vector<Placed>& placed, Scene& scene, int lightCount) {
  const auto& lights = doc.model.lights;
  SceneLoadStats* stats = doc.stats;
  if (placed.empty()) {
    // No lights of its own: the built-in look, a sun plus generated point lights over the bounds.
    scene.sun.enabled = true;
    generateLights(scene, lightCount);
    return;
  }
  const Bounds& b = scene.bounds;
  const glm::dvec3 centre = b.empty() ? glm::dvec3(0.0) : b.center();
  const double size = std::max(b.radius(), 1e-6);
  auto colour = [&](const tinygltf::Light& l) {
    return l.color.size() == 3 ? glm::dvec3(l.color[0], l.color[1], l.color[2]) : glm::dvec3(1.0);
  };
  auto peak = [](const glm::dvec3& c) { return std::max({c.x, c.y, c.z}); };
  auto reference = [&](const Placed& p) {  // where a light meets the model
    return std::max(glm::length(glm::dvec3(p.world[3]) - centre), 0.25 * size);
  };
  // One exposure for the file: the brightest light gives 1 (in illuminance) where it meets the model.
  double brightest = 0.0;
  for (const Placed& p : placed) {
    const tinygltf::Light& l = lights[size_t(p.index)];
    double e = l.intensity * peak(colour(l));
    brightest = std::max(brightest, l.type == "directional" ? e : e / (reference(p) * reference(p)));
  }
  const double exposure = brightest > 0.0 ? 1.0 / brightest : 1.0;

  scene.sun.enabled = false;
  double sunIlluminance = -1.0;
  for (const Placed& p : placed) {
    const tinygltf::Light& l = lights[size_t(p.index)];
    const std::string name = "KHR_lights_punctual " + named("light", size_t(p.index), l.name);
    glm::dvec3 c = colour(l);
    if (l.type == "directional") {
      ++stats->directionalLights;
      double e = l.intensity * peak(c);
      if (e <= sunIlluminance) {
        warn(doc, name + ": a second directional light is ignored (gblens has one sun)");
        continue;
      }
      if (sunIlluminance >= 0.0) warn(doc, "a dimmer directional light is ignored (gblens has one sun)");
      sunIlluminance = e;
      glm::dvec3 dir = glm::dmat3(p.world) * glm::dvec3(0, 0, -1);  // the light shines down its -Z
      if (!(glm::length(dir) > 1e-12)) continue;
      scene.sun.enabled = true;
      scene.sun.toSun = -glm::normalize(dir);
      scene.sun.color = glm::vec3(c * l.intensity * exposure);
      continue;
    }
    if (l.type == "spot") {
      ++stats->spotLights;
      warn(doc, name + ": spot light drawn as a point light (no cone)");
    } else {
      ++stats->pointLights;
    }
    PointLightDesc d;
    d.center = glm::dvec3(p.world[3]);
    d.color = glm::vec3(peak(c) > 0.0 ? c / peak(c) : c);
    // Radius: the file's range, or where the exposed light I/d^2 falls below 1/256 (8-bit black);
    // at most a few scene sizes (beyond that the volume only covers the screen).
    double exposed = l.intensity * peak(c) * exposure;
    double radius = l.range > 0.0 ? l.range : 16.0 * std::sqrt(exposed);
    d.radius = std::min(radius, 4.0 * size);
    // Intensity: equal to the exposed 1/d^2 light where it meets the model.
    double r = reference(p), window = 1.0 - (r * r) / (d.radius * d.radius);
    d.intensity = exposed / (r * r) / (window > 0.25 ? window * window : 0.0625);
    scene.lights.push_back(d);
  }
  scene.generatedLights = false;
}

}  // namespace

void buildNodes(Doc& doc, int lightCount) {
  const tinygltf::Model& model = doc.model;
  Scene& scene = *doc.scene;
  std::vector<int> roots;
  int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : model.scenes.empty() ? -1 : 0;
  if (sceneIndex >= 0) {
    roots = model.scenes[size_t(sceneIndex)].nodes;
  } else {  // no scenes: every root node (validateDocument made the nodes a forest)
    std::vector<char> child(model.nodes.size(), 0);
    for (const tinygltf::Node& n : model.nodes)
      for (int c : n.children) child[size_t(c)] = 1;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!child[i]) roots.push_back(int(i));
    if (!roots.empty()) ignored(doc, "no scenes: all root nodes are drawn");
  }

  std::vector<Placed> cameras, lights;
  std::vector<std::pair<size_t, glm::dmat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(size_t(*it), glm::dmat4(1.0));
  while (!stack.empty()) {
    auto [i, parent] = stack.back();
    stack.pop_back();
    const tinygltf::Node& n = model.nodes[i];
    glm::dmat4 world = parent * localMatrix(doc, i);
    if (!finite(world)) fail(doc, named("node", i, n.name), "world transform overflows (Inf or NaN)");
    if (n.mesh >= 0) {
      const std::vector<uint32_t>& meshes = doc.meshPrimitives[size_t(n.mesh)];
      if (scene.instances.size() + meshes.size() > kMaxInstances)
        fail(doc, named("node", i, n.name), "more than " + std::to_string(kMaxInstances) + " instances (absurd size)");
      for (uint32_t m : meshes) scene.instances.push_back({m, world, true});
    }
    if (n.camera >= 0) cameras.push_back({n.camera, i, world});
    if (const tinygltf::Value* ext = extension(n.extensions, "KHR_lights_punctual"))
      lights.push_back({member(*ext, "light")->GetNumberAsInt(), i, world});
    if (n.skin >= 0) ignored(doc, "skinning (drawn in the bind pose)");
    for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.emplace_back(size_t(*c), world);
  }
  if (!model.animations.empty()) ignored(doc, "animations (drawn at rest)");

  computeBounds(scene);
  Bounds framing = scene.bounds;
  if (framing.empty()) framing.add(glm::dvec3(-1.0)), framing.add(glm::dvec3(1.0));

  // Cameras by glTF camera index, then node order; the automatic camera last (always there).
  std::stable_sort(cameras.begin(), cameras.end(), [](const Placed& a, const Placed& b) { return a.index < b.index; });
  for (const Placed& p : cameras) scene.cameras.push_back(camera(doc, p, framing));
  scene.cameras.push_back(autoCamera(framing));
  addLights(doc, lights, scene, lightCount);
}

}  // namespace gb::gltf
