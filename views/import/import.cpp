// Importing a G-buffer (see import.h): sources -> CpuImages checked against the layout, the camera
// in gblens's convention, the lights, one FrameSnapshot.
#include "views/import/import.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "renderer/core/assets.h"
#include "renderer/core/json_read.h"
#include "renderer/core/layout_json.h"
#include "renderer/core/library_output.h"
#include "renderer/core/texels.h"
#include "views/import/import_internal.h"
#include "views/import/import_source.h"

namespace gb {

namespace fs = std::filesystem;

std::string layoutTargetWhere(const Layout& l, uint32_t t) {
  return (l.file.empty() ? std::string("layout") : l.file) + ": targets[" + std::to_string(t) + "]: \"" +
         l.targets[t].name + "\"";
}

bool needsCamera(const Quantity& q) {
  return (q.kind == QuantityKind::Depth && !q.ofSun && q.depth != DepthEncoding::Eye) ||
         ((q.kind == QuantityKind::Normal || q.kind == QuantityKind::Position) && q.space != Space::View);
}

namespace {

std::string targetWhere(const Layout& l, uint32_t t) { return layoutTargetWhere(l, t); }

}  // namespace

// Where a source file is: a file given on the command line of that name, else beside the layout. A
// target without a file name takes the only file given, or the one named as the target (albedo.exr).
std::string sourcePath(const ImportInput& in, const LayoutTarget& t) {
  const TargetSource& s = t.source;
  if (s.path.empty()) {
    if (in.files.size() == 1) return in.files[0];
    for (const std::string& f : in.files)
      if (fs::path(f).stem() == t.name) return f;
    return std::string();
  }
  for (const std::string& f : in.files)
    if (f == s.path || fs::path(f).filename() == fs::path(s.path).filename()) return f;
  fs::path p(s.path);
  return p.is_absolute() || in.layoutDir.empty() ? s.path : (fs::path(in.layoutDir) / p).string();
}

namespace {

OIIO::TypeDesc fileType(PixelType t) {
  switch (t) {
    case PixelType::U8: return OIIO::TypeDesc::UINT8;
    case PixelType::I8: return OIIO::TypeDesc::INT8;
    case PixelType::U16: return OIIO::TypeDesc::UINT16;
    case PixelType::I16: return OIIO::TypeDesc::INT16;
    case PixelType::U32: return OIIO::TypeDesc::UINT32;
    case PixelType::F16: return OIIO::TypeDesc::HALF;
    case PixelType::F32: return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::UNKNOWN;
}

// Moves to the EXR part a source names (an index or a part name).
bool seekPart(OIIO::ImageInput& in, const std::string& part, const std::string& where, std::string& error) {
  if (part.empty()) return true;
  char* end = nullptr;
  long index = std::strtol(part.c_str(), &end, 10);
  if (*end == '\0' && index >= 0 && index <= 65535) {
    if (in.seek_subimage(int(index), 0)) return true;
    error = where + ": source.part: the file has no part " + part;
    return false;
  }
  // OpenImageIO gives an EXR part's name as "oiio:subimagename".
  for (int i = 0; in.seek_subimage(i, 0); ++i)
    if (in.spec().get_string_attribute("oiio:subimagename") == part || in.spec().get_string_attribute("name") == part)
      return true;
  error = where + ": source.part: the file has no part named \"" + part + "\"";
  return false;
}

// Reads an image file's channels; a target with a list of formats gets the one the file holds.
bool readImageFile(const std::string& path, const TargetSource& s, LayoutTarget& t, const std::string& where,
                   uint32_t w, uint32_t h, CpuImage& img, std::string& error) {
  const std::string at = where + ": " + path;
  if (t.format.depth || t.format.packed10) {
    error = at + ": format: " + t.format.name + " is a packed GPU format; give it as a raw dump";
    return false;
  }
  auto in = openImportImage(path, where, error);
  if (!in) return false;
  if (!seekPart(*in, s.part, at, error)) return false;
  const OIIO::ImageSpec& spec = in->spec();
  // The size the file declares, against the layout's, before anything is allocated for it.
  if (uint32_t(spec.width) != w || uint32_t(spec.height) != h || spec.depth > 1) {
    error = where + ": " + path + ": size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
            ", the layout says " + std::to_string(w) + "x" + std::to_string(h);
    return false;
  }
  std::vector<int> index;
  std::vector<std::string> names = s.channels;
  if (names.empty())
    for (int i = 0; i < int(t.format.channels) && i < spec.nchannels; ++i) names.push_back(spec.channelnames[size_t(i)]);
  if (names.size() != t.format.channels) {
    error = at + ": source.channels: the file has " + std::to_string(spec.nchannels) + " channels, format " +
            t.format.name + " needs " + std::to_string(t.format.channels);
    return false;
  }
  for (const std::string& n : names) {
    auto it = std::find(spec.channelnames.begin(), spec.channelnames.end(), n);
    if (it == spec.channelnames.end()) {
      std::string all;
      for (const std::string& c : spec.channelnames) all += (all.empty() ? "" : ", ") + c;
      error = at + ": source.channels: no channel \"" + n + "\" (the file has " + all + ")";
      return false;
    }
    index.push_back(int(it - spec.channelnames.begin()));
  }
  // The format: the layout's, or the one of its list the file's channel type is held in exactly.
  for (size_t k = 0; k < names.size(); ++k) {
    const OIIO::TypeDesc type = spec.channelformat(index[k]);
    if (k == 0 && !t.formatChoices.empty()) {
      std::string list;
      for (const StorageFormat& f : t.formatChoices) {
        if (type == fileType(f.type)) t.format = f;
        list += (list.empty() ? "" : ", ") + f.name;
      }
      if (type != fileType(t.format.type)) {
        error = at + ": format: channel \"" + names[k] + "\" is " + type.c_str() + "; none of " + list + " holds it exactly";
        return false;
      }
    }
    if (type != fileType(t.format.type)) {
      const bool half = type == OIIO::TypeDesc::FLOAT && t.format.type == PixelType::F16;
      error = at + ": format: channel \"" + names[k] + "\" is " + type.c_str() + "; " + t.format.name + " holds only " +
              fileType(t.format.type).c_str() + " exactly" +
              (half ? " (a full-float file: give the target's format as [\"" + t.format.name + "\", \"" +
                          t.format.name.substr(0, t.format.name.size() - 3) + "32f\"] to accept both)"
                    : "");
      return false;
    }
  }
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.type = t.format.type;
  img.encoding = t.format.encoding;
  img.channels = t.channels;
  const size_t size = pixelTypeSize(img.type), texels = size_t(img.width) * img.height;
  size_t pixelBytes = 0;
  std::vector<size_t> offset(size_t(spec.nchannels));
  for (int i = 0; i < spec.nchannels; ++i) {
    offset[size_t(i)] = pixelBytes;
    pixelBytes += spec.channelformat(i).size();
  }
  std::vector<uint8_t> buf(texels * pixelBytes);
  LibraryOutput library;
  if (!in->read_image(in->current_subimage(), 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, buf.data())) {
    std::string detail = in->geterror();
    for (char& c : detail)
      if (c == '\n') c = ' ';
    error = at + ": cannot read pixels (" + detail + ")" + library.suffix();
    return false;
  }
  img.data.resize(texels * img.texelBytes());
  for (size_t i = 0; i < texels; ++i)
    for (size_t k = 0; k < index.size(); ++k)
      std::memcpy(&img.data[i * img.texelBytes() + k * size], &buf[i * pixelBytes + offset[size_t(index[k])]], size);
  return true;
}

void flipRows(CpuImage& img) {
  const size_t row = size_t(img.width) * img.texelBytes();
  for (uint32_t y = 0; y < img.height / 2; ++y)
    std::swap_ranges(img.data.begin() + long(y * row), img.data.begin() + long((y + 1) * row),
                     img.data.begin() + long((img.height - 1 - y) * row));
}

// One target's texels; `lt` (the frame's copy of the layout's target) gets the format a file holds.
// A multisampled attachment's planes, one per sample, each `stride` bytes (app/layer/samples.cpp
// streams them so, renderdoc_replay.py reads them so); `img` is sample 0.
bool readSamplePlanes(const uint8_t* data, size_t bytes, uint32_t count, size_t stride, const LayoutTarget& lt, uint32_t w,
                      uint32_t h, const std::string& where, CpuImage& img, std::vector<CpuImage>& samples, std::string& error,
                      TexelPool* pool = nullptr) {
  if (stride == 0 || bytes / stride < count) {
    error = where + ": " + std::to_string(count) + " samples do not fit the " + std::to_string(bytes) + " bytes read";
    return false;
  }
  samples.resize(count);
  for (uint32_t k = 0; k < count; ++k) {
    if (pool) samples[k].data = pool->take(stride);
    if (!unpackDump(data + k * stride, stride, lt, w, h, where + " (sample " + std::to_string(k) + ")", samples[k], error))
      return false;
  }
  img = samples[0];
  return true;
}

bool readTarget(const ImportInput& in, uint32_t t, LayoutTarget& lt, uint32_t w, uint32_t h, CpuImage& img,
                std::vector<CpuImage>& samples, std::string& error) {
  const Layout& l = in.layout;
  const std::string where = targetWhere(l, t);
  const TargetSource& s = lt.source;
  if (s.kind == TargetSource::Kind::RenderDoc) {
    auto it = in.renderdocTexels.find(lt.name);
    if (in.renderdocTexels.empty()) {
      error = where + ": source.renderdoc: \"" + s.resource + "\" is a texture of a RenderDoc capture: import the .rdc";
      return false;
    }
    if (it == in.renderdocTexels.end()) {
      error = where + ": source.renderdoc: the capture has no texture \"" + s.resource + "\"";
      return false;
    }
    const std::string from = where + ": source.renderdoc \"" + s.resource + "\"";
    auto count = in.renderdocSamples.find(lt.name);
    if (count != in.renderdocSamples.end())
      return readSamplePlanes(it->second.data(), it->second.size(), count->second, it->second.size() / count->second, lt, w, h,
                              from, img, samples, error);
    return unpackDump(it->second.data(), it->second.size(), lt, w, h, from, img, error);
  }
  if (s.kind == TargetSource::Kind::Live) {
    auto it = in.liveTexels.find(lt.name);
    if (it == in.liveTexels.end()) {
      error = where + ": source.live: an attachment of a running application: stream it with gblens attach";
      return false;
    }
    const ImportInput::LiveTexels& live = it->second;
    if (live.samples <= 1) {
      if (in.pool) img.data = in.pool->take(live.bytes);
      return unpackDump(live.data, live.bytes, lt, w, h, where + ": source.live", img, error);
    }
    return readSamplePlanes(live.data, live.bytes, live.samples, live.sampleStride, lt, w, h, where + ": source.live", img, samples,
                            error, in.pool);
  }
  const std::string path = sourcePath(in, lt);
  if (path.empty()) {
    error = where + ": source.file: missing (give the file in the layout, exactly one on the command line, or one named " +
            lt.name + ".*)";
    return false;
  }
  if (!sourceAllowed(in, path, where, "source.file", error)) return false;
  if (s.kind == TargetSource::Kind::Raw) return readRawDump(in, lt, path, w, h, where, img, error);
  return readImageFile(path, s, lt, where, w, h, img, error);
}

// The layout's lights in gblens's world (Y up) and as the probe reads them (eye space, uploaded form).
void importLights(const Layout& l, FrameSnapshot& f) {
  const LayoutLights& lights = l.lights;
  f.sun.enabled = false;
  f.sky.ambient = glm::vec3(0.0f);
  // gblens's sky and shadow-map projection are its renderer's; another renderer's frame states neither.
  for (const char* key : {"sky.zenith", "sky.horizon", "sky.ground"}) f.unknown[key] = "gblens's sky; the source has none";
  f.unknown["lightClipFromWorld"] = "gblens's shadow-map projection; the source has none";
  if (!lights.present) {
    const std::string why = "the layout gives no lights";
    for (const char* key : {"sun", "sky.ambient", "lights"}) f.unknown[key] = why;
    return;
  }
  const glm::dmat3 toWorld = worldFromLayoutWorld(l.camera);
  auto world = [&](glm::dvec3 v) { return toWorld * v; };
  f.sun = lights.sun;
  if (f.sun.enabled) f.sun.toSun = glm::normalize(world(lights.sun.toSun));
  f.sky.ambient = lights.ambient;
  for (PointLightDesc p : lights.points) {
    p.center = world(p.center);
    f.lightDescs.push_back(p);
    gpu::PointLight g{};
    g.eyePositionRadius = glm::vec4(glm::vec3(f.camera.eyeFromWorld * glm::dvec4(p.center, 1.0)), float(p.radius));
    g.color = glm::vec4(p.color * float(p.intensity), 0.0f);
    f.visibleLights.push_back(uint32_t(f.eyeLights.size()));
    f.eyeLights.push_back(g);
  }
  f.stencilCount = uint32_t(f.visibleLights.size());
}

// The frame's camera: the layout's (or --camera's), resolved and converted; without one, only
// quantities that need none.
bool frameCamera(const ImportInput& in, uint32_t w, uint32_t h, LayoutCamera& camera, Camera& out, std::string& error) {
  const Layout& l = in.layout;
  if (!camera.present && in.cameraFile.empty()) {
    for (const Quantity& q : l.quantities) {
      if (needsCamera(q)) {
        error = targetWhere(l, q.target) + ": quantities \"" + q.name + "\": needs the layout's camera (\"camera\")";
        return false;
      }
    }
    out.width = w;
    out.height = h;
    return true;
  }
  camera.present = true;
  if (!resolveCamera(in, camera, w, h, error)) return false;
  std::string why;
  if (!settleWorldHandedness(camera, why) || !importCamera(camera, w, h, out, why)) {
    error = (l.file.empty() ? std::string("layout") : l.file) + ": " + why;
    return false;
  }
  if (orthographic(out))  // the distance from an orthographic "eye" says nothing the eye depth does not
    for (const Quantity& q : l.quantities)
      if (q.kind == QuantityKind::Depth && q.depth == DepthEncoding::Radial && !q.ofSun) {
        error = targetWhere(l, q.target) + ": quantities \"" + q.name +
                "\": encoding: radial distance with an orthographic camera is its eye depth; say \"eye\"";
        return false;
      }
  return true;
}

}  // namespace

std::string builtinLayoutNames() {
  std::string names;
  for (const auto& [path, unused] : assets())
    if (path.rfind("layouts/", 0) == 0 && fs::path(path).extension() == ".json")
      names += (names.empty() ? "builtin:" : ", builtin:") + fs::path(path).stem().string();
  return names;
}

void setImportedOptions(FrameSnapshot& frame, const RenderOptions& options, const std::vector<std::string>& stated) {
  const RenderOptions imported = frame.options;
  frame.options = options;
  frame.options.width = imported.width, frame.options.height = imported.height;
  frame.options.reversedZ = imported.reversedZ;
  // The frame states its size and depth direction, the user the --param values; the rest are defaults.
  frame.statedOptions = stated;
  for (const char* own : {"size", "reversed_z"})
    if (std::find(stated.begin(), stated.end(), own) == stated.end()) frame.statedOptions.push_back(own);
  frame.unknown["options"] = "the source states only size and reversed_z (and the --param values given)";
  if (std::find(stated.begin(), stated.end(), "time") == stated.end()) frame.unknown["time"] = "not stated by the source";
}

bool loadImportLayout(const std::string& spec, const LayoutParameters& params, Layout& out, std::string& dir,
                      std::string& error) {
  dir.clear();
  if (spec.rfind("builtin:", 0) != 0) {
    std::error_code ec;
    const std::string stem = fs::path(spec).stem().string();
    if (!fs::exists(spec, ec) && assetText("layouts/" + stem + ".json")) {
      error = spec + ": no such layout file; the layout gblens carries is --layout builtin:" + stem;
      return false;
    }
    dir = fs::path(spec).parent_path().string();
    return loadLayoutFile(spec, params, out, error);
  }
  const std::string* text = assetText("layouts/" + spec.substr(8) + ".json");
  if (!text) {
    error = spec + ": no such built-in layout (built in: " + builtinLayoutNames() + ")";
    return false;
  }
  nlohmann::json j;
  if (!parseJson(*text, spec, j, error)) return false;
  return resolveLayoutParameters(j, params, spec, error) && parseLayout(j, spec, out, error);
}

std::vector<uint8_t> TexelPool::take(size_t bytes) {
  auto best = spare.end();
  for (auto it = spare.begin(); it != spare.end(); ++it)
    if (it->capacity() >= bytes && (best == spare.end() || it->capacity() < best->capacity())) best = it;
  if (best == spare.end()) return {};
  std::vector<uint8_t> out = std::move(*best);
  spare.erase(best);
  return out;
}

void TexelPool::give(FrameSnapshot&& frame, size_t keep) {
  for (TargetImage& t : frame.images) {
    if (t.image.data.capacity()) spare.push_back(std::move(t.image.data));
    for (CpuImage& s : t.samples)
      if (s.data.capacity()) spare.push_back(std::move(s.data));
  }
  frame = FrameSnapshot{};
  if (spare.size() > keep) spare.erase(spare.begin(), spare.end() - long(keep));  // the newest kept
}

bool importFrame(const ImportInput& in, FrameSnapshot& out, std::string& error) {
  const Layout& l = in.layout;
  Layout frameLayout = l;  // with the formats files were found to hold (a target's list of formats)
  out = FrameSnapshot{};
  std::vector<CpuImage> images(l.targets.size());
  std::vector<std::vector<CpuImage>> sampleImages(l.targets.size());  // multisampled targets: every sample
  uint32_t w = l.width, h = l.height;
  for (uint32_t t = 0; t < l.targets.size(); ++t) {
    const LayoutTarget& lt = l.targets[t];
    if (in.leftOut.count(lt.name)) continue;
    uint32_t tw = lt.width ? lt.width : l.width, th = lt.width ? lt.height : l.height;
    auto rdcSize = in.renderdocSizes.find(lt.name);
    if (rdcSize != in.renderdocSizes.end()) {  // a RenderDoc texture: its size must be the layout's
      const auto [rw, rh] = rdcSize->second;
      if (tw && (rw != tw || rh != th)) {
        error = targetWhere(l, t) + ": size: the capture's texture \"" + lt.source.resource + "\" is " +
                std::to_string(rw) + "x" + std::to_string(rh) + ", the layout says " + std::to_string(tw) + "x" +
                std::to_string(th);
        return false;
      }
      tw = rw, th = rh;
    }
    if (auto live = in.liveTexels.find(lt.name); live != in.liveTexels.end()) {  // a streamed attachment: the same rule
      const uint32_t rw = live->second.width, rh = live->second.height;
      if (tw && (rw != tw || rh != th)) {
        error = targetWhere(l, t) + ": size: the streamed attachment is " + std::to_string(rw) + "x" + std::to_string(rh) +
                ", the layout says " + std::to_string(tw) + "x" + std::to_string(th);
        return false;
      }
      tw = rw, th = rh;
    }
    if (!tw && (lt.source.kind == TargetSource::Kind::File || lt.source.kind == TargetSource::Kind::None)) {  // the file's
      std::string ignored;  // a file that does not open (or may not be read) is reported by readTarget
      const std::string path = sourcePath(in, lt);
      auto inp = sourceAllowed(in, path, "", "", ignored) ? openImportImage(path, targetWhere(l, t), ignored) : nullptr;
      if (inp) tw = uint32_t(std::max(inp->spec().width, 0)), th = uint32_t(std::max(inp->spec().height, 0));
    }
    if (!tw) tw = w, th = h;  // a raw dump without a size: the frame's (the first target's)
    if (!tw) {
      error = targetWhere(l, t) + ": size: unknown (give the layout's or the target's size, or --size)";
      return false;
    }
    if (!checkImportSize(targetWhere(l, t), tw, th, error)) return false;
    if (!w) w = tw, h = th;
    if (!readTarget(in, t, frameLayout.targets[t], tw, th, images[t], sampleImages[t], error)) return false;
    frameLayout.targets[t].formatChoices.clear();
    // A target of another size than the frame's says so in the frame's layout (the manifest check
    // holds every other target to the frame's size).
    if (tw != w || th != h) frameLayout.targets[t].width = tw, frameLayout.targets[t].height = th;
    images[t].name = l.targets[t].name;
    for (CpuImage& sample : sampleImages[t]) sample.name = l.targets[t].name;
  }
  out.setLayout(frameLayout);
  LayoutCamera camera = l.camera;
  if (!frameCamera(in, w, h, camera, out.camera, error)) return false;
  if (camera.bottomOrigin)  // after the camera is resolved: a sidecar may say so
    for (size_t t = 0; t < images.size(); ++t) {
      flipRows(images[t]);
      for (CpuImage& sample : sampleImages[t]) flipRows(sample);
    }
  // The manifest embeds the camera as imported: its matrices in the layout's conventions, where they
  // were read from (`from`), and rows top first (the images were flipped just above).
  camera.sidecar.clear();
  camera.renderdoc.reset();
  camera.bottomOrigin = false;
  out.layout.camera = camera;
  out.options.width = w;
  out.options.height = h;
  out.options.reversedZ = out.camera.reversedZ;
  for (uint32_t t = 0; t < l.targets.size(); ++t) {
    if (images[t].empty()) {  // left out: the source has no such image
      if (in.leftOut.count(l.targets[t].name)) out.absences[t] = Absent::NotInSource;
      continue;
    }
    TargetImage& ti = out.images[t];
    ti.image = std::move(images[t]);
    ti.samples = std::move(sampleImages[t]);
    ti.targetWidth = ti.image.width;
    ti.targetHeight = ti.image.height;
    out.absences[t] = Absent::No;
  }
  importLights(out.layout, out);
  return true;
}

}  // namespace gb
