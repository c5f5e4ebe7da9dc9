// Safe reading of import sources (see import_source.h).
#include "views/import/import_source.h"

#include <fstream>

#include "renderer/core/json_read.h"
#include "renderer/core/library_output.h"

namespace gb {

bool checkImportSize(const std::string& at, uint64_t w, uint64_t h, std::string& error) {
  if (w && h && w * h <= kMaxImportTexels) return true;
  error = at + ": size " + std::to_string(w) + "x" + std::to_string(h) + ": " +
          (w && h ? "more than the " + std::to_string(kMaxImportTexels) + " texels gblens imports" : "empty");
  return false;
}

std::unique_ptr<OIIO::ImageInput> openImportImage(const std::string& path, const std::string& at, std::string& error) {
  std::string why;
  if (!isRegularFile(path, why)) {
    error = at + ": source.file: " + why;
    return nullptr;
  }
  LibraryOutput library;
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string detail = OIIO::geterror();
    for (char& c : detail)
      if (c == '\n') c = ' ';
    error = at + ": " + path + ": source.file: cannot read the image (" + detail + ")" + library.suffix();
    return nullptr;
  }
  return in;
}

bool readFileRange(const std::string& path, uint64_t offset, uint64_t maxBytes, std::vector<uint8_t>& out,
                   uint64_t& fileBytes, const std::string& at, std::string& error) {
  std::string why;
  if (!isRegularFile(path, why)) {
    error = at + ": source.file: " + why;
    return false;
  }
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = f ? std::streamoff(f.tellg()) : std::streamoff(-1);
  if (size < 0) {
    error = at + ": source.file: cannot read " + path;
    return false;
  }
  fileBytes = uint64_t(size);
  out.resize(size_t(offset >= fileBytes ? 0 : std::min<uint64_t>(fileBytes - offset, maxBytes)));
  f.seekg(std::streamoff(std::min(offset, fileBytes)));
  if (!out.empty() && !f.read(reinterpret_cast<char*>(out.data()), std::streamsize(out.size()))) {
    error = at + ": source.file: cannot read " + path;
    return false;
  }
  return true;
}

}  // namespace gb
