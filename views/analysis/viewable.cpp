// Any layout's quantities decoded into gblens's own targets, for the views (viewable.h).
#include "views/analysis/viewable.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "renderer/core/assert.h"
#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"

namespace gb {

bool nativeFrame(const FrameSnapshot& f) { return f.layout.name == nativeLayout(f.options).name; }

namespace {

// Stores a decoded value as the image's type and encoding say (the inverse of CpuImage::value).
void store(CpuImage& img, uint32_t x, uint32_t y, uint32_t c, double v) {
  uint8_t* p = img.data.data() + (size_t(y) * img.width + x) * img.texelBytes() + c * pixelTypeSize(img.type);
  switch (img.type) {
    case PixelType::F16: {
      uint16_t h = floatToHalf(float(v));
      std::memcpy(p, &h, 2);
      return;
    }
    case PixelType::F32: {
      float f = float(v);
      std::memcpy(p, &f, 4);
      return;
    }
    case PixelType::U8: {
      if (img.encoding == Encoding::Srgb && c < 3) {
        v = std::clamp(v, 0.0, 1.0);
        v = v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
      }
      *p = img.encoding == Encoding::Uint ? uint8_t(std::clamp(v, 0.0, 255.0))
                                          : uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
      return;
    }
    case PixelType::U32: {
      uint32_t u = img.encoding == Encoding::Unorm24 ? uint32_t(std::lround(std::clamp(v, 0.0, 1.0) * 16777215.0))
                                                     : uint32_t(std::max(v, 0.0));
      std::memcpy(p, &u, 4);
      return;
    }
    default: GB_ASSERT(!"viewable targets use half, float, 8-bit and 32-bit uint channels only");
  }
}

// The options whose gblens layout holds decoded quantities without losing much: float formats.
RenderOptions viewableOptions(const FrameSnapshot& f) {
  RenderOptions o;
  o.width = f.camera.width;
  o.height = f.camera.height;
  o.normalFormat = NormalFormat::Rgba16f;
  o.depthFormat = DepthFormat::D32S8;
  o.accumFormat = AccumFormat::Rgba32f;
  o.shadowFormat = ShadowFormat::D32f;
  o.position = PositionSource::Rgba32f;
  o.positionSpace = PositionSpace::World;
  o.reversedZ = f.camera.reversedZ;
  o.primitiveId = f.layout.find(QuantityKind::Id) != nullptr;
  o.coverage = false;
  o.sky = false;
  return o;
}

const Quantity* firstOf(const Layout& l, std::initializer_list<QuantityKind> kinds) {
  for (QuantityKind k : kinds)
    if (const Quantity* q = l.find(k)) return q;
  return nullptr;
}

// Fills one of gblens's targets pixel by pixel from `texel` (false: the pixel stays zero).
template <class F>
void fill(FrameSnapshot& out, Target t, F texel) {
  if (out.indexOf(t) < 0) return;  // gblens's layout has no such target under these options
  TargetImage& ti = out.target(t);
  ti.targetWidth = ti.image.width = out.camera.width;
  ti.targetHeight = ti.image.height = out.camera.height;
  ti.image.data.assign(size_t(ti.image.width) * ti.image.height * ti.image.texelBytes(), 0);
  double v[4];
  for (uint32_t y = 0; y < ti.image.height; ++y)
    for (uint32_t x = 0; x < ti.image.width; ++x) {
      v[0] = v[1] = v[2] = v[3] = 0.0;
      if (texel(x, y, v))
        for (uint32_t c = 0; c < ti.image.channelCount(); ++c) store(ti.image, x, y, c, v[c]);
    }
  out.setAbsence(t, Absent::No);
}

}  // namespace

FrameSnapshot viewableFrame(const FrameSnapshot& f) {
  if (nativeFrame(f)) return f;
  FrameSnapshot out;
  out.options = viewableOptions(f);
  out.camera = f.camera;
  out.sun = f.sun;
  out.sky = f.sky;
  out.setLayout(nativeLayout(out.options));
  for (size_t i = 0; i < out.absences.size(); ++i) out.absences[i] = Absent::NotInLayout;
  for (size_t i = 0; i < out.images.size(); ++i) describeImage(out.layout.targets[i], out.images[i].image);
  const Layout& l = f.layout;
  auto has = [&](const Quantity* q, uint32_t x, uint32_t y) { return q && holds(f, *q, x, y); };

  const Quantity* albedo = firstOf(l, {QuantityKind::Albedo, QuantityKind::BaseColor});
  const Quantity* specular = firstOf(l, {QuantityKind::Specular, QuantityKind::Metallic});
  if (albedo || specular)
    fill(out, Target::AlbedoSpecular, [&](uint32_t x, uint32_t y, double* v) {
      if (has(albedo, x, y)) {
        glm::dvec4 c = decodeColor(f, *albedo, x, y);
        v[0] = c.r, v[1] = c.g, v[2] = c.b;
      }
      if (has(specular, x, y)) v[3] = decodeScalar(f, *specular, x, y);
      return true;
    });
  const Quantity* normal = l.find(QuantityKind::Normal);
  const Quantity* shadow = l.find(QuantityKind::Shadow);
  if (normal || shadow)
    fill(out, Target::NormalShadow, [&](uint32_t x, uint32_t y, double* v) {
      if (!hasSurface(f, x, y)) return false;
      if (has(normal, x, y)) {
        glm::dvec3 n = decodeNormal(f, *normal, x, y).unit;
        v[0] = n.x, v[1] = n.y, v[2] = n.z;
      }
      v[3] = has(shadow, x, y) ? decodeScalar(f, *shadow, x, y) : 1.0;
      return true;
    });
  const Quantity* depth = surfaceDepth(l);
  if (depth) {
    auto eyeDepth = [&](uint32_t x, uint32_t y) { return has(depth, x, y) ? decodeEyeDepth(f, *depth, x, y) : std::nullopt; };
    fill(out, Target::Depth, [&](uint32_t x, uint32_t y, double* v) {
      std::optional<double> z = eyeDepth(x, y);
      if (z) v[0] = *z;
      return z.has_value();
    });
    const Quantity* stencil = l.find(QuantityKind::Stencil);
    fill(out, Target::DepthStencil, [&](uint32_t x, uint32_t y, double* v) {
      std::optional<double> z = eyeDepth(x, y);
      v[0] = z ? hardwareDepth(f.camera, eyeFromEyeDepth(f.camera, x, y, *z)) : (f.camera.reversedZ ? 0.0 : 1.0);
      v[1] = has(stencil, x, y) ? decodeInteger(f, *stencil, x, y) : 0.0;
      return true;
    });
  }
  const Quantity* position = l.find(QuantityKind::Position);
  if (position || depth)
    fill(out, Target::Position, [&](uint32_t x, uint32_t y, double* v) {
      const Quantity* q = has(position, x, y) ? position : depth;
      if (!has(q, x, y)) return false;
      std::optional<glm::dvec3> e = decodePosition(f, *q, x, y);
      if (!e) return false;
      glm::dvec3 w = glm::dvec3(f.camera.worldFromEye * glm::dvec4(*e, 1.0));
      v[0] = w.x, v[1] = w.y, v[2] = w.z, v[3] = 1.0;
      return true;
    });
  for (auto [target, kind] : {std::pair{Target::Hdr, QuantityKind::Radiance}, {Target::Final, QuantityKind::Display}})
    if (const Quantity* q = l.find(kind))
      fill(out, target, [&](uint32_t x, uint32_t y, double* v) {
        if (!has(q, x, y)) return false;
        glm::dvec4 c = decodeColor(f, *q, x, y);
        v[0] = c.r, v[1] = c.g, v[2] = c.b, v[3] = q->channels.size() > 3 ? c.a : 1.0;
        return true;
      });
  if (const Quantity* id = l.find(QuantityKind::Id))
    fill(out, Target::PrimitiveId, [&](uint32_t x, uint32_t y, double* v) {
      if (!has(id, x, y)) return false;
      v[0] = decodeInteger(f, *id, x, y);
      return true;
    });
  return out;
}

}  // namespace gb
