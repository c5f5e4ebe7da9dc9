// The capture readers' fuzz entry (see capture_entry.h).
#include "tests/fuzz/capture_entry.h"

#include <filesystem>
#include <fstream>
#include <string_view>

#include "renderer/core/file_name.h"
#include "renderer/core/json_read.h"
#include "renderer/core/sha256.h"
#include "views/capture/capture.h"

namespace gb::fuzz {

namespace {

namespace fs = std::filesystem;

void writeBytes(const fs::path& path, std::string_view bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace

std::string captureOne(const uint8_t* data, size_t size, const std::string& dir) {
  if (size < 1) return "empty";
  const char mode = char(data[0]);
  if (mode != 'S' && mode != 'U') return "unknown mode";
  const std::string_view all(reinterpret_cast<const char*>(data + 1), size - 1);
  const size_t first = all.find('\0'), second = first == std::string_view::npos ? first : all.find('\0', first + 1);
  const std::string_view manifestText = all.substr(0, first);
  const std::string_view lights = first == std::string_view::npos ? "" : all.substr(first + 1, second - first - 1);
  const std::string_view file = second == std::string_view::npos ? "" : all.substr(second + 1);
  const fs::path folder = fs::path(dir) / "capture";
  std::error_code ec;
  fs::remove_all(folder, ec);
  fs::create_directories(folder, ec);
  writeBytes(folder / "lights.json", lights);
  nlohmann::json m;
  std::string error;
  // Every listed file: lights.json as given, every other one the rest of the input (only names that
  // stay in the folder are written); 'S' records their true sizes and digests.
  if (parseJson(manifestText, "manifest.json", m, error) && m.is_object() && m.contains("files") && m["files"].is_object()) {
    for (auto& [name, entry] : m["files"].items()) {
      std::string why;
      if (!safeFileName(name, why)) continue;
      const std::string_view bytes = name == "lights.json" ? lights : file;
      if (name != "lights.json") writeBytes(folder / name, bytes);
      if (mode == 'S' && entry.is_object())
        entry["bytes"] = bytes.size(), entry["sha256"] = sha256Hex(bytes.data(), bytes.size());
    }
    writeBytes(folder / "manifest.json", m.dump());
  } else {
    writeBytes(folder / "manifest.json", manifestText);
  }
  Capture c;
  return loadCapture(folder.string(), c, error) ? "" : error;
}

}  // namespace gb::fuzz
