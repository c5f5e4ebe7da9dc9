// The import path's fuzz entry (see import_entry.h).
#include "tests/fuzz/import_entry.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "renderer/core/json_read.h"
#include "renderer/core/layout_json.h"
#include "views/import/import.h"
#include "views/import/import_internal.h"
#include "views/capture/manifest_check.h"
#include "views/import/renderdoc_replay.h"

namespace gb::fuzz {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

void writeBytes(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
}

// The sources layouts name: a 4x2 float EXR (R G B A), an 8-bit PNG (RGB), a raw r32f dump, a sidecar.
void writeSources(const std::string& dir) {
  if (fs::exists(dir + "/a.exr")) return;
  fs::create_directories(dir);
  std::vector<float> rgba(4 * 2 * 4, 0.5f);
  std::vector<uint8_t> rgb(4 * 2 * 3, 128);
  OIIO::ImageSpec exr(4, 2, 4, OIIO::TypeDesc::FLOAT), png(4, 2, 3, OIIO::TypeDesc::UINT8);
  auto a = OIIO::ImageOutput::create(dir + "/a.exr");
  a->open(dir + "/a.exr", exr), a->write_image(OIIO::TypeDesc::FLOAT, rgba.data()), a->close();
  auto b = OIIO::ImageOutput::create(dir + "/a.png");
  b->open(dir + "/a.png", png), b->write_image(OIIO::TypeDesc::UINT8, rgb.data()), b->close();
  std::vector<float> depth(8, 0.5f);
  writeBytes(dir + "/a.bin", reinterpret_cast<const uint8_t*>(depth.data()), depth.size() * 4);
  const std::vector<double> view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1};
  const std::vector<double> proj = {1.2, 0, 0, 0, 0, 2.4, 0, 0, 0, 0, -1.004, -1, 0, 0, -0.2004, 0};
  std::ofstream(dir + "/cam.json") << json{{"view_from_world", view}, {"clip_from_view", proj}}.dump();
}

std::string runImport(const json& layoutJson, const std::string& dir, const std::string& cameraFile) {
  std::string error;
  json j = layoutJson;
  RenderOptions options;
  Layout layout;
  if (!resolveLayoutParameters(j, layoutParameters(options), "fuzz.json", error) || !parseLayout(j, "fuzz.json", layout, error))
    return error;
  // What parseLayout accepts, layoutJson writes back, and parseLayout accepts again (manifests).
  Layout again;
  if (!parseLayout(gb::layoutJson(layout), "again", again, error)) {
    std::fprintf(stderr, "layoutJson wrote back what parseLayout refuses: %s\n%s\n", error.c_str(),
                 gb::layoutJson(layout).dump().c_str());
    std::abort();
  }
  ImportInput in;
  in.layout = layout;
  in.layoutDir = dir;
  in.cameraFile = cameraFile;
  FrameSnapshot frame;
  return importFrame(in, frame, error) ? "" : error;
}

// One image or raw target of `format` read from `file`.
json oneTarget(const std::string& file, const std::string& format, bool raw, int w, int h, const char* quantity, int channels) {
  json q = {{"quantity", quantity}, {"channels", json::array()}};
  for (int c = 0; c < channels; ++c) q["channels"].push_back(c);
  if (std::string(quantity) == "depth") q["encoding"] = "hardware";
  json t = {{"name", "t"}, {"format", format}, {"source", {{"file", file}, {"raw", raw}}}, {"quantities", {q}}};
  if (w) t["size"] = {w, h};
  return {{"format", "gblens-layout"}, {"version", 1}, {"targets", {t}}};
}

}  // namespace

std::string importOne(const uint8_t* data, size_t size, const std::string& dir) {
  writeSources(dir);
  if (size < 1) return "empty";
  const char mode = char(data[0]);
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  std::string error;
  json j;
  switch (mode) {
    case 'L':
      if (!parseJson(rest, "fuzz.json", j, error)) return error;
      return runImport(j, dir, "");
    case 'C': {
      writeBytes(dir + "/side.json", data + 1, size - 1);
      json l = oneTarget("a.exr", "rgba32f", false, 4, 2, "albedo", 3);
      l["camera"] = {{"sidecar", "side.json"}};
      return runImport(l, dir, "");
    }
    case 'P': case 'E': case 'T': case 'H': case 'p': case 'e': case 't': case 'h': {
      const char upper = char(mode & ~0x20);
      const std::string ext = upper == 'P' ? ".png" : upper == 'E' ? ".exr" : upper == 'T' ? ".tif" : ".hdr";
      writeBytes(dir + "/in" + ext, data + 1, size - 1);
      const bool exact = mode == upper;  // upper case: the layout gives 4x2; lower case: the file's size
      std::string e1 = runImport(oneTarget("in" + ext, "rgba32f", false, exact ? 4 : 0, 2, "albedo", 3), dir, "");
      std::string e2 = runImport(oneTarget("in" + ext, "rgb8_unorm", false, exact ? 4 : 0, 2, "albedo", 3), dir, "");
      return e1.empty() || e2.empty() ? "" : e2;  // accepted as either format
    }
    case 'R': {
      if (size < 5) return "short";
      static const char* const formats[] = {"r32f", "rgba8_unorm", "rgb10a2_unorm", "d24s8", "d32s8", "d16",
                                            "rg16_snorm", "rgba16f", "r32_uint", "rgba8_srgb"};
      const std::string format = formats[data[1] % 10];
      const bool depth = format[0] == 'd';
      const json l = oneTarget("in.bin", format, true, 1 + data[2] % 64, 1 + data[3] % 64, depth ? "depth" : "albedo",
                               depth ? 1 : format == "r32f" || format == "r32_uint" ? 1 : format == "rg16_snorm" ? 2 : 3);
      // Byte 4: 3 (mod 4) writes the rest as given (a size the layout may not explain); otherwise at
      // most the dump's own size, so that inputs reach the unpackers.
      size_t bytes = size - 5;
      Layout parsed;
      if (data[4] % 4 != 3 && parseLayout(l, "fuzz.json", parsed, error))
        bytes = std::min(bytes, dumpBytes(parsed.targets[0], 1 + data[2] % 64, 1 + data[3] % 64));
      writeBytes(dir + "/in.bin", data + 5, bytes);
      return runImport(l, dir, "");
    }
    case 'M': {
      const size_t nul = rest.find('\0');
      json m, lights;
      FrameSnapshot f;
      std::vector<ManifestTarget> targets;
      std::vector<ManifestFile> files;
      if (!parseJson(rest.substr(0, nul), "manifest.json", m, error) ||
          !parseJson(nul == std::string_view::npos ? "{}" : rest.substr(nul + 1), "lights.json", lights, error) ||
          !checkManifestFormat(m, "manifest.json", error) || !manifestFiles(m, "manifest.json", files, error) ||
          !frameFromManifest(m, lights, "manifest.json", "lights.json", f, targets, error))
        return error;
      return "";
    }
    case 'D': {
      if (!std::getenv("GBLENS_FUZZ_RDC")) return "rdc skipped";
      writeBytes(dir + "/in.rdc", data + 1, size - 1);
      RdcListing listing;
      RdcReplayOptions o;
      return listRenderDocCapture(dir + "/in.rdc", listing, error, o) ? "" : error;
    }
    default: return "unknown mode";
  }
}

}  // namespace gb::fuzz
