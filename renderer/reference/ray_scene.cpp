// The scene as Embree geometry: one triangle geometry per instance (geomID = instance index),
// world-space float vertices for the search only. A context filter applies what the rasterizer
// applies: single-sided back faces (seen from the camera, or from the sun for shadow rays) and
// alpha-cut texels are skipped; shadow rays see only shadow casters, never the triangle they start on.
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "renderer/core/assert.h"
#include "renderer/reference/reference.h"
#include "renderer/reference/sampler.h"

namespace gb::reference {

struct RayScene::Impl {
  const Scene* scene = nullptr;
  RTCDevice device = nullptr;
  RTCScene rtc = nullptr;
  std::vector<MipTexture> textures;
  struct InstanceInfo {
    const float* vertices = nullptr;    // Embree's world-space vertex buffer (x, y, z per vertex)
    const uint32_t* indices = nullptr;  // Embree's index buffer (3 per triangle)
    const MaterialDesc* material = nullptr;
    bool mirrored = false;              // the transform flips the winding
    bool castsShadow = true;
  };
  std::vector<InstanceInfo> instances;
};

namespace {

struct RayContext {
  RTCIntersectContext base;  // first: Embree hands this pointer back to the filter
  const RayScene::Impl* impl;
  bool shadow;
  uint32_t ignoreInstance, ignoreTriangle;
};

glm::dvec2 vertexUv(const Vertex& v, int set) { return set == 0 ? glm::dvec2(v.uv0) : glm::dvec2(v.uv1); }

// Alpha of the base colour at barycentrics (u, v) of the triangle, in texture level 0.
double alphaAt(const RayScene::Impl& impl, uint32_t instance, uint32_t triangle, double u, double v) {
  const Scene& s = *impl.scene;
  const Instance& inst = s.instances[instance];
  const Mesh& mesh = s.meshes[inst.mesh];
  const MaterialDesc& m = *impl.instances[instance].material;
  double alpha = m.baseColor.a;
  if (m.baseColorTexture < 0) return alpha;
  const uint32_t* idx = &s.indices[mesh.firstIndex + 3 * triangle];
  glm::dvec2 uv = (1.0 - u - v) * vertexUv(s.vertices[mesh.firstVertex + idx[0]], m.baseColorUv) +
                  u * vertexUv(s.vertices[mesh.firstVertex + idx[1]], m.baseColorUv) +
                  v * vertexUv(s.vertices[mesh.firstVertex + idx[2]], m.baseColorUv);
  glm::dvec3 t = glm::dmat3(m.baseUvTransform) * glm::dvec3(uv, 1.0);
  return alpha * impl.textures[size_t(m.baseColorTexture)].sampleLevel0(glm::dvec2(t)).a;
}

bool accept(const RayContext& rc, uint32_t instance, uint32_t triangle, double u, double v, glm::dvec3 dir) {
  const RayScene::Impl& impl = *rc.impl;
  const RayScene::Impl::InstanceInfo& info = impl.instances[instance];
  const MaterialDesc& m = *info.material;
  if (rc.shadow) {
    if (!info.castsShadow) return false;
    if (instance == rc.ignoreInstance && triangle == rc.ignoreTriangle) return false;
  }
  if (!m.doubleSided) {
    // Culled by the rasterizer: a back face seen from the camera, or, for a shadow ray (dir
    // toward the sun), a face turned away from the sun, which the shadow pass culls too. A
    // closed caster still blocks through its sun-facing side; an open single-sided sheet facing
    // away from the sun (a sky dome seen from inside) lets the sun through, as on the GPU.
    const float* p = info.vertices;
    const uint32_t* i = info.indices + 3 * triangle;
    glm::dvec3 a(p[3 * i[0]], p[3 * i[0] + 1], p[3 * i[0] + 2]);
    glm::dvec3 b(p[3 * i[1]], p[3 * i[1] + 1], p[3 * i[1] + 2]);
    glm::dvec3 c(p[3 * i[2]], p[3 * i[2] + 1], p[3 * i[2] + 2]);
    const glm::dvec3 camera = rc.shadow ? -dir : dir;  // the rasterizer's viewing direction
    bool front = (glm::dot(glm::cross(b - a, c - a), camera) < 0.0) != info.mirrored;
    if (!front) return false;
  }
  if (m.alphaMode != AlphaMode::Opaque && alphaAt(impl, instance, triangle, u, v) < m.alphaCutoff) return false;
  return true;
}

void filter(const RTCFilterFunctionNArguments* args) {
  const auto* rc = reinterpret_cast<const RayContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    uint32_t instance = RTCHitN_geomID(args->hit, args->N, i), triangle = RTCHitN_primID(args->hit, args->N, i);
    double u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    glm::dvec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                   RTCRayN_dir_z(args->ray, args->N, i));
    if (!accept(*rc, instance, triangle, u, v, dir)) args->valid[i] = 0;
  }
}

void onEmbreeError(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "gblens: embree error %d: %s\n", int(code), message ? message : "");
}

}  // namespace

RayScene::RayScene(const Scene& scene, unsigned threads) : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.scene = &scene;
  std::string config = "threads=" + std::to_string(threads ? threads : 1);
  d.device = rtcNewDevice(config.c_str());
  GB_ASSERT(d.device);
  rtcSetDeviceErrorFunction(d.device, onEmbreeError, nullptr);
  d.rtc = rtcNewScene(d.device);
  rtcSetSceneFlags(d.rtc, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(d.rtc, RTC_BUILD_QUALITY_HIGH);
  for (const Texture& t : scene.textures) d.textures.emplace_back(t);
  d.instances.resize(scene.instances.size());
  static const MaterialDesc kDefault;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    const Mesh& mesh = scene.meshes[inst.mesh];
    Impl::InstanceInfo& info = d.instances[i];
    info.material = mesh.material >= 0 && size_t(mesh.material) < scene.materials.size() ? &scene.materials[mesh.material]
                                                                                        : &kDefault;
    info.mirrored = glm::determinant(glm::dmat3(inst.worldFromObject)) < 0.0;
    info.castsShadow = inst.castsShadow;
    if (mesh.indexCount < 3) continue;
    uint32_t vertexCount = 0;
    for (uint32_t k = 0; k < mesh.indexCount; ++k)
      vertexCount = std::max(vertexCount, scene.indices[mesh.firstIndex + k] + 1);
    RTCGeometry g = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
    for (uint32_t k = 0; k < vertexCount; ++k) {
      glm::dvec3 p = glm::dvec3(inst.worldFromObject * glm::dvec4(glm::dvec3(scene.vertices[mesh.firstVertex + k].position), 1.0));
      v[3 * k] = float(p.x);
      v[3 * k + 1] = float(p.y);
      v[3 * k + 2] = float(p.z);
    }
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(uint32_t), mesh.indexCount / 3));
    for (uint32_t k = 0; k < mesh.indexCount / 3 * 3; ++k) idx[k] = scene.indices[mesh.firstIndex + k];
    info.vertices = v;
    info.indices = idx;
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(d.rtc, g, unsigned(i));
    rtcReleaseGeometry(g);  // the scene holds it
  }
  rtcCommitScene(d.rtc);
}

RayScene::~RayScene() {
  if (impl_->rtc) rtcReleaseScene(impl_->rtc);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

const Scene& RayScene::scene() const { return *impl_->scene; }
const MipTexture& RayScene::texture(int index) const { return impl_->textures[size_t(index)]; }

RayScene::Hit RayScene::firstHit(const glm::dvec3& o, const glm::dvec3& dir) const {
  RayContext rc{};
  rtcInitIntersectContext(&rc.base);
  rc.base.filter = filter;
  rc.impl = impl_.get();
  rc.shadow = false;
  RTCRayHit rh{};
  rh.ray.org_x = float(o.x);
  rh.ray.org_y = float(o.y);
  rh.ray.org_z = float(o.z);
  rh.ray.dir_x = float(dir.x);
  rh.ray.dir_y = float(dir.y);
  rh.ray.dir_z = float(dir.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->rtc, &rc.base, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.instance = rh.hit.geomID;
  h.triangle = rh.hit.primID;
  return h;
}

bool RayScene::reachesSun(const glm::dvec3& o, const glm::dvec3& toSun, uint32_t instance, uint32_t triangle,
                          double tnear) const {
  RayContext rc{};
  rtcInitIntersectContext(&rc.base);
  rc.base.filter = filter;
  rc.impl = impl_.get();
  rc.shadow = true;
  rc.ignoreInstance = instance;
  rc.ignoreTriangle = triangle;
  RTCRay ray{};
  ray.org_x = float(o.x);
  ray.org_y = float(o.y);
  ray.org_z = float(o.z);
  ray.dir_x = float(toSun.x);
  ray.dir_y = float(toSun.y);
  ray.dir_z = float(toSun.z);
  ray.tnear = float(tnear);
  ray.tfar = std::numeric_limits<float>::infinity();
  ray.mask = ~0u;
  rtcOccluded1(impl_->rtc, &rc.base, &ray);
  return ray.tfar >= 0.0f;  // set to -inf when blocked
}

}  // namespace gb::reference
