// Compare masks (compare.h, CompareMask): silhouettes from primitive_id, the shadow penumbra band
// from the stored shadow term, a user's mask image (Filament's imagediff masks; Skia Gold's edge
// filters), and the mask as an image. compare() decides over the unmasked pixels.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "renderer/core/decode.h"
#include "views/analysis/compare.h"

namespace gb {

namespace {

enum : uint8_t { kSilhouette = 1, kPenumbra = 2, kFile = 4 };

// Marks pixels where `value` differs from a 4-neighbour's (and `inside` ones) in the frame.
template <class Value, class Inside>
void markEdges(const FrameSnapshot& f, CompareMask& m, uint8_t bit, Value value, Inside inside) {
  for (uint32_t y = 0; y < m.height; ++y)
    for (uint32_t x = 0; x < m.width; ++x) {
      const double v = value(x, y);
      bool edge = inside(v);
      for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int nx = int(x) + dx, ny = int(y) + dy;
        if (nx >= 0 && ny >= 0 && nx < int(m.width) && ny < int(m.height)) edge |= value(uint32_t(nx), uint32_t(ny)) != v;
      }
      if (edge) m.bits[size_t(y) * m.width + x] |= bit;
    }
  (void)f;
}

bool silhouettes(const Capture& c, CompareMask& m) {
  const Quantity* id = c.frame.layout.find(QuantityKind::Id);
  if (!id || !layoutImage(c.frame, id->target) || layoutImage(c.frame, id->target)->targetWidth != m.width) return false;
  markEdges(c.frame, m, kSilhouette, [&](uint32_t x, uint32_t y) { return double(decodeInteger(c.frame, *id, x, y)); },
            [](double) { return false; });
  return true;
}

bool penumbra(const Capture& c, CompareMask& m) {
  const Quantity* shadow = c.frame.layout.find(QuantityKind::Shadow);
  if (!shadow || !layoutImage(c.frame, shadow->target)) return false;
  CompareMask band = m;
  std::fill(band.bits.begin(), band.bits.end(), 0);
  markEdges(c.frame, band, kPenumbra, [&](uint32_t x, uint32_t y) { return decodeScalar(c.frame, *shadow, x, y); },
            [](double v) { return v > 0.0 && v < 1.0; });
  // Grown by a pixel: the shadow edge's neighbours on both sides.
  for (uint32_t y = 0; y < m.height; ++y)
    for (uint32_t x = 0; x < m.width; ++x)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = int(x) + dx, ny = int(y) + dy;
          if (nx >= 0 && ny >= 0 && nx < int(m.width) && ny < int(m.height) && band.bits[size_t(ny) * m.width + nx])
            m.bits[size_t(y) * m.width + x] |= kPenumbra;
        }
  return true;
}

bool maskFile(const std::string& path, CompareMask& m, std::string& error) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // a PNG's colour as stored, whatever its alpha
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) {
    error = "--mask " + path + ": cannot read it as an image (" + OIIO::geterror() + ")";
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (uint32_t(spec.width) != m.width || uint32_t(spec.height) != m.height) {
    error = "--mask " + path + ": " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
            ", the captures are " + std::to_string(m.width) + "x" + std::to_string(m.height);
    return false;
  }
  std::vector<float> px(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data())) {
    error = "--mask " + path + ": " + in->geterror();
    return false;
  }
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i)
    for (int c = 0; c < std::min(spec.nchannels, 3); ++c)
      if (px[i * spec.nchannels + c] != 0.0f) m.bits[i] |= kFile;
  return true;
}

}  // namespace

bool buildCompareMask(const Capture& a, const Capture& b, const std::string& spec, CompareMask& m, std::string& error) {
  m.width = a.frame.camera.width;
  m.height = a.frame.camera.height;
  m.bits.assign(size_t(m.width) * m.height, 0);
  std::stringstream parts(spec);
  for (std::string part; std::getline(parts, part, ',');) {
    if (part.empty()) continue;
    m.parts.push_back(part);
    if (part == "silhouettes") {
      const bool any = silhouettes(a, m) | silhouettes(b, m);
      if (!any) {
        error = "--mask silhouettes: neither capture has an id target of the frame's size (gblens capture --primitive-id on)";
        return false;
      }
    } else if (part == "penumbra") {
      const bool any = penumbra(a, m) | penumbra(b, m);
      if (!any) {
        error = "--mask penumbra: neither capture stores a shadow term";
        return false;
      }
    } else if (!maskFile(part, m, error)) {
      return false;
    }
  }
  return true;
}

uint64_t CompareMask::count() const {
  return uint64_t(std::count_if(bits.begin(), bits.end(), [](uint8_t b) { return b != 0; }));
}

Rgba8Image maskImage(const CompareMask& m) {
  Rgba8Image img{m.width, m.height, std::vector<uint8_t>(size_t(m.width) * m.height * 4, 0)};
  for (size_t i = 0; i < m.bits.size(); ++i) {
    uint8_t* p = &img.pixels[i * 4];
    p[0] = m.bits[i] & kSilhouette ? 255 : 0;
    p[1] = m.bits[i] & kPenumbra ? 255 : 0;
    p[2] = m.bits[i] & kFile ? 255 : 0;
    p[3] = 255;
  }
  return img;
}

}  // namespace gb
