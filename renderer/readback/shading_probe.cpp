// shadePointsOnDevice: a compute shader calls the lighting passes' point-light formula over a buffer
// of cases, so its float rounding can be measured against the double reference.
#include "renderer/readback/shading_probe.h"

#include "renderer/readback/buffer_probe.h"

namespace gb {

std::vector<glm::vec3> shadePointsOnDevice(Renderer& r, const std::vector<ShadingCase>& cases) {
  if (cases.empty()) return {};
  GpuContext& ctx = *r.ctx;
  const size_t groups = (cases.size() + 63) / 64, count = groups * 64;
  Buffer values = createBuffer(ctx, count * 4 * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Readback);
  auto* v = static_cast<glm::vec4*>(values.mapped);
  for (size_t i = 0; i < count; ++i) {
    const ShadingCase c = i < cases.size() ? cases[i] : ShadingCase{{0, 0, 1}, {0, 0, -1}, {0, 0, -0.5f}, 1.0f};
    v[4 * i] = glm::vec4(c.normal, 0.0f);
    v[4 * i + 1] = glm::vec4(c.position, 1.0f);
    v[4 * i + 2] = glm::vec4(c.light, c.radius);
    v[4 * i + 3] = glm::vec4(0.0f);
  }
  runBufferProbe(r, Shader::shading_probe_comp, {}, values, uint32_t(groups));
  std::vector<glm::vec3> out(cases.size());
  for (size_t i = 0; i < cases.size(); ++i) out[i] = glm::vec3(v[4 * i + 3]);
  destroyBuffer(ctx, values);
  return out;
}

}  // namespace gb
