// Lossless EXR I/O of CpuImages through OpenImageIO (per-channel formats, ZIP compression).
#include "views/capture/exr.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>

#include "renderer/core/assert.h"

namespace gb {

static bool integerStored(PixelType t) {
  return t == PixelType::U8 || t == PixelType::I8 || t == PixelType::U16 || t == PixelType::I16;
}

std::vector<ExrChannel> exrChannels(const CpuImage& img) {
  std::vector<ExrChannel> out;
  for (uint32_t c = 0; c < img.channelCount(); ++c) {
    std::string base = img.name + "." + img.channels[c];
    if (integerStored(img.type)) {
      out.push_back({base, "float", int(c), false});
      out.push_back({img.name + ".raw." + img.channels[c], "uint", int(c), true});
    } else if (img.type == PixelType::F16) {
      out.push_back({base, "half", int(c), true});
    } else if (img.type == PixelType::U32 || img.channels[c] == "Stencil") {
      out.push_back({base, "uint", int(c), img.type == PixelType::U32});
    } else {
      out.push_back({base, "float", int(c), true});
    }
  }
  return out;
}

static OIIO::TypeDesc typeOf(const std::string& t) {
  return t == "uint" ? OIIO::TypeDesc::UINT32 : t == "half" ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
}

// The file's header: one channel per ExrChannel in its format, ZIP, no time stamp, and the
// target's name, type and encoding as attributes. `pixelBytes`: one interleaved pixel.
static OIIO::ImageSpec exrSpec(const CpuImage& img, const std::vector<ExrChannel>& chans, size_t& pixelBytes) {
  OIIO::ImageSpec spec(int(img.width), int(img.height), int(chans.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames.clear();
  spec.channelformats.clear();
  pixelBytes = 0;
  for (const ExrChannel& ch : chans) {
    spec.channelnames.push_back(ch.name);
    spec.channelformats.push_back(typeOf(ch.type));
    pixelBytes += typeOf(ch.type).size();
  }
  spec.alpha_channel = -1;  // "A" of hdr/final is data here, never premultiplied
  spec.attribute("compression", "zip");
  // No time stamp (OpenImageIO adds one unless given): the same frame gives the same bytes,
  // so two captures' file digests can be compared directly. The manifest has the time.
  spec.attribute("DateTime", "");
  spec.attribute("gblens:target", img.name);
  spec.attribute("gblens:type", name(img.type));
  spec.attribute("gblens:encoding", name(img.encoding));
  return spec;
}

// How each file channel is written: half bits, raw bits, a float stencil as uint, or the
// decoded value (of an 8-bit channel from a table: sRGB decoding per texel is slow).
namespace {
enum class PlanKind { Half, Bits, StencilUint, Decoded, Decoded8 };
struct ChannelPlan {
  PlanKind kind;
  uint32_t c;
  std::vector<float> table;
};
}  // namespace

static std::vector<ChannelPlan> channelPlans(const CpuImage& img, const std::vector<ExrChannel>& chans) {
  std::vector<ChannelPlan> plans;
  for (const ExrChannel& ch : chans) {
    ChannelPlan p{ch.type == "half" ? PlanKind::Half
                  : ch.raw          ? PlanKind::Bits
                  : ch.type == "uint" ? PlanKind::StencilUint
                                      : PlanKind::Decoded,
                  uint32_t(ch.source), {}};
    if (p.kind == PlanKind::Decoded && pixelTypeSize(img.type) == 1) {
      CpuImage one = img;  // one texel of the same description
      one.width = one.height = 1;
      one.data.assign(img.texelBytes(), 0);
      for (uint32_t v = 0; v < 256; ++v) {
        one.data[p.c] = uint8_t(v);
        p.table.push_back(float(one.value(0, 0, p.c)));
      }
      p.kind = PlanKind::Decoded8;
    }
    plans.push_back(std::move(p));
  }
  return plans;
}

// The channels interleaved in their file formats, pixel by pixel, channel by channel.
static std::vector<uint8_t> interleave(const CpuImage& img, const std::vector<ChannelPlan>& plans, size_t pixelBytes) {
  std::vector<uint8_t> buf(pixelBytes * img.width * img.height);
  uint8_t* p = buf.data();
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x)
      for (const ChannelPlan& pl : plans) {
        uint32_t bits = 0;
        switch (pl.kind) {
          case PlanKind::Half: {
            uint16_t h = uint16_t(img.raw(x, y, pl.c));
            std::memcpy(p, &h, 2);
            p += 2;
            continue;
          }
          case PlanKind::Bits: bits = img.raw(x, y, pl.c); break;  // F32 bits, U32, or the 8/16-bit integer
          case PlanKind::StencilUint: {                            // read back as float
            double v = img.value(x, y, pl.c);
            GB_ASSERT(v >= 0.0 && v <= 4294967295.0 && v == std::floor(v));
            bits = uint32_t(v);
            break;
          }
          case PlanKind::Decoded:
          case PlanKind::Decoded8: {
            float f = pl.kind == PlanKind::Decoded8 ? pl.table[img.raw(x, y, pl.c)] : float(img.value(x, y, pl.c));
            std::memcpy(&bits, &f, 4);
            break;
          }
        }
        std::memcpy(p, &bits, 4);
        p += 4;
      }
  return buf;
}

bool writeExr(const std::string& path, const CpuImage& img, std::string& error) {
  std::vector<ExrChannel> chans = exrChannels(img);
  size_t pixelBytes = 0;
  OIIO::ImageSpec spec = exrSpec(img, chans, pixelBytes);
  std::vector<uint8_t> buf = interleave(img, channelPlans(img, chans), pixelBytes);
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) {
    error = path + ": no OpenEXR writer (" + OIIO::geterror() + ")";
    return false;
  }
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UNKNOWN, buf.data()) || !out->close()) {
    error = path + ": cannot write EXR (" + out->geterror() + ")";
    return false;
  }
  return true;
}

// Where each expected channel is in the file (index[k] for chans[k]); false with a message when
// one is missing or of another type.
static bool findChannels(const std::string& path, const OIIO::ImageSpec& spec, const std::vector<ExrChannel>& chans,
                         std::vector<int>& index, std::string& error) {
  index.assign(chans.size(), -1);
  for (size_t k = 0; k < chans.size(); ++k) {
    const ExrChannel& ch = chans[k];
    for (int i = 0; i < spec.nchannels; ++i)
      if (spec.channelnames[size_t(i)] == ch.name) index[k] = i;
    if (index[k] < 0) {
      error = path + ": channel " + ch.name + " is missing";
      return false;
    }
    if (spec.channelformat(index[k]) != typeOf(ch.type)) {
      error = path + ": channel " + ch.name + " is " + spec.channelformat(index[k]).c_str() + ", expected " + ch.type;
      return false;
    }
  }
  return true;
}

// One file channel (at `src`, every `stride` bytes) into its channel of img.data: raw values
// stored as they are (an 8/16-bit channel checked to fit), the stencil as float.
static bool storeChannel(const std::string& path, const ExrChannel& ch, const uint8_t* src, size_t stride, CpuImage& img,
                         std::string& error) {
  const size_t texels = size_t(img.width) * img.height, size = pixelTypeSize(img.type);
  for (size_t i = 0; i < texels; ++i, src += stride) {
    uint8_t* dst = img.data.data() + i * img.texelBytes() + size_t(ch.source) * size;
    uint32_t v = 0;
    if (ch.type == "half") {
      uint16_t h;
      std::memcpy(&h, src, 2);
      v = h;
    } else {
      std::memcpy(&v, src, 4);
    }
    if (!ch.raw) {  // Stencil: float in memory
      float f = float(v);
      std::memcpy(dst, &f, 4);
    } else if (size == 1) {
      if (v > 0xFF) {
        error = path + ": channel " + ch.name + " holds " + std::to_string(v) + ", not an 8-bit value";
        return false;
      }
      *dst = uint8_t(v);
    } else if (size == 2) {
      if (v > 0xFFFF) {
        error = path + ": channel " + ch.name + " holds " + std::to_string(v) + ", not a 16-bit value";
        return false;
      }
      uint16_t h = uint16_t(v);
      std::memcpy(dst, &h, 2);
    } else {
      std::memcpy(dst, &v, 4);
    }
  }
  return true;
}

bool readExr(const std::string& path, CpuImage& img, std::string& error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    error = path + ": not a readable EXR (" + OIIO::geterror() + ")";
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (uint32_t(spec.width) != img.width || uint32_t(spec.height) != img.height || spec.x != 0 || spec.y != 0) {
    error = path + ": size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
            ", the manifest says " + std::to_string(img.width) + "x" + std::to_string(img.height);
    return false;
  }
  std::vector<ExrChannel> chans = exrChannels(img);
  if (size_t(spec.nchannels) != chans.size()) {
    error = path + ": " + std::to_string(spec.nchannels) + " channels, expected " + std::to_string(chans.size());
    return false;
  }
  // Find every channel, check its type, then read the whole file once in its native formats.
  std::vector<size_t> offset(size_t(spec.nchannels), 0);
  size_t pixelBytes = 0;
  for (int i = 0; i < spec.nchannels; ++i) {
    offset[size_t(i)] = pixelBytes;
    pixelBytes += spec.channelformat(i).size();
  }
  std::vector<int> index;
  if (!findChannels(path, spec, chans, index, error)) return false;
  const size_t texels = size_t(img.width) * img.height;
  std::vector<uint8_t> buf(texels * pixelBytes);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, buf.data())) {
    error = path + ": cannot read pixels (" + in->geterror() + ")";
    return false;
  }
  img.data.assign(texels * img.texelBytes(), 0);
  for (size_t k = 0; k < chans.size(); ++k) {
    if (!chans[k].raw && chans[k].type == "float") continue;  // decoded convenience channel: the raw one is exact
    if (!storeChannel(path, chans[k], buf.data() + offset[size_t(index[k])], pixelBytes, img, error)) return false;
  }
  in->close();
  return true;
}

}  // namespace gb
