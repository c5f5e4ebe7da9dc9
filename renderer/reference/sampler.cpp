// The reference's mip chains and trilinear lookups (see sampler.h for how they follow the GPU).
#include "renderer/reference/sampler.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/image.h"

namespace gb::reference {

static double linearToSrgb(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

// The value an 8-bit texel holds after storing `linear` (sRGB-encoded or plain UNORM).
static float store8(double linear, bool srgb) {
  if (!srgb) return float(std::lround(std::clamp(linear, 0.0, 1.0) * 255.0) / 255.0);
  return float(srgbToLinear(std::lround(linearToSrgb(linear) * 255.0) / 255.0));
}

MipTexture::MipTexture(const Texture& t) : repeat_(t.repeat) {
  if (t.width == 0 || t.height == 0) return;
  Level base{t.width, t.height, std::vector<glm::vec4>(size_t(t.width) * t.height)};
  for (size_t i = 0; i < base.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      double v = t.rgba8[i * 4 + c] / 255.0;
      base.texels[i][c] = float(t.srgb && c < 3 ? srgbToLinear(v) : v);
    }
  levels_.push_back(std::move(base));
  // vkCmdBlitImage with VK_FILTER_LINEAR from level k to level k+1: each destination texel
  // centre maps to source coordinates and is filtered bilinearly (a 2x2 box for even sizes),
  // in linear space for sRGB formats, then stored as 8 bits.
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& src = levels_.back();
    Level dst{std::max(src.width / 2, 1u), std::max(src.height / 2, 1u), {}};
    dst.texels.resize(size_t(dst.width) * dst.height);
    for (uint32_t y = 0; y < dst.height; ++y)
      for (uint32_t x = 0; x < dst.width; ++x) {
        double sx = (x + 0.5) * src.width / dst.width - 0.5, sy = (y + 0.5) * src.height / dst.height - 0.5;
        int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
        double fx = sx - x0, fy = sy - y0;
        glm::dvec4 acc(0.0);
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i) {
            int xi = std::clamp(x0 + i, 0, int(src.width) - 1), yj = std::clamp(y0 + j, 0, int(src.height) - 1);
            double w = (i ? fx : 1 - fx) * (j ? fy : 1 - fy);
            acc += w * glm::dvec4(src.texels[size_t(yj) * src.width + xi]);
          }
        glm::vec4& out = dst.texels[size_t(y) * dst.width + x];
        for (int c = 0; c < 4; ++c) out[c] = store8(acc[c], t.srgb && c < 3);
      }
    levels_.push_back(std::move(dst));
  }
}

glm::dvec4 MipTexture::bilinear(const Level& l, glm::dvec2 uv) const {
  double sx = uv.x * l.width - 0.5, sy = uv.y * l.height - 0.5;
  double fx0 = std::floor(sx), fy0 = std::floor(sy);
  double fx = sx - fx0, fy = sy - fy0;
  auto wrap = [this](long long i, uint32_t n) {
    if (repeat_) {
      long long m = i % (long long)n;
      return uint32_t(m < 0 ? m + n : m);
    }
    return uint32_t(std::clamp<long long>(i, 0, (long long)n - 1));
  };
  glm::dvec4 acc(0.0);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      uint32_t xi = wrap((long long)fx0 + i, l.width), yj = wrap((long long)fy0 + j, l.height);
      acc += (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * glm::dvec4(l.texels[size_t(yj) * l.width + xi]);
    }
  return acc;
}

glm::dvec4 MipTexture::sampleLevel0(glm::dvec2 uv) const { return bilinear(levels_[0], uv); }

glm::dvec4 MipTexture::sample(glm::dvec2 uv, glm::dvec2 dx, glm::dvec2 dy) const {
  const Level& l0 = levels_[0];
  glm::dvec2 size(l0.width, l0.height);
  double rho = std::max(glm::length(dx * size), glm::length(dy * size));
  double lambda = rho > 0.0 ? std::log2(rho) : -1e9;
  double maxLevel = double(levels_.size() - 1);
  if (!(lambda > 0.0)) return bilinear(l0, uv);  // magnification (or NaN): level 0
  lambda = std::min(lambda, maxLevel);
  int k = int(std::floor(lambda));
  double f = lambda - k;
  glm::dvec4 a = bilinear(levels_[size_t(k)], uv);
  if (f == 0.0 || k + 1 > int(maxLevel)) return a;
  return glm::mix(a, bilinear(levels_[size_t(k) + 1], uv), f);
}

}  // namespace gb::reference
