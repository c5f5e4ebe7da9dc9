// encodeNormalsOnDevice: a compute shader calls the G-buffer pass's encoder over a buffer of
// vectors, so the CPU mirror (renderer/core/codec.cpp) can be compared with what the device runs.
#include "renderer/readback/codec_probe.h"

#include <cstring>

#include "renderer/readback/buffer_probe.h"

namespace gb {

std::vector<glm::vec4> encodeNormalsOnDevice(Renderer& r, const std::vector<glm::vec3>& normals, NormalFormat format,
                                             OctEncoding encoding) {
  GpuContext& ctx = *r.ctx;
  const size_t groups = (normals.size() + 63) / 64, count = groups * 64;
  if (normals.empty()) return {};
  uint32_t code = gpu::kNormalRgba16f;
  switch (format) {
    case NormalFormat::Rgba16f: code = gpu::kNormalRgba16f; break;
    case NormalFormat::Rgba8Snorm: code = gpu::kNormalRgba8Snorm; break;
    case NormalFormat::OctRg16: code = gpu::kNormalOctRg16; break;
    case NormalFormat::Rgb10a2: code = gpu::kNormalRgb10a2; break;
  }
  Buffer values = createBuffer(ctx, count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Readback);
  auto* v = static_cast<glm::vec4*>(values.mapped);
  for (size_t i = 0; i < count; ++i) v[i] = glm::vec4(i < normals.size() ? normals[i] : glm::vec3(0, 0, 1), 0.0f);
  std::vector<SpecConstant> spec = {{gpu::kSpecNormalEncoding, code},
                                    {gpu::kSpecOctPrecise, encoding == OctEncoding::Precise ? 1u : 0u}};
  runBufferProbe(r, Shader::codec_probe_comp, spec, values, uint32_t(groups));
  std::vector<glm::vec4> out(v, v + normals.size());
  destroyBuffer(ctx, values);
  return out;
}

}  // namespace gb
