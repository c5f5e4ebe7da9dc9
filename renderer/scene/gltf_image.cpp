// Image decoding through OpenImageIO (PNG, JPEG: the formats core glTF allows), from memory,
// one worker per core. Sizes are checked from the header before the pixels are allocated.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <thread>

#include "renderer/core/library_output.h"
#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

struct Encoded {
  const uint8_t* data = nullptr;
  size_t size = 0;
};

Encoded encodedBytes(const Doc& doc, const tinygltf::Image& img) {
  if (img.bufferView >= 0) {
    const tinygltf::BufferView& v = doc.model.bufferViews[size_t(img.bufferView)];
    return {doc.model.buffers[size_t(v.buffer)].data.data() + v.byteOffset, v.byteLength};
  }
  return {img.image.data(), img.image.size()};
}

// Decodes one image; returns an error message, or "" on success.
std::string decodeOne(Encoded bytes, DecodedImage& out, std::atomic<uint64_t>& texelBudget) {
  static const uint8_t png[4] = {0x89, 'P', 'N', 'G'}, jpeg[3] = {0xFF, 0xD8, 0xFF};
  const char* name = nullptr;
  if (bytes.size >= 4 && std::memcmp(bytes.data, png, 4) == 0) name = "image.png";
  if (bytes.size >= 3 && std::memcmp(bytes.data, jpeg, 3) == 0) name = "image.jpg";
  if (!name) return "not a PNG or JPEG image (the formats glTF allows)";

  OIIO::Filesystem::IOMemReader proxy(bytes.data, bytes.size);
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // glTF colour is not premultiplied
  void* proxyPointer = &proxy;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxyPointer);
  auto in = OIIO::ImageInput::create(name, false, &config, &proxy);
  if (!in) return "cannot decode: " + OIIO::geterror();
  OIIO::ImageSpec spec;
  if (!in->open(name, spec, config)) {
    std::string e = in->geterror();  // retrieved, so OpenImageIO does not print it again
    return "cannot decode: " + (e.empty() ? std::string("unreadable header") : e);
  }
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return "cannot decode: empty image";
  if (uint32_t(spec.width) > kMaxTextureSide || uint32_t(spec.height) > kMaxTextureSide)
    return std::to_string(spec.width) + "x" + std::to_string(spec.height) + " is larger than " +
           std::to_string(kMaxTextureSide) + " on a side";
  uint64_t texels = uint64_t(spec.width) * uint64_t(spec.height);
  uint64_t left = texelBudget.load();
  do {
    if (left < texels) return "the file's textures together exceed " + std::to_string(kMaxTexels >> 20) + "M texels";
  } while (!texelBudget.compare_exchange_weak(left, left - texels));

  out.width = uint32_t(spec.width);
  out.height = uint32_t(spec.height);
  out.rgba8.assign(texels * 4, 255);
  int channels = std::min(spec.nchannels, 4);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, out.rgba8.data(), 4)) {
    std::string e = in->geterror();
    out = DecodedImage{};
    return "cannot decode: " + (e.empty() ? std::string("corrupt data") : e);
  }
  if (channels <= 2) {  // grey (+ alpha): replicate grey into g and b, move alpha to a
    for (uint64_t i = 0; i < texels; ++i) {
      uint8_t* p = &out.rgba8[i * 4];
      uint8_t a = channels == 2 ? p[1] : 255;
      p[1] = p[2] = p[0];
      p[3] = a;
    }
  }
  return {};
}

}  // namespace

std::vector<DecodedImage> decodeImages(const Doc& doc, const std::vector<bool>& needed) {
  const auto& images = doc.model.images;
  std::vector<DecodedImage> out(images.size());
  std::vector<std::string> errors(images.size());
  std::vector<size_t> work;
  for (size_t i = 0; i < images.size(); ++i)
    if (i < needed.size() && needed[i]) work.push_back(i);
  std::atomic<uint64_t> texelBudget{kMaxTexels};
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t k; (k = next.fetch_add(1)) < work.size();) {
      size_t i = work[k];
      try {
        errors[i] = decodeOne(encodedBytes(doc, images[i]), out[i], texelBudget);
      } catch (const std::exception& e) {
        errors[i] = std::string("cannot decode: ") + e.what();
      }
    }
  };
  // libpng prints its errors itself: captured, and folded into the message of the image that failed.
  LibraryOutput library;
  size_t threads = std::min<size_t>(work.size(), std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  const std::string printed = library.suffix();
  for (size_t i = 0; i < images.size(); ++i)
    if (!errors[i].empty()) {
      const tinygltf::Image& img = images[i];
      std::string where = img.uri.empty() || img.uri.rfind("data:", 0) == 0 ? "" : " ('" + img.uri + "')";
      fail(doc, named("image", i, img.name) + where, errors[i] + printed);
    }
  return out;
}

}  // namespace gb::gltf
