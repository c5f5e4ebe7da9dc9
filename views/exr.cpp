// Lossless EXR I/O of CpuImages through OpenImageIO (per-channel formats, ZIP compression).
#include "views/exr.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>

#include "renderer/vk/check.h"

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

bool writeExr(const std::string& path, const CpuImage& img, std::string& error) {
  std::vector<ExrChannel> chans = exrChannels(img);
  OIIO::ImageSpec spec(int(img.width), int(img.height), int(chans.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames.clear();
  spec.channelformats.clear();
  size_t pixelBytes = 0;
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

  // Interleave the channels in their file formats (pixel by pixel, channel by channel).
  std::vector<uint8_t> buf(pixelBytes * img.width * img.height);
  uint8_t* p = buf.data();
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x)
      for (const ExrChannel& ch : chans) {
        uint32_t c = uint32_t(ch.source);
        if (ch.type == "half") {
          uint16_t h = uint16_t(img.raw(x, y, c));
          std::memcpy(p, &h, 2);
          p += 2;
          continue;
        }
        uint32_t bits;
        if (ch.raw) {
          bits = img.raw(x, y, c);  // F32 bits, U32 value, or the stored 8/16-bit integer
        } else if (ch.type == "uint") {  // Stencil read back as float
          double v = img.value(x, y, c);
          GB_ASSERT(v >= 0.0 && v <= 4294967295.0 && v == std::floor(v));
          bits = uint32_t(v);
        } else {  // decoded value of an integer-stored channel
          float f = float(img.value(x, y, c));
          std::memcpy(&bits, &f, 4);
        }
        std::memcpy(p, &bits, 4);
        p += 4;
      }

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
  img.data.assign(size_t(img.width) * img.height * img.texelBytes(), 0);
  const size_t texels = size_t(img.width) * img.height, size = pixelTypeSize(img.type);
  std::vector<uint32_t> buf(texels);
  for (const ExrChannel& ch : chans) {
    int index = -1;
    for (int i = 0; i < spec.nchannels; ++i)
      if (spec.channelnames[size_t(i)] == ch.name) index = i;
    if (index < 0) {
      error = path + ": channel " + ch.name + " is missing";
      return false;
    }
    if (spec.channelformat(index) != typeOf(ch.type)) {
      error = path + ": channel " + ch.name + " is " + spec.channelformat(index).c_str() + ", expected " + ch.type;
      return false;
    }
    if (!ch.raw && ch.type == "float") continue;  // decoded convenience channel: the raw one is exact
    if (!in->read_image(0, 0, index, index + 1, typeOf(ch.type), buf.data())) {
      error = path + ": cannot read channel " + ch.name + " (" + in->geterror() + ")";
      return false;
    }
    const uint16_t* halves = reinterpret_cast<const uint16_t*>(buf.data());
    for (size_t i = 0; i < texels; ++i) {
      uint8_t* dst = img.data.data() + i * img.texelBytes() + size_t(ch.source) * size;
      uint32_t v = ch.type == "half" ? halves[i] : buf[i];
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
  }
  in->close();
  return true;
}

}  // namespace gb
