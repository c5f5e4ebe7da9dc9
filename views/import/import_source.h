// Reading an import's source files safely (import.cpp): regular files only (a directory, FIFO or
// device named as a source is refused), every size a file declares checked against the layout's
// and a sane bound before anything is allocated for it, and what the image libraries print folded
// into the one-line message.
#pragma once
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gb {

// An imported target is at most 2^28 texels (16384 x 16384): gblens's views, captures and GPU
// images all hold whole targets, and a file declaring more is broken or hostile, not a G-buffer.
constexpr uint64_t kMaxImportTexels = 1ull << 28;

// False with "AT: size WxH: more than ... texels" when w x h is beyond kMaxImportTexels.
bool checkImportSize(const std::string& at, uint64_t w, uint64_t h, std::string& error);

// Opens an image through OpenImageIO: a regular file, its library messages captured. `at` names
// the target and file in the message ("AT: source.file: cannot read the image (...)").
std::unique_ptr<OIIO::ImageInput> openImportImage(const std::string& path, const std::string& at, std::string& error);

// Reads at most maxBytes from `offset` in a regular file (nothing before the offset is read or
// allocated); `fileBytes` receives its whole size.
bool readFileRange(const std::string& path, uint64_t offset, uint64_t maxBytes, std::vector<uint8_t>& out,
                   uint64_t& fileBytes, const std::string& at, std::string& error);

}  // namespace gb
