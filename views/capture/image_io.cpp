// PNG output (RGBA through OpenImageIO, palette through libpng), atomic by temporary file + rename.
#include "views/capture/image_io.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>
#include <png.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "renderer/core/assert.h"
#include "views/capture/debris.h"

namespace gb {

bool writeAtomically(const std::string& path, const std::string& suffix,
                     const std::function<bool(const std::string&)>& write) {
  namespace fs = std::filesystem;
  fs::path target(path);
  // Stamped with this process (debris.h), so a later run can tell an interrupted write's file.
  static std::atomic<uint64_t> sequence{0};
  fs::path tmp = target.parent_path() / ("." + target.filename().string() + ".tmp-" + processStamp() + "-" +
                                         std::to_string(sequence++) + suffix);
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

namespace {

// libpng's errors end the write here (its documented longjmp), with the message kept.
[[noreturn]] void pngFailed(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message;
  png_longjmp(png, 1);
}

// No C++ object lives in this frame: libpng's longjmp skips no destructor.
bool writeIndexed(FILE* file, uint32_t width, uint32_t height, const uint8_t* indices, const png_color* colours,
                  int count, std::string* detail) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, detail, pngFailed, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    *detail = "out of memory";
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_PLTE(png, info, colours, count);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  for (uint32_t y = 0; y < height; ++y) png_write_row(png, indices + size_t(y) * width);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

bool writeIndexedPng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& indices,
                     const std::vector<uint8_t>& palette, std::string& error) {
  GB_ASSERT(indices.size() == size_t(width) * height && palette.size() % 3 == 0 && palette.size() <= 256 * 3);
  std::string detail;
  const bool ok = writeAtomically(path, ".png", [&](const std::string& tmp) {
    FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file) {
      detail = std::strerror(errno);
      return false;
    }
    std::vector<png_color> colours(palette.size() / 3);
    for (size_t i = 0; i < colours.size(); ++i) colours[i] = {palette[3 * i], palette[3 * i + 1], palette[3 * i + 2]};
    const bool written = writeIndexed(file, width, height, indices.data(), colours.data(), int(colours.size()), &detail);
    return (std::fclose(file) == 0) && written;
  });
  if (!ok) error = path + ": cannot write PNG" + (detail.empty() ? "" : " (" + detail + ")");
  return ok;
}

namespace {

// The folder `path` lies in, as written ("." for a bare name).
std::filesystem::path folderOf(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

// The nearest folder of `dir` and its ancestors that exists must be one this process can write.
bool creatable(const std::string& flag, const std::filesystem::path& dir, std::string& error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path p = fs::absolute(dir, ec).lexically_normal();
  while (!p.empty() && !fs::exists(p, ec) && p != p.parent_path()) p = p.parent_path();
  if (!fs::is_directory(p, ec)) {
    error = flag + p.string() + ": not a folder";
    return false;
  }
  if (access(p.c_str(), W_OK | X_OK) != 0) {
    error = flag + p.string() + ": cannot write in it (" + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

}  // namespace

bool checkFileDestination(const std::string& flag, const std::string& path, std::string& error) {
  namespace fs = std::filesystem;
  const std::string at = (flag.empty() ? "" : flag + " ") + path;
  std::error_code ec;
  const fs::path folder = folderOf(path);
  if (path.empty() || fs::path(path).filename().empty()) {
    error = at + ": not a file name";
    return false;
  }
  if (fs::is_directory(fs::symlink_status(path, ec))) {
    error = at + ": is a folder";
    return false;
  }
  if (!fs::is_directory(folder, ec)) {
    error = at + ": no folder " + folder.string() + " to write it in";
    return false;
  }
  return creatable(at + ": ", folder, error);
}

bool checkFolderDestination(const std::string& flag, const std::string& dirText, const std::string& marker,
                            const std::string& what, std::string& error) {
  namespace fs = std::filesystem;
  const std::string at = (flag.empty() ? "" : flag + " ") + dirText;
  std::error_code ec;
  // A folder replaced as a whole: a link there is replaced too; one written into: followed.
  const fs::file_status st = marker.empty() ? fs::status(dirText, ec) : fs::symlink_status(dirText, ec);
  if (fs::is_symlink(st)) return creatable(at + ": ", folderOf(dirText), error);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) {
      error = at + ": exists and is not a directory";
      return false;
    }
    if (!marker.empty() && !fs::is_empty(dirText, ec) && !fs::exists(fs::path(dirText) / marker, ec)) {
      error = at + ": exists, is not empty and holds no " + what + " (" + marker + "); not overwritten";
      return false;
    }
    return creatable(at + ": ", marker.empty() ? fs::path(dirText) : folderOf(dirText), error);
  }
  return creatable(at + ": ", folderOf(dirText), error);
}

bool replaceDirectory(const std::string& dirText, const std::string& marker, const std::string& what,
                      const std::function<bool(const std::string& tmp, std::string& error)>& write,
                      std::string& error) {
  namespace fs = std::filesystem;
  fs::path dir = fs::absolute(fs::path(dirText)).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  std::error_code ec;
  if (!checkFolderDestination("", dirText, marker, what, error)) return false;
  fs::path parent = dir.parent_path();
  fs::create_directories(parent, ec);
  // The writer's pid and start time (debris.h): a later run removes what an interrupted one left.
  std::string stamp = processStamp() + "-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count());
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
  std::error_code missing;  // (symlink_status sets it when nothing is there)
  bool hadOld = fs::exists(fs::symlink_status(dir, missing));  // a symbolic link there is replaced, as a file's is
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
