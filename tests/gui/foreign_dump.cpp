// foreign_deferred's --dump read and decoded by the test (foreign_dump.h).
#include "tests/gui/foreign_dump.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

namespace gb::gui {

bool ForeignDump::load(const std::filesystem::path& dir, std::string& error) {
  std::ifstream cameraFile(dir / "camera.json");
  const nlohmann::json camera = nlohmann::json::parse(cameraFile, nullptr, false);
  if (camera.is_discarded()) {
    error = (dir / "camera.json").string() + ": not JSON";
    return false;
  }
  width = camera["width"];
  height = camera["height"];
  for (const nlohmann::json& t : camera["targets"]) {
    const std::string name = t["name"];
    std::ifstream in(dir / t["file"].get<std::string>(), std::ios::binary);
    bytes[name] = {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    texelBytes[name] = t["bytes_per_texel"];
    if (bytes[name].size() != size_t(width) * height * texelBytes[name]) {
      error = name + ": " + std::to_string(bytes[name].size()) + " bytes for " + std::to_string(width) + "x" +
              std::to_string(height) + " texels of " + std::to_string(texelBytes[name]);
      return false;
    }
  }
  return true;
}

uint8_t ForeignDump::code(const std::string& target, uint32_t x, uint32_t y, uint32_t c) const {
  return uint8_t(bytes.at(target)[(size_t(y) * width + x) * texelBytes.at(target) + c]);
}

uint32_t ForeignDump::f32Bits(const std::string& target, uint32_t x, uint32_t y, uint32_t c) const {
  uint32_t bits;
  std::memcpy(&bits, bytes.at(target).data() + (size_t(y) * width + x) * texelBytes.at(target) + c * 4, 4);
  return bits;
}

float ForeignDump::f32(const std::string& target, uint32_t x, uint32_t y, uint32_t c) const {
  const uint32_t bits = f32Bits(target, x, y, c);
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}

bool ForeignDump::surface(uint32_t x, uint32_t y) const {
  const float w = f32("position", x, y, 3);
  return w != 1.0f && w > 0.0f && std::isfinite(w);
}

double ForeignDump::occlusion(uint32_t x, uint32_t y) const { return code("occlusion", x, y) / 255.0; }

double ForeignDump::albedo(uint32_t x, uint32_t y, uint32_t c) const {
  const double v = code("albedo", x, y, c) / 255.0;  // IEC 61966-2-1
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

std::array<double, 3> ForeignDump::normal(uint32_t x, uint32_t y) const {
  std::array<double, 3> n;
  for (uint32_t c = 0; c < 3; ++c) n[c] = code("normal", x, y, c) / 255.0 * 2.0 - 1.0;
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& v : n) v /= length;
  return n;
}

Summary summarize(const std::vector<double>& values) {
  Summary s;
  s.count = values.size();
  if (values.empty()) return s;
  s.min = *std::min_element(values.begin(), values.end());
  s.max = *std::max_element(values.begin(), values.end());
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / double(values.size());
  return s;
}

}  // namespace gb::gui
