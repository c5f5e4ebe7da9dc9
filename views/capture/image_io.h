// Writing images for people (PNG: RGBA through OpenImageIO, palette through libpng) atomically: a temporary file in the same folder, then rename,
// so an interrupted write never leaves a half file under the real name.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gb {

struct Rgba8Image {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> pixels;  // sRGB-encoded RGBA, rows top to bottom
};

// Returns false and fills `error` (naming the file) on failure.
bool writePng(const std::string& path, const Rgba8Image& image, std::string& error);
// An 8-bit palette PNG (libpng): `indices` (width x height, rows top to bottom) into `palette`
// (sRGB bytes, RGB per entry, at most 256 entries). A colour map's image at a quarter of RGBA's bytes
// and a fraction of its size deflated (smooth indices, where the colours' bytes are not).
bool writeIndexedPng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& indices,
                     const std::vector<uint8_t>& palette, std::string& error);

// Runs `write(tmpPath)`, then renames tmpPath to `path`. Removes the temporary on failure.
bool writeAtomically(const std::string& path, const std::string& suffix,
                     const std::function<bool(const std::string& tmpPath)>& write);
// `text` as the file `path`, through writeAtomically; false with "PATH: cannot write" in `error`.
bool writeTextAtomically(const std::string& path, const std::string& text, std::string& error);

// Destinations checked before any work (compare's -o, --json, --report, --junit): one rule for files
// and folders. A file is written beside itself and renamed into place, so its folder must exist and
// it must not be a folder; a folder (replaceDirectory's rule) may be missing, empty or hold `marker`
// (empty marker: any folder, written into). A symbolic link at either is replaced, never written
// through. False with "FLAG PATH: why".
bool checkFileDestination(const std::string& flag, const std::string& path, std::string& error);
bool checkFolderDestination(const std::string& flag, const std::string& dir, const std::string& marker,
                            const std::string& what, std::string& error);

// Writes a folder atomically: `write(tmp)` fills a fresh folder beside `dir`, which then takes its
// place (an old one moves aside first and is deleted only after the rename). `dir` may be missing,
// empty, or hold `marker` (a file only this kind of folder has: a capture's manifest.json); any
// other folder is refused, never clobbered. `what` names the kind in messages ("capture").
bool replaceDirectory(const std::string& dir, const std::string& marker, const std::string& what,
                      const std::function<bool(const std::string& tmp, std::string& error)>& write,
                      std::string& error);

}  // namespace gb
