// Texture sampling for the reference, made to follow the GPU's: the mip chain is built as the
// renderer builds it (each level a linear-filtered 2:1 blit of the one above, stored as 8-bit,
// sRGB-encoded for colour), and lookups are trilinear in linear space (sRGB decoded before
// filtering) with the level of detail lambda = log2(max(|d(uv)/dx|, |d(uv)/dy|) * size) from the
// derivatives the caller passes (the reference uses the 2x2 quad's coarse differences, as
// llvmpipe does). The GPU's own LOD arithmetic is approximate, so textured albedo is compared
// with a looser, reported tolerance; untextured albedo is exact.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "renderer/scene/scene.h"

namespace gb::reference {

class MipTexture {
 public:
  MipTexture() = default;
  explicit MipTexture(const Texture& texture);
  // Trilinear lookup (linear RGBA). dUVdx/dUVdy: change of uv per pixel step.
  glm::dvec4 sample(glm::dvec2 uv, glm::dvec2 dUVdx, glm::dvec2 dUVdy) const;
  // Bilinear lookup in level 0 (alpha tests inside ray queries, where no derivatives exist).
  glm::dvec4 sampleLevel0(glm::dvec2 uv) const;
  bool empty() const { return levels_.empty(); }

 private:
  struct Level {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> texels;  // linear values of the stored 8-bit texels
  };
  std::vector<Level> levels_;
  bool repeat_ = true;
  glm::dvec4 bilinear(const Level& level, glm::dvec2 uv) const;
};

}  // namespace gb::reference
