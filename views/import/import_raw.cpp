// Raw dumps (import.cpp reads every other source): texels packed as the target's format says, from
// the layout's offset, rows packed or `row_stride` bytes apart. The file's size must be what the
// layout explains: a dump of another size, or one with bytes inserted that shift every texel after
// them, is refused, never read as far as it goes.
#include <algorithm>
#include <cstring>

#include "renderer/core/texels.h"
#include "views/import/import_internal.h"
#include "views/import/import_source.h"

namespace gb {

bool gpuFormatOf(const LayoutTarget& t, TexelFormat& gpu) {
  for (int f = 0; f <= int(TexelFormat::D16); ++f)
    if (t.format.name == texelFormatInfo(TexelFormat(f)).name) {
      gpu = TexelFormat(f);
      return true;
    }
  return false;
}

size_t dumpBytes(const LayoutTarget& t, uint32_t w, uint32_t h) {
  TexelFormat gpu{};
  return gpuFormatOf(t, gpu) ? packedImageBytes(gpu, w, h) : size_t(w) * h * t.format.packedBytes();
}

bool unpackDump(const uint8_t* data, size_t bytes, const LayoutTarget& t, uint32_t w, uint32_t h, const std::string& at,
                CpuImage& img, std::string& error) {
  TexelFormat gpu{};
  const bool isGpuFormat = gpuFormatOf(t, gpu);
  const size_t need = dumpBytes(t, w, h);
  if (bytes < need) {
    error = at + ": holds " + std::to_string(bytes) + " bytes; " + t.format.name + " " + std::to_string(w) + "x" +
            std::to_string(h) + " needs " + std::to_string(need);
    return false;
  }
  if (isGpuFormat) {
    unpackTexelsInto(gpu, data, w, h, img);  // img's buffer kept (TexelPool)
  } else {
    img.name.clear();
    img.width = w;
    img.height = h;
    img.type = t.format.type;
    img.encoding = t.format.encoding;
    img.data.assign(data, data + need);
  }
  img.channels = t.channels;
  return true;
}

namespace {

// Where a raw target's bytes end in its file: offset + rows (`last`: the last row unpadded).
uint64_t rawEnd(const LayoutTarget& t, uint32_t w, uint32_t h, bool last = false) {
  const TargetSource& s = t.source;
  if (!s.rowStride) return s.offset + dumpBytes(t, w, h);
  return s.offset + s.rowStride * (h - (last ? 1 : 0)) + (last ? dumpBytes(t, w, 1) : 0);
}

// The largest end of the other raw targets of the layout that read the same file (a file holding
// several dumps at their offsets); 0 when none does.
uint64_t othersEnd(const ImportInput& in, const LayoutTarget& self, const std::string& path, uint32_t w, uint32_t h) {
  uint64_t end = 0;
  for (const LayoutTarget& t : in.layout.targets) {
    if (t.name == self.name || t.source.kind != TargetSource::Kind::Raw || sourcePath(in, t) != path) continue;
    const uint32_t tw = t.width ? t.width : in.layout.width ? in.layout.width : w;
    const uint32_t th = t.width ? t.height : in.layout.width ? in.layout.height : h;
    end = std::max(end, rawEnd(t, tw, th));
  }
  return end;
}

}  // namespace

bool readRawDump(const ImportInput& in, const LayoutTarget& lt, const std::string& path, uint32_t w, uint32_t h,
                 const std::string& where, CpuImage& img, std::string& error) {
  const TargetSource& s = lt.source;
  const std::string at = where + ": " + path;
  const uint64_t row = dumpBytes(lt, w, 1);
  if (s.rowStride && (lt.format.depth || s.rowStride < row)) {
    error = at + ": source.row_stride: " +
            (lt.format.depth ? std::string("a depth/stencil dump is planes of packed rows; give no row_stride")
                             : std::to_string(s.rowStride) + " is less than a row's " + std::to_string(row) + " bytes");
    return false;
  }
  const uint64_t end = rawEnd(lt, w, h), shortEnd = s.rowStride ? rawEnd(lt, w, h, true) : end;
  std::vector<uint8_t> bytes;
  uint64_t fileBytes = 0;
  if (!readFileRange(path, s.offset, end - s.offset, bytes, fileBytes, where, error)) return false;
  const std::string what = lt.format.name + " " + std::to_string(w) + "x" + std::to_string(h) +
                           (s.rowStride ? ", rows " + std::to_string(s.rowStride) + " bytes apart" : "");
  if (fileBytes < shortEnd) {
    error = at + ": holds " + std::to_string(fileBytes - std::min(s.offset, fileBytes)) + " bytes after offset " +
            std::to_string(s.offset) + "; " + what + " needs " + std::to_string(shortEnd - s.offset);
    return false;
  }
  // The size must be explained: this dump's end, or another dump's of the same file beyond it.
  const uint64_t others = othersEnd(in, lt, path, w, h);
  if (fileBytes != std::max(others, end) && fileBytes != std::max(others, shortEnd)) {
    error = at + ": " + std::to_string(fileBytes) + " bytes, the layout explains " + std::to_string(std::max(others, end)) +
            " (offset " + std::to_string(s.offset) + " + " + what +
            "): a dump of another size, or bytes inserted that would shift the texels; give source.offset or "
            "source.row_stride if the file is laid out so";
    return false;
  }
  if (s.rowStride) {  // the rows packed together, as unpackDump reads them
    std::vector<uint8_t> packed(size_t(row) * h);
    for (uint32_t y = 0; y < h; ++y) std::memcpy(&packed[size_t(row) * y], &bytes[size_t(s.rowStride) * y], size_t(row));
    bytes.swap(packed);
  }
  return unpackDump(bytes.data(), bytes.size(), lt, w, h, at, img, error);
}

}  // namespace gb
