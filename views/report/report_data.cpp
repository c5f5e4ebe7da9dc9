// The report's data files (report_page.cpp writes them beside the page): per compared group, both
// sides' stored channel values and decoded values (decoded_image.h: the view values the probe shows) and the
// per-pixel error, as float32 arrays, deflated (zlib) and base64-encoded inside a script the page loads
// when the group is shown (a page opened from disk may load scripts, not read files). A side whose
// decoded values equal its stored ones bit for bit writes them once.
#include <openssl/evp.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "renderer/core/assert.h"
#include "views/analysis/decoded_image.h"
#include "views/capture/image_io.h"
#include "views/report/report_internal.h"

namespace gb {

namespace {

// float32 array of `components` interleaved per pixel -> planes (one per component) -> with `shuffle`
// the bytes of the floats shuffled (every float's first byte, then every second byte, ...: OpenEXR's
// and Blosc's shuffle, so deflate sees the slowly varying high bytes together; it helps floats of a
// float target and hurts values of an 8-bit one, whose few distinct floats deflate finds whole) ->
// zlib deflate -> base64 (EVP_EncodeBlock: no line breaks). page.js undoes it in reverse.
std::string pack(const std::vector<float>& values, uint32_t components, bool shuffle) {
  const size_t n = values.size(), pixels = n / components;
  std::vector<unsigned char> shuffled(n * sizeof(float));
  for (size_t i = 0; i < pixels; ++i)
    for (uint32_t k = 0; k < components; ++k) {
      unsigned char bytes[sizeof(float)];
      std::memcpy(bytes, &values[i * components + k], sizeof(float));
      const size_t j = size_t(k) * pixels + i;  // the float's place in its plane
      for (size_t b = 0; b < sizeof(float); ++b) shuffled[shuffle ? b * n + j : j * sizeof(float) + b] = bytes[b];
    }
  uLongf size = compressBound(uLong(shuffled.size()));
  std::vector<unsigned char> deflated(size);
  const int z = compress2(deflated.data(), &size, shuffled.data(), uLong(shuffled.size()), Z_BEST_SPEED);
  GB_ASSERT(z == Z_OK);
  std::string b64(4 * ((size + 2) / 3) + 1, '\0');
  const int written = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(b64.data()), deflated.data(), int(size));
  b64.resize(size_t(written));
  return b64;
}

// Finite minimum and maximum of each component (the page's display ranges).
nlohmann::json ranges(const std::vector<float>& v, uint32_t components) {
  nlohmann::json out = nlohmann::json::array();
  for (uint32_t k = 0; k < components; ++k) {
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = k; i < v.size(); i += components)
      if (std::isfinite(v[i])) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
    out.push_back(lo <= hi ? nlohmann::json::array({lo, hi}) : nlohmann::json(nullptr));
  }
  return out;
}

// One side of a group: what the page shows about it, and its packed arrays.
nlohmann::json side(const FrameSnapshot& f, const Quantity& q, bool shuffle) {
  const TargetImage& ti = f.images[q.target];
  const CpuImage& image = ti.image;
  const uint32_t channels = uint32_t(q.channels.size());
  std::vector<float> stored(size_t(image.width) * image.height * channels);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      for (uint32_t k = 0; k < channels; ++k)
        stored[(size_t(y) * image.width + x) * channels + k] = float(ti.value(x + ti.x0, y + ti.y0, q.channels[k]));
  const std::vector<ViewDef> views = layoutViews(f.layout);
  const int index = findView(views, q.name);
  GB_ASSERT(index >= 0);  // every quantity has its view
  const ViewDef& view = views[size_t(index)];
  const std::vector<float> decoded = decodedImage<float>(f, view);
  const uint32_t n = decodedComponents(f, view);
  const bool same = decoded.size() == stored.size() && std::memcmp(decoded.data(), stored.data(), stored.size() * sizeof(float)) == 0;
  nlohmann::json names = nlohmann::json::array(), components = nlohmann::json::array();
  for (uint32_t c : q.channels) names.push_back(image.channels[c]);
  for (uint32_t k = 0; k < n; ++k) components.push_back(k < view.componentNames.size() ? view.componentNames[k] : std::to_string(k));
  return {{"target", f.layout.targets[q.target].name},
          {"quantity", q.name},
          {"kind", name(q.kind)},
          {"visual", name(view.visual)},
          {"space", view.space},
          {"channels", names},
          {"components", components},
          {"stored", pack(stored, channels, shuffle)},
          {"decoded", same ? nlohmann::json(nullptr) : nlohmann::json(pack(decoded, n, shuffle))},
          {"ranges", ranges(decoded, n)}};
}

}  // namespace

bool writeGroupData(const Capture& a, const Capture& b, const GroupResult& g, const std::string& file,
                    std::string& error) {
  const Quantity &qa = *a.frame.layout.findByName(g.group.group), &qb = *b.frame.layout.findByName(g.group.group);
  const PixelType type = a.frame.images[qa.target].image.type;
  const bool shuffle = type == PixelType::F16 || type == PixelType::F32;
  nlohmann::json data = {{"key", g.group.key},
                         {"width", g.width},
                         {"height", g.height},
                         {"shuffled", shuffle},
                         {"a", side(a.frame, qa, shuffle)},
                         {"b", side(b.frame, qb, shuffle)},
                         {"error", pack(g.errors, 1, shuffle)}};
  return writeTextAtomically(file, "gblensData(" + data.dump() + ");\n", error);
}

}  // namespace gb
