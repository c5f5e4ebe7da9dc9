// The measurements of evidence.h: channel values, clear texels, surface masks, sample pixels.
#include "views/infer/evidence.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>


namespace gb {


glm::dvec4 channelValues(const CpuImage& img, uint32_t x, uint32_t y, const std::vector<uint32_t>& ch) {
  glm::dvec4 v(0.0);
  for (size_t k = 0; k < ch.size() && k < 4; ++k) v[int(k)] = img.value(x, y, ch[k]);
  return v;
}

std::array<uint32_t, 4> channelRaw(const CpuImage& img, uint32_t x, uint32_t y, const std::vector<uint32_t>& ch) {
  std::array<uint32_t, 4> r{};
  for (size_t k = 0; k < ch.size() && k < 4; ++k) r[k] = img.raw(x, y, ch[k]);
  return r;
}

ClearTexel commonTexel(const CpuImage& img) {
  ClearTexel out;
  const size_t bytes = img.texelBytes(), n = size_t(img.width) * img.height;
  if (!bytes || img.data.size() < bytes * n) return out;
  std::map<std::vector<uint8_t>, size_t> counts;
  const size_t step = std::max<size_t>(1, n / 20000);
  size_t seen = 0;
  for (size_t i = 0; i < n; i += step, ++seen)
    ++counts[std::vector<uint8_t>(img.data.begin() + long(i * bytes), img.data.begin() + long((i + 1) * bytes))];
  auto best = std::max_element(counts.begin(), counts.end(), [](auto& a, auto& b) { return a.second < b.second; });
  out.bytes = best->first;
  out.fraction = double(best->second) / double(seen);
  return out;
}

namespace {

// A texel that looks like a clear value: every channel 0, or a single channel at "infinity" (an eye
// depth's 1e10, a float's inf): not a surface's own value (a big floor's normal, albedo or material
// index is often the most common texel of its target, and is no clear value).
bool clearLike(const CpuImage& img, const std::vector<uint8_t>& bytes) {
  CpuImage one = img;
  one.width = one.height = 1;
  one.data = bytes;
  bool zero = true;
  for (uint32_t c = 0; c < img.channelCount(); ++c) zero = zero && one.value(0, 0, c) == 0.0;
  if (zero) return true;
  const double v = one.value(0, 0, 0);
  return img.channelCount() == 1 && (!std::isfinite(v) || std::abs(v) >= 1e9);
}

}  // namespace

SurfaceMask maskFromClearTexels(const std::vector<const CpuImage*>& images) {
  SurfaceMask m;
  std::vector<std::pair<const CpuImage*, ClearTexel>> cleared;
  for (const CpuImage* img : images) {
    if (!img || img->empty()) continue;
    ClearTexel c = commonTexel(*img);
    if (c.fraction > 0.02 && c.fraction < 0.98 && clearLike(*img, c.bytes)) cleared.emplace_back(img, std::move(c));
  }
  if (cleared.empty()) return m;
  m.width = cleared[0].first->width, m.height = cleared[0].first->height;
  m.at.assign(size_t(m.width) * m.height, 0);
  for (auto& [img, c] : cleared) {
    if (img->width != m.width || img->height != m.height) continue;
    const size_t bytes = img->texelBytes();
    for (size_t i = 0; i < m.at.size(); ++i)
      if (std::memcmp(img->data.data() + i * bytes, c.bytes.data(), bytes) != 0) m.at[i] = 1;
  }
  m.from = "texels that differ from the clear value of " + std::to_string(cleared.size()) + " target(s)";
  return m;
}

std::vector<glm::uvec2> samplePixels(const SurfaceMask& s, uint32_t w, uint32_t h, size_t wanted) {
  std::vector<glm::uvec2> all;
  for (uint32_t y = 2; y + 2 < h; ++y)
    for (uint32_t x = 2; x + 2 < w; ++x)
      if (s.surface(x, y)) all.push_back({x, y});
  if (all.size() <= wanted) return all;
  std::vector<glm::uvec2> out;
  const double step = double(all.size()) / double(wanted);
  for (double i = 0.0; size_t(i) < all.size(); i += step) out.push_back(all[size_t(i)]);
  return out;
}

}  // namespace gb
