// Hover and status-bar text of a view at a pixel (see view_text.h).
#include "views/analysis/view_text.h"

#include <algorithm>
#include <cstdio>

#include "renderer/core/decode.h"
#include "views/analysis/visualize.h"

namespace gb {

std::string storedText(const CpuImage& img, uint32_t x, uint32_t y, uint32_t c) {
  char buf[48];
  if (img.encoding == Encoding::Float)
    std::snprintf(buf, sizeof buf, "%.9g", img.value(x, y, c));
  else
    std::snprintf(buf, sizeof buf, "%u", img.raw(x, y, c));
  return buf;
}

// The decoded value, named as the view's components and labelled with its space or unit.
static std::string decodedText(const FrameSnapshot& f, const ViewDef& v, const std::array<double, 4>& value) {
  const Quantity& q = f.layout.quantities[size_t(v.quantity)];
  std::string out = v.space.empty() ? (v.unit.empty() ? std::string(name(v.kind)) : v.unit) : v.space;
  char buf[64];
  const uint32_t n = v.visual == Visual::Color ? std::min(v.components, 4u) : v.components;
  for (uint32_t c = 0; c < n; ++c) {
    if (v.integer)
      std::snprintf(buf, sizeof buf, " %u", uint32_t(value[c]));
    else
      std::snprintf(buf, sizeof buf, " %s%.7g", v.components > 1 ? (v.componentNames[c] + " ").c_str() : "", value[c]);
    out += buf;
  }
  if (v.visual == Visual::Normal) {
    std::snprintf(buf, sizeof buf, " (|stored| %.7g)", value[3]);
    out += buf;
  }
  if (v.visual == Visual::Position) {
    std::snprintf(buf, sizeof buf, ", %.7g from the eye", value[3]);
    out += buf;
  }
  if (v.visual == Visual::Id)
    if (auto it = q.idNames.find(uint32_t(value[0])); it != q.idNames.end()) out += " (" + it->second + ")";
  if (v.visual == Visual::Stencil) {
    std::string bits;
    for (const auto& [bitName, mask] : q.stencilBits)
      if (uint32_t(value[0]) & mask) bits += (bits.empty() ? "" : ", ") + bitName;
    if (!bits.empty()) out += " (" + bits + ")";
  }
  return out;
}

int storageDigits(PixelType t, Encoding e) {
  // Enough digits to tell one storage step from the next: ceil(log10(2^bits)) + 1 for normalised
  // integers, the mantissa's decimal digits for floats.
  switch (e) {
    case Encoding::Float: return t == PixelType::F16 ? 4 : 7;
    case Encoding::Unorm10: return 4;
    case Encoding::Unorm24: return 8;
    case Encoding::Uint: return 10;
    default: return pixelTypeSize(t) == 1 ? 4 : pixelTypeSize(t) == 2 ? 6 : 7;
  }
}

std::vector<std::string> texelValueLines(const FrameSnapshot& f, const ViewDef& v,
                                         const std::optional<std::array<double, 4>>& value, uint32_t shown) {
  std::vector<std::string> lines;
  const TargetImage* ti = layoutImage(f, f.layout.quantities[size_t(v.quantity)].target);
  if (!ti || !value) return lines;
  const int digits = storageDigits(ti->image.type, ti->image.encoding);
  const uint32_t n = std::min(v.components, 4u);
  char buf[64];
  for (uint32_t c = 0; c < n; ++c) {
    if (!(shown & (1u << c)) && n > 1) continue;
    const std::string label = n > 1 && c < v.componentNames.size() ? v.componentNames[c] + " " : "";
    if (v.integer)
      std::snprintf(buf, sizeof buf, "%s%u", label.c_str(), uint32_t((*value)[c]));
    else
      std::snprintf(buf, sizeof buf, "%s%.*g", label.c_str(), digits, (*value)[c]);
    lines.push_back(buf);
  }
  return lines;
}

std::string viewValueText(const FrameSnapshot& f, const ViewDef& v, uint32_t x, uint32_t y) {
  const Quantity& q = f.layout.quantities[size_t(v.quantity)];
  const TargetImage* ti = layoutImage(f, q.target);
  if (!ti || !ti->contains(x, y)) return "";
  const LayoutTarget& lt = f.layout.targets[q.target];
  char head[96];
  std::snprintf(head, sizeof head, "%s (%u, %u)  stored %s (%s)", v.name.c_str(), x, y, lt.name.c_str(), lt.format.name.c_str());
  std::string out = head;
  for (uint32_t c : q.channels)
    out += " " + (c < lt.channels.size() ? lt.channels[c] : std::to_string(c)) + " " +
           storedText(ti->image, x - ti->x0, y - ti->y0, c);
  std::optional<std::array<double, 4>> value = viewValue(f, v, x, y);
  out += value ? "  -> " + decodedText(f, v, *value) : "  -> nothing drawn here";
  return out;
}

}  // namespace gb
