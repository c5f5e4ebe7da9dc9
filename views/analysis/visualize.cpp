// A view's decoded values and their CPU mapping (see visualize.h); the shader mirrors mapTexel.
#include "views/analysis/visualize.h"
#include "views/analysis/sample_views.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "renderer/core/assert.h"
#include "renderer/core/decode.h"
#include "shaders/view_colors.h"
#include "renderer/core/parallel_rows.h"

namespace gb {

using namespace gpu;

ViewSettings defaultSettings(const ViewDef& d) {
  ViewSettings s;
  s.channels = d.channels;
  s.autoRange = d.autoRange;
  s.falseColor = d.falseColor;
  s.black = d.black;
  s.white = d.white;
  return s;
}

std::optional<std::array<double, 4>> viewValue(const FrameSnapshot& f, const ViewDef& view, uint32_t x, uint32_t y) {
  if (view.spreadOf >= 0) return sampleSpread(f, uint32_t(view.spreadOf), x, y);
  GB_ASSERT(view.quantity >= 0 && size_t(view.quantity) < f.layout.quantities.size());
  const Quantity& q = f.layout.quantities[size_t(view.quantity)];
  if (!holds(f, q, x, y)) return std::nullopt;
  std::array<double, 4> out{};
  switch (view.visual) {
    case Visual::Color: {
      glm::dvec4 c = decodeColor(f, q, x, y);
      out = {c.r, c.g, c.b, q.channels.size() > 3 ? c.a : 1.0};
      break;
    }
    case Visual::Scalar: out[0] = decodeScalar(f, q, x, y); break;
    case Visual::Vector: {
      std::array<double, 4> s = storedValues(f, q, x, y);
      for (size_t k = 0; k < q.channels.size() && k < 4; ++k) out[k] = s[k] * q.scale + q.bias;
      break;
    }
    case Visual::Normal: {
      if (!hasSurface(f, x, y)) return std::nullopt;
      NormalSample n = decodeNormal(f, q, x, y);
      double length = glm::length(n.stored);
      glm::dvec3 u = length > 0.0 && std::isfinite(length) ? n.stored / length : glm::dvec3(0.0);
      out = {u.x, u.y, u.z, length};
      break;
    }
    case Visual::Depth: {
      if (!q.ofSun && !decodeEyeDepth(f, q, x, y)) return std::nullopt;  // nothing drawn
      double s = storedValues(f, q, x, y)[0];
      if (q.ofSun && q.background && s == *q.background) return std::nullopt;  // the shadow map's clear value
      out[0] = q.ofSun || q.depth == DepthEncoding::Hardware ? s : s * q.scale + q.bias;
      break;
    }
    case Visual::Position: {
      if (!hasSurface(f, x, y)) return std::nullopt;
      std::optional<glm::dvec3> e = decodePosition(f, q, x, y);
      if (!e) return std::nullopt;
      glm::dvec3 p = spaceFromEye(f, q.space, *e, true);
      out = {p.x, p.y, p.z, glm::length(*e)};
      break;
    }
    case Visual::Motion: {
      glm::dvec2 m = decodeMotion(f, q, x, y);
      out = {m.x, m.y, 0.0, 0.0};
      break;
    }
    case Visual::Id:
    case Visual::Stencil:
    case Visual::Count: out[0] = decodeInteger(f, q, x, y); break;
  }
  return out;
}

CpuImage decodedViewImage(const std::string& name, uint32_t width, uint32_t height, bool integer) {
  CpuImage out;
  out.width = width;
  out.height = height;
  out.name = name;
  out.type = integer ? PixelType::U32 : PixelType::F32;
  out.encoding = integer ? Encoding::Uint : Encoding::Float;
  out.channels = integer ? std::vector<std::string>{name} : std::vector<std::string>{"0", "1", "2", "3"};
  out.data.assign(size_t(width) * height * out.texelBytes(), 0);
  return out;
}

CpuImage viewImage(const FrameSnapshot& f, const ViewDef& view) {
  const TargetImage* ti = layoutImage(f, view.target);
  if (!ti || !ti->present()) return {};
  CpuImage out = decodedViewImage(view.name, ti->image.width, ti->image.height, view.integer);
  const uint32_t n = out.channelCount();
  // Every texel is a function of the read-only frame alone: rows on every core (a stream's frame is
  // decoded while the viewer waits to show it).
  parallelRows(out.height, size_t(out.width) * out.height, [&](uint32_t y0, uint32_t y1) {
    for (uint32_t y = y0; y < y1; ++y)
      for (uint32_t x = 0; x < out.width; ++x) {
        std::optional<std::array<double, 4>> v = viewValue(f, view, ti->x0 + x, ti->y0 + y);
        uint8_t* p = out.data.data() + (size_t(y) * out.width + x) * out.texelBytes();
        for (uint32_t c = 0; c < n; ++c) {
          uint32_t bits = kEmptyTexel;
          if (v && view.integer) {
            bits = uint32_t((*v)[c]);
          } else if (v) {
            float value = float((*v)[c]);
            std::memcpy(&bits, &value, 4);
            if (std::isnan(value)) bits = 0x7FC00000u;  // never the empty texel's payload
          }
          std::memcpy(p + 4 * c, &bits, 4);
        }
      }
  });
  return out;
}

ViewMapping viewMapping(const ViewDef& view, const ViewSettings& s) {
  ViewMapping m;
  const uint32_t available = view.visual == Visual::Normal || view.visual == Visual::Position ? 0x7u : (1u << view.components) - 1;
  m.mask = s.channels & available;
  if (!m.mask) m.mask = view.channels;
  switch (view.visual) {
    case Visual::Color:
    case Visual::Position:
    case Visual::Vector:
      m.mapping = kViewMapColor;
      if (view.visual == Visual::Color && (m.mask & 0x7u)) m.flags |= kViewFlagSrgb;
      if (view.visual == Visual::Position && s.distance) m.mapping = kViewMapGrey, m.mask = 0x8;
      break;
    case Visual::Normal: m.mapping = kViewMapNormal; break;
    case Visual::Depth: m.mapping = kViewMapDepth; break;
    case Visual::Scalar: m.mapping = kViewMapGrey; break;
    case Visual::Id: m.mapping = kViewMapId; break;
    case Visual::Stencil: m.mapping = kViewMapStencil; break;
    case Visual::Motion: m.mapping = kViewMapMotion, m.mask = 0x3; break;
    case Visual::Count: m.mapping = kViewMapHeat; break;
  }
  // One component of a colour or normal: grey (as RenderDoc shows one channel); alpha alongside colour
  // components is not displayable as colour: the colour components.
  if ((m.mapping == kViewMapColor || m.mapping == kViewMapNormal) && std::popcount(m.mask) == 1) {
    m.mapping = kViewMapGrey;
    m.flags &= ~kViewFlagSrgb;
  }
  if (m.mapping == kViewMapColor || m.mapping == kViewMapNormal) m.mask &= (std::popcount(m.mask & 0x7u) ? 0x7u : 0xFu);
  if (m.mapping == kViewMapGrey || m.mapping == kViewMapDepth) {
    if (s.falseColor) m.flags |= kViewFlagFalseColor;
    if (s.log) m.flags |= kViewFlagLog;
  }
  return m;
}

RangeStats imageRange(const CpuImage& img, const ViewDef& view, uint32_t mask) {
  RangeStats r;
  double lo = 1e300, hi = -1e300;
  auto add = [&](double v) {
    if (std::isnan(v)) return void(++r.nan);
    if (std::isinf(v)) return void(++r.inf);
    ++r.count;
    if (v < 0.0) ++r.negative;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      if (img.raw(x, y, 0) == kEmptyTexel && img.type == PixelType::F32) continue;
      if (view.visual == Visual::Motion) {
        add(std::hypot(img.value(x, y, 0), img.value(x, y, 1)));
        continue;
      }
      for (uint32_t c = 0; c < img.channelCount(); ++c)
        if (mask & (1u << c)) add(img.value(x, y, c));
    }
  if (r.count) r.lo = lo, r.hi = hi;
  return r;
}

ResolvedRange resolveRange(const ViewDef& view, const ViewSettings& s, const std::vector<RangeStats>* stats) {
  ResolvedRange r;
  r.black = s.black;
  r.white = s.white;
  if (!s.autoRange || !stats || stats->empty()) return r;
  RangeStats all;
  double lo = 1e300, hi = -1e300;
  for (const RangeStats& st : *stats) {
    all.count += st.count;
    all.nan += st.nan;
    all.inf += st.inf;
    all.negative += st.negative;
    if (st.count) lo = std::min(lo, st.lo), hi = std::max(hi, st.hi);
  }
  if (all.count) all.lo = lo, all.hi = hi;
  r.stats = all;
  if (!all.count) return r;
  r.fromData = true;
  if (view.visual == Visual::Count || view.visual == Visual::Motion) {  // 0 .. the largest (a count: at least 1)
    r.black = 0.0f;
    r.white = float(view.visual == Visual::Count ? std::max(hi, 1.0) : (hi > 0.0 ? hi : 1.0));
  } else {
    r.black = float(lo);
    r.white = float(hi > lo ? hi : lo + 1.0);  // a constant image: any non-empty span
  }
  return r;
}

static float rangePlace(float x, float lo, float hi, uint32_t flags) {
  if ((flags & kViewFlagLog) && lo > 0.0f && hi > lo && x > 0.0f) return std::log(x / lo) / std::log(hi / lo);
  return (x - lo) / (hi != lo ? hi - lo : 1.0f);
}

glm::vec3 mapTexel(const ViewDef&, const ViewSettings& s, const ViewMapping& m, const ResolvedRange& r,
                   const std::array<float, 4>& v, bool empty) {
  if (empty) return glm::vec3(0.0f);
  const float lo = r.black, hi = r.white, span = hi != lo ? hi - lo : 1.0f;
  const int first = std::countr_zero(m.mask | 0x10u);
  const float x = v[size_t(std::min(first, 3))];
  glm::vec3 d(0.0f);
  switch (m.mapping) {
    case kViewMapNormal:
    case kViewMapColor: {
      const float gain = m.mapping == kViewMapColor ? std::exp2(s.exposure) : 1.0f;
      for (int c = 0; c < 3; ++c) d[c] = (m.mask & (1u << c)) ? (v[size_t(c)] * gain - lo) / span : 0.0f;
      break;
    }
    case kViewMapGrey: {
      float place = rangePlace(x, lo, hi, m.flags);
      d = (m.flags & kViewFlagFalseColor) ? colors::viridis(place) : glm::vec3(place);
      break;
    }
    case kViewMapDepth: {
      float place = std::clamp(rangePlace(x, lo, hi, m.flags), 0.0f, 1.0f);
      d = (m.flags & kViewFlagFalseColor) ? colors::viridis(1.0f - place) : glm::vec3(1.0f - 0.9f * place);
      break;
    }
    case kViewMapId: d = colors::idColor(uint32_t(x)); break;
    case kViewMapStencil: d = colors::stencilColor(s.stencilBits ? uint32_t(x) & s.stencilBits : uint32_t(x)); break;
    case kViewMapMotion: d = colors::motionColor(glm::vec2(v[0], v[1]), hi); break;
    default: d = colors::heatColor(x / std::max(hi, 1.0f)); break;
  }
  return glm::clamp(d, 0.0f, 1.0f);
}

static uint8_t displayByte(float v, bool srgb) {
  v = std::clamp(v, 0.0f, 1.0f);
  if (srgb) v = v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(v * 255.0f));
}

Rgba8Image visualize(const FrameSnapshot& f, const ViewDef& view, const ViewSettings& s) {
  Rgba8Image out;
  CpuImage img = viewImage(f, view);
  if (img.empty()) return out;
  const ViewMapping m = viewMapping(view, s);
  std::vector<RangeStats> stats = {imageRange(img, view, m.mask)};
  const ResolvedRange r = resolveRange(view, s, &stats);
  out.width = img.width;
  out.height = img.height;
  out.pixels.assign(size_t(out.width) * out.height * 4, 255);
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      std::array<float, 4> v{};
      for (uint32_t c = 0; c < img.channelCount(); ++c) v[c] = float(img.value(x, y, c));
      const bool empty = !view.integer && img.raw(x, y, 0) == kEmptyTexel;
      glm::vec3 d = mapTexel(view, s, m, r, v, empty);
      uint8_t* p = &out.pixels[(size_t(y) * out.width + x) * 4];
      for (int c = 0; c < 3; ++c) p[c] = displayByte(d[c], m.flags & kViewFlagSrgb);
    }
  return out;
}

void heatColor(double count, double max, uint8_t out[3]) {
  glm::vec3 c = colors::heatColor(float(count / std::max(max, 1.0)));
  for (int i = 0; i < 3; ++i) out[i] = uint8_t(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255.0f));
}

}  // namespace gb
