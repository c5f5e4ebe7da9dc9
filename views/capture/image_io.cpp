// PNG output through OpenImageIO, atomic by temporary file + rename.
#include "views/capture/image_io.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <filesystem>
#include <fstream>

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

bool writeTextAtomically(const std::string& path, const std::string& text, std::string& error) {
  const bool ok = writeAtomically(path, ".tmp", [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    return bool(out.flush());
  });
  if (!ok) error = path + ": cannot write";
  return ok;
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

bool replaceDirectory(const std::string& dirText, const std::string& marker, const std::string& what,
                      const std::function<bool(const std::string& tmp, std::string& error)>& write,
                      std::string& error) {
  namespace fs = std::filesystem;
  fs::path dir = fs::absolute(fs::path(dirText)).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) {
      error = dirText + ": exists and is not a directory";
      return false;
    }
    if (!fs::is_empty(dir, ec) && !fs::exists(dir / marker, ec)) {
      error = dirText + ": exists, is not empty and holds no " + what + " (" + marker + "); not overwritten";
      return false;
    }
  }
  fs::path parent = dir.parent_path();
  fs::create_directories(parent, ec);
  std::string stamp = std::to_string(getpid()) + "-" +
                      std::to_string(std::chrono::steady_clock::now().time_since_epoch().count());
  fs::path tmp = parent / ("." + dir.filename().string() + ".partial-" + stamp);
  if (!fs::create_directory(tmp, ec)) {
    error = tmp.string() + ": cannot create (" + ec.message() + ")";
    return false;
  }
  if (!write(tmp.string(), error)) {
    fs::remove_all(tmp, ec);
    return false;
  }
  // Swap into place: an old folder moves aside first and is deleted only after the rename.
  fs::path old = parent / ("." + dir.filename().string() + ".old-" + stamp);
  bool hadOld = fs::exists(dir, ec);
  if (hadOld) fs::rename(dir, old, ec);
  if (!ec) fs::rename(tmp, dir, ec);
  if (ec) {
    error = dirText + ": cannot move the " + what + " into place (" + ec.message() + ")";
    std::error_code ignore;
    if (hadOld && !fs::exists(dir, ignore)) fs::rename(old, dir, ignore);
    fs::remove_all(tmp, ignore);
    return false;
  }
  if (hadOld) fs::remove_all(old, ec);
  return true;
}

}  // namespace gb
