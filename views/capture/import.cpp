// Importing a G-buffer (see import.h): sources -> CpuImages checked against the layout, the camera
// in gblens's convention, the lights, one FrameSnapshot.
#include "views/capture/import.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "renderer/core/assets.h"
#include "renderer/core/layout_json.h"
#include "renderer/core/texels.h"

namespace gb {

namespace fs = std::filesystem;

std::string layoutTargetWhere(const Layout& l, uint32_t t) {
  return (l.file.empty() ? std::string("layout") : l.file) + ": targets[" + std::to_string(t) + "]: \"" +
         l.targets[t].name + "\"";
}

namespace {

std::string targetWhere(const Layout& l, uint32_t t) { return layoutTargetWhere(l, t); }

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
  if (*end == '\0') {
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

bool readImageFile(const std::string& path, const TargetSource& s, const LayoutTarget& t, const std::string& where,
                   CpuImage& img, std::string& error) {
  const std::string at = where + ": " + path;
  if (t.format.depth || t.format.packed10) {
    error = at + ": format: " + t.format.name + " is a packed GPU format; give it as a raw dump";
    return false;
  }
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    error = at + ": source.file: cannot read the image (" + OIIO::geterror() + ")";
    return false;
  }
  if (!seekPart(*in, s.part, at, error)) return false;
  const OIIO::ImageSpec& spec = in->spec();
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
    const OIIO::TypeDesc type = spec.channelformat(index.back());
    if (type != fileType(t.format.type)) {
      error = at + ": format: channel \"" + n + "\" is " + type.c_str() + "; " + t.format.name +
              " holds only " + fileType(t.format.type).c_str() + " exactly";
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
  if (!in->read_image(in->current_subimage(), 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, buf.data())) {
    error = at + ": cannot read pixels (" + in->geterror() + ")";
    return false;
  }
  img.data.resize(texels * img.texelBytes());
  for (size_t i = 0; i < texels; ++i)
    for (size_t k = 0; k < index.size(); ++k)
      std::memcpy(&img.data[i * img.texelBytes() + k * size], &buf[i * pixelBytes + offset[size_t(index[k])]], size);
  return true;
}

// A packed dump (raw file or RenderDoc texels) of a target's format.
bool unpackDump(const uint8_t* data, size_t size, uint64_t offset, const LayoutTarget& t, uint32_t w, uint32_t h,
                const std::string& at, CpuImage& img, std::string& error) {
  TexelFormat gpu{};
  bool isGpuFormat = false;
  for (int f = 0; f <= int(TexelFormat::D16); ++f)
    if (t.format.name == texelFormatInfo(TexelFormat(f)).name) {
      gpu = TexelFormat(f);
      isGpuFormat = true;
    }
  const size_t need = isGpuFormat ? packedImageBytes(gpu, w, h) : size_t(w) * h * t.format.packedBytes();
  if (size < offset || size - offset < need) {
    error = at + ": holds " + std::to_string(size - std::min<size_t>(offset, size)) + " bytes after offset " +
            std::to_string(offset) + "; " + t.format.name + " " + std::to_string(w) + "x" + std::to_string(h) + " needs " +
            std::to_string(need);
    return false;
  }
  const uint8_t* src = data + offset;
  if (isGpuFormat) {
    img = unpackTexels(gpu, src, w, h);
  } else {
    img.width = w;
    img.height = h;
    img.type = t.format.type;
    img.encoding = t.format.encoding;
    img.data.assign(src, src + need);
  }
  img.channels = t.channels;
  return true;
}

bool readFile(const std::string& path, std::vector<uint8_t>& out, std::string& error, const std::string& at) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    error = at + ": source.file: cannot read " + path;
    return false;
  }
  out.assign(std::istreambuf_iterator<char>(f), {});
  return true;
}

void flipRows(CpuImage& img) {
  const size_t row = size_t(img.width) * img.texelBytes();
  for (uint32_t y = 0; y < img.height / 2; ++y)
    std::swap_ranges(img.data.begin() + long(y * row), img.data.begin() + long((y + 1) * row),
                     img.data.begin() + long((img.height - 1 - y) * row));
}

bool readTarget(const ImportInput& in, uint32_t t, uint32_t w, uint32_t h, CpuImage& img, std::string& error) {
  const Layout& l = in.layout;
  const LayoutTarget& lt = l.targets[t];
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
    return unpackDump(it->second.data(), it->second.size(), 0, lt, w, h, where + ": source.renderdoc \"" + s.resource + "\"",
                      img, error);
  }
  if (s.kind == TargetSource::Kind::Live) {
    auto it = in.liveTexels.find(lt.name);
    if (it == in.liveTexels.end()) {
      error = where + ": source.live: an attachment of a running application: stream it with gblens attach";
      return false;
    }
    return unpackDump(it->second.data, it->second.bytes, 0, lt, w, h, where + ": source.live", img, error);
  }
  const std::string path = sourcePath(in, lt);
  if (path.empty()) {
    error = where + ": source.file: missing (give the file in the layout, exactly one on the command line, or one named " +
            lt.name + ".*)";
    return false;
  }
  if (s.kind == TargetSource::Kind::Raw) {
    std::vector<uint8_t> bytes;
    return readFile(path, bytes, error, where) &&
           unpackDump(bytes.data(), bytes.size(), s.offset, lt, w, h, where + ": " + path, img, error);
  }
  if (!readImageFile(path, s, lt, where, img, error)) return false;
  if (img.width != w || img.height != h) {
    error = where + ": " + path + ": size " + std::to_string(img.width) + "x" + std::to_string(img.height) +
            ", the layout says " + std::to_string(w) + "x" + std::to_string(h);
    return false;
  }
  return true;
}

glm::dmat4 matrixFromFloats(const std::vector<uint8_t>& bytes, uint64_t offset, bool rowMajor) {
  glm::dmat4 m(1.0);
  for (int i = 0; i < 16; ++i) {
    float v;
    std::memcpy(&v, bytes.data() + offset + size_t(i) * 4, 4);
    if (rowMajor)
      m[i % 4][i / 4] = v;
    else
      m[i / 4][i % 4] = v;
  }
  return m;
}

// The camera's size, when it gives one, against the images' (the projection's aspect is for it).
bool checkCameraSize(const LayoutCamera& c, const std::string& from, uint32_t w, uint32_t h, std::string& error) {
  if (!c.width || (c.width == w && c.height == h)) return true;
  error = from + ": camera: size: the matrices are for " + std::to_string(c.width) + "x" + std::to_string(c.height) +
          ", the images are " + std::to_string(w) + "x" + std::to_string(h);
  return false;
}

// The layout's camera with its matrices filled from the sidecar or the uniform buffer, for images
// of w x h.
bool resolveCamera(const ImportInput& in, LayoutCamera& c, uint32_t w, uint32_t h, std::string& error) {
  const std::string file = in.layout.file.empty() ? std::string("layout") : in.layout.file;
  const std::string where = file + ": camera";
  std::string sidecar = !in.cameraFile.empty() ? in.cameraFile : c.sidecar;
  if (!sidecar.empty()) {
    if (in.cameraFile.empty() && fs::path(sidecar).is_relative()) {
      // Beside the imported files first (a renderer writes its camera beside its images; Blender's
      // script does), then beside the layout.
      std::string found;
      std::error_code ec;
      for (const std::string& input : in.files)
        if (found.empty() && fs::exists(fs::path(input).parent_path() / sidecar, ec))
          found = (fs::path(input).parent_path() / sidecar).string();
      if (found.empty() && !in.layoutDir.empty()) found = (fs::path(in.layoutDir) / sidecar).string();
      if (!found.empty()) sidecar = found;
    }
    std::ifstream f(sidecar);
    // The layout's conventions, the sidecar's matrices (and whatever conventions it gives).
    nlohmann::json j = layoutCameraJson(c), side;
    for (const char* key : {"sidecar", "renderdoc", "view_from_world", "clip_from_view"}) j.erase(key);
    try {
      if (!f) throw std::runtime_error("cannot read the file");
      side = nlohmann::json::parse(f);
      if (!side.is_object()) throw std::runtime_error("expected a JSON object");
    } catch (const std::exception& e) {
      error = where + ": sidecar: " + sidecar + ": " + e.what();
      return false;
    }
    for (auto& [k, v] : side.items()) j[k] = v;
    return parseLayoutCamera(j, sidecar, c, error) && checkCameraSize(c, sidecar, w, h, error);
  }
  if (c.renderdoc) {
    const LayoutCamera::BufferMatrix& b = *c.renderdoc;
    const std::vector<uint8_t>& bytes = in.renderdocCameraBuffer;
    if (bytes.empty()) {
      error = where + ": renderdoc: the matrices are in buffer \"" + b.buffer +
              "\" of a RenderDoc capture; import the .rdc, or give the camera with --camera";
      return false;
    }
    if (bytes.size() < std::max(b.viewOffset, b.clipOffset) + 64) {
      error = where + ": renderdoc: buffer \"" + b.buffer + "\" holds " + std::to_string(bytes.size()) +
              " bytes, the matrices need " + std::to_string(std::max(b.viewOffset, b.clipOffset) + 64);
      return false;
    }
    glm::dmat4 view = matrixFromFloats(bytes, b.viewOffset, b.rowMajor);
    c.clipFromView = matrixFromFloats(bytes, b.clipOffset, b.rowMajor);
    for (auto [m, name] : {std::pair{&view, "view matrix"}, {&c.clipFromView, "clip_from_view"}})
      if (!(std::abs(glm::determinant(*m)) > 1e-30)) {
        error = where + ": renderdoc: " + name + " read from \"" + b.buffer + "\" is singular";
        return false;
      }
    c.viewFromWorld = b.worldFromView ? glm::inverse(view) : view;
  }
  return checkCameraSize(c, file, w, h, error);
}

// The layout's lights in gblens's world (Y up) and as the probe reads them (eye space, uploaded form).
void importLights(const Layout& l, FrameSnapshot& f) {
  const LayoutLights& lights = l.lights;
  f.sun.enabled = false;
  f.sky.ambient = glm::vec3(0.0f);
  if (!lights.present) return;
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

}  // namespace

bool importCamera(const LayoutCamera& c, uint32_t width, uint32_t height, Camera& out, std::string& error) {
  // gblens eye space = S * source view space (S flips Z for a left-handed view); gblens world =
  // R * source world (R turns Z up into Y up). Clip space: Vulkan's, y down, depth 0..1.
  glm::dmat4 S(1.0), R(1.0), C(1.0);
  if (c.leftHanded) S[2][2] = -1.0;
  R = glm::dmat4(worldFromLayoutWorld(c));
  if (c.convention != LayoutCamera::Convention::Vulkan) C[1][1] = -1.0;  // NDC y up -> down (rows are top first)
  if (c.convention == LayoutCamera::Convention::Gl) {  // z' = (z + w) / 2
    C[2][2] = 0.5;
    C[3][2] = 0.5;
  }
  out = Camera{};
  out.width = width;
  out.height = height;
  out.eyeFromWorld = S * c.viewFromWorld * glm::inverse(R);
  out.worldFromEye = glm::inverse(out.eyeFromWorld);
  out.clipFromEye = C * c.clipFromView * glm::inverse(S);
  const double det = glm::determinant(out.clipFromEye);
  if (!std::isfinite(det) || std::abs(det) < 1e-300) {
    error = "camera: clip_from_view: singular after conversion";
    return false;
  }
  out.eyeFromClip = glm::inverse(out.clipFromEye);
  out.clipFromWorld = out.clipFromEye * out.eyeFromWorld;
  const glm::dmat4& p = out.clipFromEye;
  out.yfov = 2.0 * std::atan(1.0 / std::abs(p[1][1]));
  out.aspect = std::abs(p[1][1] / p[0][0]);
  // Where the far plane lands: 0 for reversed Z (a perspective's depth at infinity is -p22 / p23 ...).
  const double farDepth = hardwareDepth(out, {0.0, 0.0, -1e12});
  out.reversedZ = farDepth < 0.5;
  auto depthAt = [&](double target) {  // eye depth where the hardware depth is `target` (bisection)
    double lo = 1e-9, hi = 1e12;
    for (int i = 0; i < 200; ++i) {
      double mid = std::sqrt(lo * hi);
      (hardwareDepth(out, {0.0, 0.0, -mid}) < target) != out.reversedZ ? lo = mid : hi = mid;
    }
    return lo;
  };
  out.znear = depthAt(out.reversedZ ? 1.0 : 0.0);
  out.zfar = depthAt(out.reversedZ ? 0.0 : 1.0);
  return true;
}

void setImportedOptions(FrameSnapshot& frame, const RenderOptions& options) {
  const RenderOptions imported = frame.options;
  frame.options = options;
  frame.options.width = imported.width, frame.options.height = imported.height;
  frame.options.reversedZ = imported.reversedZ;
}

bool loadImportLayout(const std::string& spec, const LayoutParameters& params, Layout& out, std::string& dir,
                      std::string& error) {
  dir.clear();
  if (spec.rfind("builtin:", 0) != 0) {
    dir = fs::path(spec).parent_path().string();
    return loadLayoutFile(spec, params, out, error);
  }
  const std::string* text = assetText("layouts/" + spec.substr(8) + ".json");
  if (!text) {
    std::string names;
    for (const auto& [path, unused] : assets())
      if (path.rfind("layouts/", 0) == 0 && fs::path(path).extension() == ".json")
        names += (names.empty() ? "builtin:" : ", builtin:") + fs::path(path).stem().string();
    error = spec + ": no such built-in layout (built in: " + names + ")";
    return false;
  }
  nlohmann::json j = nlohmann::json::parse(*text);
  return resolveLayoutParameters(j, params, spec, error) && parseLayout(j, spec, out, error);
}

bool importFrame(const ImportInput& in, FrameSnapshot& out, std::string& error) {
  const Layout& l = in.layout;
  out = FrameSnapshot{};
  out.setLayout(l);
  std::vector<CpuImage> images(l.targets.size());
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
      auto inp = OIIO::ImageInput::open(sourcePath(in, lt));
      if (inp) tw = uint32_t(inp->spec().width), th = uint32_t(inp->spec().height);
    }
    if (!tw) tw = w, th = h;  // a raw dump without a size: the frame's (the first target's)
    if (!tw) {
      error = targetWhere(l, t) + ": size: unknown (give the layout's or the target's size, or --size)";
      return false;
    }
    if (!w) w = tw, h = th;
    if (!readTarget(in, t, tw, th, images[t], error)) return false;
    images[t].name = l.targets[t].name;
  }
  LayoutCamera camera = l.camera;
  if (camera.present || !in.cameraFile.empty()) {
    camera.present = true;
    if (!resolveCamera(in, camera, w, h, error)) return false;
    std::string why;
    if (!importCamera(camera, w, h, out.camera, why)) {
      error = (l.file.empty() ? std::string("layout") : l.file) + ": " + why;
      return false;
    }
  } else {
    for (const Quantity& q : l.quantities) {
      const bool needsCamera = (q.kind == QuantityKind::Depth && !q.ofSun && q.depth != DepthEncoding::Eye) ||
                               ((q.kind == QuantityKind::Normal || q.kind == QuantityKind::Position) && q.space != Space::View);
      if (needsCamera) {
        error = targetWhere(l, q.target) + ": quantities \"" + q.name + "\": needs the layout's camera (\"camera\")";
        return false;
      }
    }
    out.camera.width = w;
    out.camera.height = h;
  }
  if (camera.bottomOrigin)  // after the camera is resolved: a sidecar may say so
    for (CpuImage& image : images) flipRows(image);
  // The manifest embeds the camera as imported: its matrices in the layout's conventions (not where
  // they were read from), and rows top first (the images were flipped just above).
  camera.sidecar.clear();
  camera.renderdoc.reset();
  camera.bottomOrigin = false;
  out.layout.camera = camera;
  out.options.width = w;
  out.options.height = h;
  out.options.reversedZ = out.camera.reversedZ;
  for (uint32_t t = 0; t < l.targets.size(); ++t) {
    if (images[t].empty()) continue;  // left out: absent, not captured
    TargetImage& ti = out.images[t];
    ti.image = std::move(images[t]);
    ti.targetWidth = ti.image.width;
    ti.targetHeight = ti.image.height;
    out.absences[t] = Absent::No;
  }
  importLights(out.layout, out);
  return true;
}

}  // namespace gb
