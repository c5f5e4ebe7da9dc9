// PNG output through OpenImageIO, atomic by temporary file + rename.
#include "views/capture/image_io.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>

namespace gb {

bool writeAtomically(const std::string& path, const std::string& suffix,
                     const std::function<bool(const std::string&)>& write) {
  namespace fs = std::filesystem;
  fs::path target(path);
  fs::path tmp = target.parent_path() / ("." + target.filename().string() + ".tmp" + std::to_string(getpid()) + suffix);
  if (!write(tmp.string())) {
    std::error_code ec;
    fs::remove(tmp, ec);
    return false;
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

bool writePng(const std::string& path, const Rgba8Image& image, std::string& error) {
  std::string detail;
  bool ok = writeAtomically(path, ".png", [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create("png");
    if (!out) {
      detail = OIIO::geterror();
      return false;
    }
    OIIO::ImageSpec spec(int(image.width), int(image.height), 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data())) {
      detail = out->geterror();
      return false;
    }
    return out->close();
  });
  if (!ok) error = path + ": cannot write PNG" + (detail.empty() ? "" : " (" + detail + ")");
  return ok;
}

}  // namespace gb
