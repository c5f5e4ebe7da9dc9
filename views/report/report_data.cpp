// The report's data per compared group: what the page needs to draw and read it (names, formats,
// how stored bits become values, display ranges) in report.js, and the texels themselves in chunk
// files data/<key>.<chunk>.js that the page loads as it needs them (texel_chunks.h): both sides'
// stored bits, their decoded values (the probe's, decoded_image.h) where they are not simply the
// stored values, and the per-pixel error. A page opened from disk may load scripts, not read files.
#include <cmath>
#include <cstring>
#include <filesystem>

#include "renderer/core/assert.h"
#include "views/analysis/decoded_image.h"
#include "views/analysis/view_text.h"
#include "views/capture/image_io.h"
#include "views/report/report_internal.h"
#include "views/report/texel_chunks.h"

namespace gb {

namespace {

// How the page turns a channel's stored bits into its value (CpuImage::value): floats by their bits,
// 8-bit integers through a table, wider integers by a division the writer has checked against
// decodeRaw for every value (a table where none holds).
nlohmann::json valueRule(const CpuImage& img, uint32_t c) {
  if (img.type == PixelType::F32 || img.type == PixelType::F16) return {{"float", img.type == PixelType::F32 ? 32 : 16}};
  const size_t bytes = pixelTypeSize(img.type);
  auto table = [&](uint32_t n) {
    nlohmann::json t = nlohmann::json::array();
    for (uint32_t r = 0; r < n; ++r) t.push_back(decodeRaw(img.type, img.encoding, c, r));
    return nlohmann::json{{"table", t}};
  };
  if (bytes == 1) return table(256);
  const bool isSigned = img.type == PixelType::I16;
  const uint32_t checked = bytes == 2 ? 65536u : 1u << 20;  // 32-bit: the first 2^20 values and the top one
  for (double divisor : {1.0, 3.0, 255.0, 1023.0, 32767.0, 65535.0, 16777215.0}) {
    auto rule = [&](uint32_t r) {
      const double v = (isSigned ? double(int16_t(uint16_t(r))) : double(r)) / divisor;
      return isSigned ? std::fmax(v, -1.0) : v;
    };
    const uint32_t top = bytes == 2 ? 0xFFFFu : ~0u;
    bool holds = rule(top) == decodeRaw(img.type, img.encoding, c, top);
    for (uint32_t r = 0; holds && r < checked; ++r) holds = rule(r) == decodeRaw(img.type, img.encoding, c, r);
    if (holds) return {{"divisor", divisor}, {"signed", isSigned}};
  }
  return bytes == 2 ? table(65536) : nlohmann::json{{"table", nullptr}};  // none: the page shows the bits alone
}

// Finite minimum and maximum of each plane (the page's display ranges).
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

// Interleaved floats (`n` per pixel) as planes of their bits.
TexelArray floatPlanes(const std::vector<float>& v, uint32_t n) {
  TexelArray a{4, n, std::vector<uint32_t>(v.size())};
  const size_t pixels = v.size() / n;
  for (size_t i = 0; i < pixels; ++i)
    for (uint32_t k = 0; k < n; ++k) std::memcpy(&a.values[k * pixels + i], &v[i * n + k], 4);
  return a;
}

struct Side {
  nlohmann::json meta;
  TexelArray stored, decoded;  // decoded.values empty: the stored channels' values are the decoded ones
};

Side side(const FrameSnapshot& f, const Quantity& q) {
  const TargetImage& ti = f.images[q.target];
  const CpuImage& image = ti.image;
  const uint32_t channels = uint32_t(q.channels.size()), w = image.width, h = image.height;
  const size_t pixels = size_t(w) * h;
  Side s;
  s.stored = {uint32_t(pixelTypeSize(image.type)), channels, std::vector<uint32_t>(pixels * channels)};
  std::vector<float> storedValues(pixels * channels);
  for (uint32_t k = 0; k < channels; ++k)
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        s.stored.values[k * pixels + i] = image.raw(x, y, q.channels[k]);
        storedValues[i * channels + k] = float(image.value(x, y, q.channels[k]));
      }
  const std::vector<ViewDef> views = layoutViews(f.layout);
  const int index = findView(views, q.name);
  GB_ASSERT(index >= 0);  // every quantity has its view
  const ViewDef& view = views[size_t(index)];
  const std::vector<float> decoded = decodedImage<float>(f, view);
  const uint32_t n = decodedComponents(f, view);
  const bool same = decoded.size() == storedValues.size() &&
                    std::memcmp(decoded.data(), storedValues.data(), decoded.size() * sizeof(float)) == 0;
  if (!same) s.decoded = floatPlanes(decoded, n);
  const LayoutTarget& lt = f.layout.targets[q.target];
  nlohmann::json names = nlohmann::json::array(), components = nlohmann::json::array(), rules = nlohmann::json::array();
  for (uint32_t c : q.channels) names.push_back(image.channels[c]), rules.push_back(valueRule(image, c));
  // sRGB codes compare as code / 255 (storedUnit): the page's error rule reads them so.
  const nlohmann::json units = image.encoding == Encoding::Srgb ? nlohmann::json({{"divisor", 255.0}, {"signed", false}}) : nlohmann::json(nullptr);
  for (uint32_t k = 0; k < n; ++k) components.push_back(k < view.componentNames.size() ? view.componentNames[k] : std::to_string(k));
  s.meta = {{"target", lt.name},
            {"format", lt.format.name},
            {"type", name(image.type)},
            {"encoding", name(image.encoding)},
            {"quantity", q.name},
            {"kind", name(q.kind)},
            {"visual", name(view.visual)},
            {"space", view.space.empty() ? view.unit : view.space},
            {"integer", view.integer},
            {"digits", storageDigits(image.type, image.encoding)},
            {"channels", names},
            {"rules", rules},
            {"units", units},
            {"components", components},
            {"decoded", !same},
            {"ranges", ranges(decoded, n)}};
  return s;
}

// The chunks: pass 0; passes 1 and 2; passes 3 and 4 in bands of kTexelBand rows.
struct Chunk {
  std::string id;
  std::vector<uint32_t> passes;
  uint32_t row0, row1;
};
std::vector<Chunk> chunks(uint32_t height) {
  std::vector<Chunk> out = {{"0", {0}, 0, height}, {"1", {1, 2}, 0, height}};
  for (uint32_t r = 0, band = 0; r < height; r += kTexelBand, ++band)
    out.push_back({"2." + std::to_string(band), {3, 4}, r, std::min(height, r + kTexelBand)});
  return out;
}

// The stored units the colour and exact metrics compare (compare.cpp storedUnits): the values, but
// sRGB channels as code / 255.
double storedUnit(const CpuImage& img, uint32_t c, uint32_t raw) {
  return img.encoding == Encoding::Srgb ? raw / 255.0 : decodeRaw(img.type, img.encoding, c, raw);
}

// Whether the page can compute the group's error itself, bit for bit: the largest |A-B| of the stored
// units (what colour and exact metrics measure where both sides store alike). Checked on every pixel;
// where it holds the error costs nothing in the data.
bool errorIsStoredUnitDifference(const Capture& a, const Capture& b, const Quantity& qa, const Quantity& qb,
                                 const GroupResult& g) {
  if (g.group.kind != MetricKind::Colour && g.group.kind != MetricKind::Exact) return false;
  const CpuImage &ia = a.frame.images[qa.target].image, &ib = b.frame.images[qb.target].image;
  const size_t n = std::min({qa.channels.size(), qb.channels.size(), size_t(4)});
  for (uint32_t y = 0; y < g.height; ++y)
    for (uint32_t x = 0; x < g.width; ++x) {
      double e = 0.0;
      for (size_t k = 0; k < n; ++k) {
        const double u = storedUnit(ia, qa.channels[k], ia.raw(x, y, qa.channels[k]));
        const double v = storedUnit(ib, qb.channels[k], ib.raw(x, y, qb.channels[k]));
        e = std::max(e, absDifference(u, v));
      }
      const float want = g.errors[size_t(y) * g.width + x], got = float(e);
      if (std::memcmp(&want, &got, sizeof got) != 0) return false;
    }
  return true;
}

}  // namespace

bool writeGroupData(const Capture& a, const Capture& b, const GroupResult& g, const std::string& stem,
                    nlohmann::json& meta, std::string& error) {
  const Quantity &qa = *a.frame.layout.findByName(g.group.group), &qb = *b.frame.layout.findByName(g.group.group);
  Side sa = side(a.frame, qa), sb = side(b.frame, qb);
  GB_ASSERT(g.errors.size() == size_t(g.width) * g.height && sa.stored.values.size() == g.errors.size() * sa.stored.planes);
  const bool errorRule = errorIsStoredUnitDifference(a, b, qa, qb, g);
  const TexelArray err = errorRule ? TexelArray{4, 1, {}} : floatPlanes(g.errors, 1);
  // B against A where the arrays line up: what they share costs nothing.
  const bool storedRef = sb.stored.bytes == sa.stored.bytes && sb.stored.planes == sa.stored.planes;
  const bool decodedRef = !sa.decoded.values.empty() && !sb.decoded.values.empty() && sa.decoded.planes == sb.decoded.planes;
  // The arrays in the order the page reads them from each pass of a chunk.
  const std::vector<std::pair<const TexelArray*, const TexelArray*>> arrays = {
      {&sa.stored, nullptr}, {&sa.decoded, nullptr}, {&sb.stored, storedRef ? &sa.stored : nullptr},
      {&sb.decoded, decodedRef ? &sa.decoded : nullptr}, {&err, nullptr}};
  nlohmann::json ids = nlohmann::json::array();
  for (const Chunk& c : chunks(g.height)) {
    std::vector<uint8_t> bytes;
    for (uint32_t p : c.passes)
      for (const auto& [array, ref] : arrays)
        if (!array->values.empty()) encodeTexels(*array, ref, g.width, g.height, p, c.row0, c.row1, bytes);
    const std::string file = stem + "." + c.id + ".js";
    const std::string script = "gblensChunk(" + nlohmann::json(g.group.key).dump() + ", \"" + c.id + "\", " +
                               std::to_string(bytes.size()) + ", " + deflatedLiteral(bytes) + ");\n";
    if (!writeTextAtomically(file, script, error)) return false;
    ids.push_back({{"id", c.id}, {"passes", c.passes}, {"rows", {c.row0, c.row1}}});
  }
  float top = 0.0f;
  bool infinite = false;
  for (float e : g.errors) {
    if (std::isfinite(e)) top = std::max(top, e);
    infinite |= std::isinf(e);
  }
  meta = {{"width", g.width},
          {"height", g.height},
          {"band", kTexelBand},
          {"chunks", ids},
          {"a", sa.meta},
          {"b", sb.meta},
          {"b_stored_against_a", storedRef},
          {"b_decoded_against_a", decodedRef},
          {"error", {{"unit", errorUnit(g)}, {"max", top}, {"infinite", infinite},
                     {"rule", errorRule ? nlohmann::json("max_abs_stored_units") : nlohmann::json(nullptr)}}}};
  return true;
}

}  // namespace gb
