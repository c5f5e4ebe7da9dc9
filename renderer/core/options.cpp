// Names of the option values, shared by CLI, UI, manifest and bench.
#include "renderer/core/options.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>

namespace gb {

template <class E, size_t N>
using Names = std::array<std::pair<E, const char*>, N>;

static const Names<Path, 2> kPath = {{{Path::TwoPass, "two-pass"}, {Path::SinglePass, "single-pass"}}};
static const Names<Method, 5> kMethod = {{{Method::Auto, "auto"},
                                          {Method::Deferred, "deferred"},
                                          {Method::Forward, "forward"},
                                          {Method::Tiled, "tiled"},
                                          {Method::Clustered, "clustered"}}};
static const Names<NormalFormat, 4> kNormal = {{{NormalFormat::Rgba16f, "rgba16f"},
                                                {NormalFormat::Rgba8Snorm, "rgba8-snorm"},
                                                {NormalFormat::OctRg16, "oct-rg16"},
                                                {NormalFormat::Rgb10a2, "rgb10a2"}}};
static const Names<OctEncoding, 2> kOct = {{{OctEncoding::Nearest, "nearest"}, {OctEncoding::Precise, "precise"}}};
static const Names<DepthFormat, 2> kDepth = {{{DepthFormat::D32S8, "d32s8"}, {DepthFormat::D24S8, "d24s8"}}};
static const Names<AccumFormat, 3> kAccum = {
    {{AccumFormat::Rgba16f, "rgba16f"}, {AccumFormat::Rgba32f, "rgba32f"}, {AccumFormat::Rgba8, "rgba8"}}};
static const Names<ShadowFormat, 2> kShadow = {{{ShadowFormat::D32f, "d32f"}, {ShadowFormat::D16, "d16"}}};
static const Names<StencilMask, 2> kMask = {{{StencilMask::PerLight, "per-light"}, {StencilMask::Shared, "shared"}}};
static const Names<StencilLayers, 3> kLayers = {
    {{StencilLayers::Auto, "auto"}, {StencilLayers::On, "on"}, {StencilLayers::Off, "off"}}};
static const Names<LightSetup, 3> kLightSetup = {
    {{LightSetup::Auto, "auto"}, {LightSetup::Cpu, "cpu"}, {LightSetup::Gpu, "gpu"}}};
static const Names<FairySplat, 3> kFairySplat = {
    {{FairySplat::Auto, "auto"}, {FairySplat::Raster, "raster"}, {FairySplat::Compute, "compute"}}};
static const Names<GBufferClear, 3> kGBufferClear = {
    {{GBufferClear::Auto, "auto"}, {GBufferClear::RenderPass, "render-pass"}, {GBufferClear::Compute, "compute"}}};
static const Names<ClusterAssign, 3> kClusterAssign = {
    {{ClusterAssign::Auto, "auto"}, {ClusterAssign::Gpu, "gpu"}, {ClusterAssign::Cpu, "cpu"}}};
static const Names<TonemapPass, 3> kTonemapPass = {
    {{TonemapPass::Auto, "auto"}, {TonemapPass::Raster, "raster"}, {TonemapPass::Compute, "compute"}}};
static const Names<GBufferKind, 3> kGBufferKind = {
    {{GBufferKind::Auto, "auto"}, {GBufferKind::Raster, "raster"}, {GBufferKind::Visibility, "visibility"}}};
static const Names<PositionSource, 3> kPosition = {
    {{PositionSource::Depth, "depth"}, {PositionSource::Rgba16f, "rgba16f"}, {PositionSource::Rgba32f, "rgba32f"}}};
static const Names<CameraMotion, 2> kCameraMotion = {{{CameraMotion::Off, "off"}, {CameraMotion::Orbit, "orbit"}}};
static const Names<Jitter, 2> kJitter = {{{Jitter::Off, "off"}, {Jitter::Halton, "halton"}}};
static const Names<PositionSpace, 2> kPositionSpace = {{{PositionSpace::World, "world"}, {PositionSpace::Camera, "camera"}}};

template <class E, size_t N>
static const char* lookup(const Names<E, N>& names, E v) {
  for (auto& [e, n] : names)
    if (e == v) return n;
  return "?";
}
template <class E, size_t N>
static bool find(const Names<E, N>& names, const std::string& text, E& out) {
  for (auto& [e, n] : names)
    if (text == n) {
      out = e;
      return true;
    }
  return false;
}

const char* name(Path v) { return lookup(kPath, v); }
const char* name(Method v) { return lookup(kMethod, v); }
const char* name(NormalFormat v) { return lookup(kNormal, v); }
const char* name(OctEncoding v) { return lookup(kOct, v); }
const char* name(DepthFormat v) { return lookup(kDepth, v); }
const char* name(AccumFormat v) { return lookup(kAccum, v); }
const char* name(ShadowFormat v) { return lookup(kShadow, v); }
const char* name(StencilMask v) { return lookup(kMask, v); }
const char* name(StencilLayers v) { return lookup(kLayers, v); }
const char* name(PositionSource v) { return lookup(kPosition, v); }
const char* name(LightSetup v) { return lookup(kLightSetup, v); }
const char* name(FairySplat v) { return lookup(kFairySplat, v); }
bool parse(const std::string& t, FairySplat& o) { return find(kFairySplat, t, o); }
const char* name(GBufferClear v) { return lookup(kGBufferClear, v); }
bool parse(const std::string& t, GBufferClear& o) { return find(kGBufferClear, t, o); }
const char* name(ClusterAssign v) { return lookup(kClusterAssign, v); }
bool parse(const std::string& t, ClusterAssign& o) { return find(kClusterAssign, t, o); }
const char* name(TonemapPass v) { return lookup(kTonemapPass, v); }
bool parse(const std::string& t, TonemapPass& o) { return find(kTonemapPass, t, o); }
const char* name(GBufferKind v) { return lookup(kGBufferKind, v); }
bool parse(const std::string& t, GBufferKind& o) { return find(kGBufferKind, t, o); }
bool parse(const std::string& t, LightSetup& o) { return find(kLightSetup, t, o); }
const char* name(PositionSpace v) { return lookup(kPositionSpace, v); }
bool parse(const std::string& t, Path& o) { return find(kPath, t, o); }
bool parse(const std::string& t, Method& o) { return find(kMethod, t, o); }
bool parse(const std::string& t, NormalFormat& o) { return find(kNormal, t, o); }
bool parse(const std::string& t, OctEncoding& o) { return find(kOct, t, o); }
bool parse(const std::string& t, DepthFormat& o) { return find(kDepth, t, o); }
bool parse(const std::string& t, AccumFormat& o) { return find(kAccum, t, o); }
bool parse(const std::string& t, ShadowFormat& o) { return find(kShadow, t, o); }
bool parse(const std::string& t, StencilMask& o) { return find(kMask, t, o); }
bool parse(const std::string& t, StencilLayers& o) { return find(kLayers, t, o); }
bool perLightMask(const RenderOptions& o, Method ran) {
  return ran == Method::Deferred && o.stencilCulling && o.stencilMask == StencilMask::PerLight;
}
bool stencilLayersOn(const RenderOptions& o, Method ran, bool cpuDevice) {
  return perLightMask(o, ran) &&
         (o.stencilLayers == StencilLayers::On || (o.stencilLayers == StencilLayers::Auto && cpuDevice));
}
bool parse(const std::string& t, PositionSource& o) { return find(kPosition, t, o); }
bool parse(const std::string& t, PositionSpace& o) { return find(kPositionSpace, t, o); }
const char* name(CameraMotion v) { return lookup(kCameraMotion, v); }
bool parse(const std::string& t, CameraMotion& o) { return find(kCameraMotion, t, o); }
const char* name(Jitter v) { return lookup(kJitter, v); }
bool parse(const std::string& t, Jitter& o) { return find(kJitter, t, o); }

// ---- the option table ------------------------------------------------------------------------

namespace {

struct Entry {
  OptionInfo info;
  std::function<std::string(const RenderOptions&)> get;
  std::function<bool(RenderOptions&, const std::string&)> set;  // false: value not accepted
};

template <class E, size_t N>
std::vector<std::string> choicesOf(const Names<E, N>& names) {
  std::vector<std::string> out;
  for (auto& [e, n] : names) out.push_back(n);
  return out;
}

// An option whose values are the names of an enum.
template <class E, size_t N>
Entry choice(const char* name, const char* help, const Names<E, N>& names, E RenderOptions::*member) {
  return {{name, help, OptionKind::Choice, choicesOf(names)},
          [&names, member](const RenderOptions& o) { return std::string(lookup(names, o.*member)); },
          [&names, member](RenderOptions& o, const std::string& v) { return find(names, v, o.*member); }};
}

Entry onOff(const char* name, const char* help, bool RenderOptions::*member) {
  return {{name, help, OptionKind::Choice, {"on", "off"}},
          [member](const RenderOptions& o) { return std::string(o.*member ? "on" : "off"); },
          [member](RenderOptions& o, const std::string& v) {
            if (v != "on" && v != "off") return false;
            o.*member = v == "on";
            return true;
          }};
}

bool parseReal(const std::string& v, double& out) {
  char* end = nullptr;
  out = std::strtod(v.c_str(), &end);
  return !v.empty() && end && *end == 0 && std::isfinite(out);
}
bool parseInt(const std::string& v, long long lo, long long hi, long long& out) {
  char* end = nullptr;
  out = std::strtoll(v.c_str(), &end, 10);
  return !v.empty() && end && *end == 0 && out >= lo && out <= hi;
}
// The shortest text that reads back as the same value of the member's type (0.01f -> "0.01").
template <class T>
std::string realText(T v) {
  char buf[64];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, double(v));
    if (T(std::strtod(buf, nullptr)) == v) break;
  }
  return buf;
}

template <class T>
Entry integer(const char* name, const char* help, T RenderOptions::*member, long long lo, long long hi) {
  return {{name, help, OptionKind::Integer, {}},
          [member](const RenderOptions& o) { return std::to_string(o.*member); },
          [member, lo, hi](RenderOptions& o, const std::string& v) {
            long long x;
            if (!parseInt(v, lo, hi, x)) return false;
            o.*member = T(x);
            return true;
          }};
}

template <class T>
Entry real(const char* name, const char* help, T RenderOptions::*member, double lo, double hi) {
  return {{name, help, OptionKind::Real, {}},
          [member](const RenderOptions& o) { return realText<T>(o.*member); },
          [member, lo, hi](RenderOptions& o, const std::string& v) {
            double x;
            if (!parseReal(v, x) || x < lo || x > hi) return false;
            o.*member = T(x);
            return true;
          }};
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = {
      {{"size", "output size WxH (1..16384 each)", OptionKind::Text, {}},
       [](const RenderOptions& o) { return std::to_string(o.width) + "x" + std::to_string(o.height); },
       [](RenderOptions& o, const std::string& v) {
         unsigned w = 0, h = 0;
         char x = 0, extra = 0;
         if (std::sscanf(v.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w == 0 ||
             h == 0 || w > 16384 || h > 16384)
           return false;
         o.width = w;
         o.height = h;
         return true;
       }},
      real("time", "animation time in seconds (fixed)", &RenderOptions::time, -1e9, 1e9),
      integer("lights", "generated point lights (0..65536)", &RenderOptions::lights, 0, 65536),
      integer("camera", "camera index", &RenderOptions::camera, 0, 1 << 20),
      choice("path", "two render passes, or one with subpasses and input attachments", kPath, &RenderOptions::path),
      choice("method",
             "lighting method (auto: the one measured fastest on this device for the light count; --stats says "
             "which ran and why)",
             kMethod, &RenderOptions::method),
      onOff("eye_depth", "USE_EYE_DEPTH: positions from the R32F eye-depth target (off: from hardware depth)",
            &RenderOptions::eyeDepth),
      onOff("stencil_culling", "LIGHT_STENCIL_CULLING", &RenderOptions::stencilCulling),
      choice("stencil_mask", "per-light (exact, 7 bits per stencil batch) | shared (the sample's one mask)", kMask,
             &RenderOptions::stencilMask),
      choice("stencil_layers",
             "per-light mask: lights covering disjoint pixels share a bit, one draw per layer (auto: on a CPU device)",
             kLayers, &RenderOptions::stencilLayers),
      choice("light_setup",
             "where light animation, culling and the visible list run: cpu | gpu (compute; methods tiled and "
             "clustered) | auto (gpu for those on a GPU device)",
             kLightSetup, &RenderOptions::lightSetup),
      onOff("reversed_z", "hardware depth 1 at the near plane, 0 at the far plane", &RenderOptions::reversedZ),
      choice("normal_format", "normal_shadow storage", kNormal, &RenderOptions::normalFormat),
      choice("oct_encoding",
             "octahedral normals (oct-rg16): each coordinate rounded to the nearest code, or the best of the four "
             "neighbouring codes (precise)",
             kOct, &RenderOptions::octEncoding),
      choice("depth_format", "hardware depth/stencil format", kDepth, &RenderOptions::depthFormat),
      choice("position", "position source of the lighting passes: reconstructed from depth, or a stored target",
             kPosition, &RenderOptions::position),
      choice("position_space", "origin of a stored position: the world's or the camera's", kPositionSpace,
             &RenderOptions::positionSpace),
      choice("accum_format", "light accumulation (hdr) format", kAccum, &RenderOptions::accumFormat),
      choice("shadow_format", "shadow map depth format", kShadow, &RenderOptions::shadowFormat),
      integer("shadow_map_size", "shadow map size in texels (square)", &RenderOptions::shadowMapSize, 16, 16384),
      real("shadow_bias_constant", "shadow map constant depth bias (depth-format units)",
           &RenderOptions::shadowBiasConstant, -1e6, 1e6),
      real("shadow_bias_slope", "shadow map slope-scaled depth bias", &RenderOptions::shadowBiasSlope, -1e6, 1e6),
      real("shadow_bias_clamp", "largest shadow map depth bias (0: no clamp)", &RenderOptions::shadowBiasClamp, -1.0,
           1.0),
      onOff("fairies", "fairy-light sprites", &RenderOptions::fairies),
      choice("fairy_splat",
             "fairy sprites drawn as quads (raster) or splatted per tile in compute (the same image) | auto (compute on "
             "a GPU device)",
             kFairySplat, &RenderOptions::fairySplat),
      choice("gbuffer_clear",
             "how the G-buffer's colour targets are cleared: render-pass (load op) | compute (clear_gbuffer, storage "
             "views) | auto (compute for tiled and clustered on a GPU device)",
             kGBufferClear, &RenderOptions::gbufferClear),
      choice("cluster_assign",
             "method clustered: lights assigned to the occupied clusters in compute (gpu) or to a fixed view-space "
             "grid on the CPU, shaded in a fragment pass (cpu) | auto (cpu on a CPU device)",
             kClusterAssign, &RenderOptions::clusterAssign),
      choice("tonemap_pass",
             "how hdr becomes final: raster (full-screen pass, sRGB attachment) | compute (tonemap_compute: sRGB "
             "encoded in the shader, a storage view of final) | auto (compute for tiled and clustered on a GPU device)",
             kTonemapPass, &RenderOptions::tonemapPass),
      choice("gbuffer",
             "how the G-buffer is filled: raster (materials shaded where they are drawn) | visibility (the raster pass "
             "writes depth and a visibility id, gbuffer_resolve rebuilds the same targets in compute) | auto (the one "
             "measured faster on this kind of device: raster on a CPU device, visibility on a GPU)",
             kGBufferKind, &RenderOptions::gbuffer),
      onOff("sky", "skybox", &RenderOptions::sky),
      real("exposure", "tone-mapping exposure", &RenderOptions::exposure, 0.0, 1e6),
      onOff("primitive_id", "write the primitive_id debug target (instance + triangle) in the G-buffer pass",
            &RenderOptions::primitiveId),
      choice("camera_motion",
             "the scene camera over time: off | orbit (about the scene's centre and the world up axis, 10 degrees "
             "per second, rising and falling by 2% of the scene's radius every 4 s)",
             kCameraMotion, &RenderOptions::cameraMotion),
      choice("jitter",
             "sub-pixel offset of the projection: off | halton (Halton(2,3), index 1 + (round(time / time_step) mod "
             "16)); the capture's camera stays unjittered",
             kJitter, &RenderOptions::jitter),
      onOff("motion",
            "write the motion target in the G-buffer pass: screen motion in pixels toward the previous frame "
            "(time - time_step), +y down, jitter excluded",
            &RenderOptions::motion),
      real("time_step",
           "seconds from the previous frame to this one (1e-9..1e9): the motion target's previous camera, the "
           "jitter's frame number",
           &RenderOptions::timeStep, 1e-9, 1e9),
  };
  return table;
}

const Entry* findEntry(const std::string& name) {
  for (const Entry& e : entries())
    if (e.info.name == name) return &e;
  return nullptr;
}

}  // namespace

const std::vector<OptionInfo>& optionTable() {
  static const std::vector<OptionInfo> infos = [] {
    std::vector<OptionInfo> v;
    for (const Entry& e : entries()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

const OptionInfo* findOption(const std::string& name) {
  for (const OptionInfo& i : optionTable())
    if (i.name == name) return &i;
  return nullptr;
}

std::string flagName(const std::string& optionName) {
  std::string f = "--" + optionName;
  for (char& c : f)
    if (c == '_') c = '-';
  return f;
}

std::string getOption(const RenderOptions& o, const std::string& name) {
  const Entry* e = findEntry(name);
  return e ? e->get(o) : std::string();
}

bool setOption(RenderOptions& o, const std::string& name, const std::string& value, std::string& error) {
  const Entry* e = findEntry(name);
  if (!e) {
    error = "unknown option '" + name + "'";
    return false;
  }
  if (e->set(o, value)) return true;
  error = flagName(name) + " " + value + ": ";
  if (e->info.kind == OptionKind::Choice) {
    error += "expected one of";
    for (const std::string& c : e->info.choices) error += " " + c;
  } else if (name == "size") {
    error += "expected WxH with 1..16384 each, e.g. 1280x720";
  } else {
    error += "not a valid value (" + e->info.help + ")";
  }
  return false;
}

}  // namespace gb
