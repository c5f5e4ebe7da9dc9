// Safe reading of import sources (see import_source.h).
#include "views/import/import_source.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "renderer/core/json_read.h"
#include "renderer/core/library_output.h"
#include "views/import/import_internal.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

// Whether `path` lies inside `folder`, both resolved (symbolic links, "..") as far as they exist.
bool inside(const fs::path& folder, const fs::path& path) {
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
  if (ec) return false;
  const fs::path p = fs::weakly_canonical(path, ec);
  if (ec) return false;
  auto r = root.begin(), q = p.begin();
  for (; r != root.end() && !r->empty(); ++r, ++q)
    if (q == p.end() || *q != *r) return false;
  return true;
}

}  // namespace

bool sourceAllowed(const ImportInput& in, const std::string& path, const std::string& where, const std::string& field,
                   std::string& error) {
  if (in.allowOutsideSources || std::find(in.files.begin(), in.files.end(), path) != in.files.end()) return true;
  std::vector<fs::path> roots;
  if (in.layout.file.rfind("builtin:", 0) != 0) roots.push_back(in.layoutDir);  // a layout file's folder
  for (const std::string& f : in.files) roots.push_back(fs::path(f).parent_path());
  if (!in.capture.empty()) roots.push_back(fs::path(in.capture).parent_path());
  for (const fs::path& root : roots)
    if (inside(root, path)) return true;
  error = where + ": " + field + " \"" + path + "\": outside the layout's folder and the given files' folders " +
          "(a layout reads only files beside it or beside the files given; --allow-outside-sources lets it)";
  return false;
}

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
