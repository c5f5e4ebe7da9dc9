// Every render option, one struct, one name per option: the CLI flags, the viewer's toggles,
// the capture manifest and the bench report all use these names.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace gb {

enum class Path { TwoPass, SinglePass };
// Lighting methods. Auto picks, per device, the one measured fastest there (method_choice.h).
enum class Method { Deferred, Forward, Tiled, Clustered, Auto };
enum class NormalFormat { Rgba16f, Rgba8Snorm, OctRg16, Rgb10a2 };
// How an octahedral normal is rounded to its code: each coordinate to the nearest, or the best
// of the four neighbouring codes (smallest angle after decoding; Cigolle et al. 2014).
enum class OctEncoding { Nearest, Precise };
enum class DepthFormat { D32S8, D24S8 };        // the hardware depth/stencil target
enum class AccumFormat { Rgba16f, Rgba32f, Rgba8 };  // the light accumulation (hdr) target
enum class ShadowFormat { D32f, D16 };
// Where the lighting passes get the surface position: reconstructed from depth (eye depth or
// hardware depth, per eyeDepth), or a stored position target (tutorials 001-003) in fp16/fp32.
enum class PositionSource { Depth, Rgba16f, Rgba32f };
// What a stored position is relative to: the world origin (the tutorials) or the camera
// (world axes, camera at the origin: camera-relative rendering).
enum class PositionSpace { World, Camera };
// How LIGHT_STENCIL_CULLING marks pixels: one shared mask for all lights (the Apple sample:
// cheap to draw, but one light's mark lets another light shade), or an exact mask per light
// (Z-fail toggles one stencil bit per light, 7 lights per batch).
enum class StencilMask { PerLight, Shared };
// Per-light mask: lights whose volumes cover disjoint pixels share a stencil bit and are drawn
// instanced, a layer at a time. It saves draws, which cost a CPU device (lavapipe) about as much
// rasterizer time as the fragments they shade; on a GPU draws are cheap and grouping only adds
// CPU time. Auto: on for a CPU device.
enum class StencilLayers { Auto, On, Off };
// Where the per-frame light work (animation, eye space, culling, the visible list) runs: on the
// CPU (classifyLights), or in two compute passes (light_setup, light_compact; no CPU work per
// light). Auto: the GPU for methods tiled and clustered on a GPU device, where the CPU's per-light
// work was most of the frame (docs/performance.md); the CPU elsewhere (deferred needs its light
// classes and layers; a CPU device does it faster on the CPU).
enum class LightSetup { Auto, Cpu, Gpu };
// How the fairy sprites reach hdr: drawn (blended quads), or splatted in compute (binned per tile,
// blended per pixel in draw order: the same image, no fill cost). Auto: compute on a GPU device
// (where the raster pass cost more than the lighting at 65536 lights), raster on a CPU device
// and in the single-pass path (fairies are a subpass there).
enum class FairySplat { Auto, Raster, Compute };
// How the G-buffer's colour targets are cleared before the geometry: by the render pass (load op
// CLEAR), or by a compute pass through storage views (clear_gbuffer). On the H100 the render
// pass clears go through the GPU's few raster back ends and took 0.74 ms at 1080p and 2.95 ms at
// 4K (docs/perf-gpu.md); compute writes at memory speed. Auto: compute on a GPU device for the
// compute methods (tiled, clustered); the render pass for deferred (measured slower there), on a
// CPU device and in the single-pass path (its G-buffer may live in tile memory).
enum class GBufferClear { Auto, RenderPass, Compute };
// Where method clustered assigns lights to clusters: on the GPU, to the occupied clusters of the
// G-buffer (Olsson et al. 2012: cluster_bounds, cluster_bins, cluster_lists in compute, shading in
// compute), or on the CPU, to a fixed view-space grid shaded by one full-screen fragment pass
// (renderer/core/cluster_grid.h). Auto: the CPU on a CPU device, whose compute passes and image
// stores are slow (lavapipe, docs/performance.md), the GPU elsewhere.
enum class ClusterAssign { Auto, Gpu, Cpu };
// How hdr becomes final: a full-screen raster pass writing the sRGB attachment, or a compute
// pass encoding sRGB itself into a UNORM storage view of final (tonemap_compute). On the H100 a
// raster pass runs on 2 of 66 TPCs (the tone map took 0.15 ms at 1080p, 0.67 ms at 4K); compute
// writes at memory speed. Auto: compute for tiled and clustered on a GPU device (as GBufferClear);
// raster on a CPU device (lavapipe's compute pass took 6 ms at 720p: docs/performance.md), for
// deferred and forward, and in the single-pass path (the tone map is its last subpass).
enum class TonemapPass { Auto, Raster, Compute };
// How the G-buffer is filled: the raster pass shades every material where it draws (raster), or
// the raster pass writes only depth and a visibility id (draw + triangle, visibility.h) and a
// compute pass, gbuffer_resolve, rebuilds each pixel's surface from its triangle and writes the
// same G-buffer targets (Burns and Hunt, JCGT 2013). Auto: the kind measured faster on the kind
// of device (chooseGBuffer, method_choice.h: raster on a CPU device, visibility on a GPU), raster
// where visibility cannot run; the renderer resolves it before anything reads it (frameOptions).
enum class GBufferKind { Raster, Visibility, Auto };
// Camera motion over time (renderer/core/camera_motion.h): none, or the scene camera orbiting the
// scene's centre about the world up axis (10 degrees per second) while rising and falling a little.
enum class CameraMotion { Off, Orbit };
// The projection's sub-pixel offset per frame (camera_motion.h): none, or Halton(2,3), its index
// from the frame number round(time / time_step).
enum class Jitter { Off, Halton };

struct RenderOptions {
  uint32_t width = 1280, height = 720;
  double time = 0.0;  // animation time in seconds
  int lights = 256;   // generated point lights (built-in scene, files without lights)
  int camera = 0;     // index into Scene::cameras
  Path path = Path::TwoPass;
  Method method = Method::Auto;
  bool eyeDepth = true;        // USE_EYE_DEPTH: reconstruct positions from the eye-depth target
  bool stencilCulling = true;  // LIGHT_STENCIL_CULLING
  StencilMask stencilMask = StencilMask::PerLight;
  StencilLayers stencilLayers = StencilLayers::Auto;
  LightSetup lightSetup = LightSetup::Auto;
  FairySplat fairySplat = FairySplat::Auto;
  GBufferClear gbufferClear = GBufferClear::Auto;
  ClusterAssign clusterAssign = ClusterAssign::Auto;
  TonemapPass tonemapPass = TonemapPass::Auto;
  GBufferKind gbuffer = GBufferKind::Auto;
  bool reversedZ = false;
  // Octahedral 16+16-bit normals and fp32 accumulation: `gblens bench` found each dominating the
  // former defaults (rgba16f normals; fp16 accumulation) on lavapipe: same or lower frame time,
  // lower error (normal 0.0029 -> 0.00045 deg mean; lighting 7e-4 -> 8e-8 relative).
  NormalFormat normalFormat = NormalFormat::OctRg16;
  OctEncoding octEncoding = OctEncoding::Precise;  // on the frontier on both bench scenes (docs/accuracy.md)
  DepthFormat depthFormat = DepthFormat::D32S8;
  AccumFormat accumFormat = AccumFormat::Rgba32f;
  ShadowFormat shadowFormat = ShadowFormat::D32f;
  PositionSource position = PositionSource::Depth;
  PositionSpace positionSpace = PositionSpace::World;
  uint32_t shadowMapSize = 2048;
  // Shadow-map depth bias (vkCmdSetDepthBias): the Apple sample's 0.015 / 7 / 0.02 adapted to
  // a [0,1] depth range in texels.
  float shadowBiasConstant = 2.0f;
  float shadowBiasSlope = 2.5f;
  float shadowBiasClamp = 0.01f;
  bool fairies = true;
  bool sky = true;
  float exposure = 1.0f;
  // What the caller will look at: targets that are not needed are not computed.
  bool coverage = false;      // masked/full coverage targets (views 8, 9, --stats, captures)
  bool keepGBuffer = true;    // single-pass: store the G-buffer (views, captures) instead of transient
  bool primitiveId = false;   // debug target primitive_id (instance + triangle), for the reference comparison
  // Across frames: the camera's motion, the projection's jitter, and the motion target (screen
  // motion in pixels toward the previous frame, at time - timeStep; the jitter's frame number is
  // round(time / timeStep)).
  CameraMotion cameraMotion = CameraMotion::Off;
  Jitter jitter = Jitter::Off;
  bool motion = false;
  double timeStep = 1.0 / 30.0;  // seconds from the previous frame to this one (> 0)

  // Every member compares (a new option can never be forgotten by a hand-written comparison).
  bool operator==(const RenderOptions&) const = default;
};

// The single-pass path (G-buffer and lighting as subpasses) applies to deferred lighting only:
// forward has no G-buffer, and tiled and clustered read it in compute passes, outside any render
// pass. (Auto with the single-pass path always picks deferred: chooseMethod.)
inline bool singlePassFrame(const RenderOptions& o) {
  return o.path == Path::SinglePass && (o.method == Method::Deferred || o.method == Method::Auto);
}
// The G-buffer lives only in tile memory (never stored): single pass and no view reads it.
inline bool transientGBuffer(const RenderOptions& o) { return singlePassFrame(o) && !o.keepGBuffer; }

// ---- The option table: every user-settable option under one name ----------------------------
// The name is the JSON key (reports, bench rows, capture manifests) and, with '_' -> '-', the CLI
// flag: "normal_format" <-> --normal-format. Values are the same strings everywhere.
enum class OptionKind { Choice, Integer, Real, Text };
struct OptionInfo {
  std::string name;
  std::string help;
  OptionKind kind = OptionKind::Choice;
  std::vector<std::string> choices;  // Choice: the accepted values
};
const std::vector<OptionInfo>& optionTable();
const OptionInfo* findOption(const std::string& name);
std::string flagName(const std::string& optionName);  // "normal_format" -> "--normal-format"
// The option's value as text ("rgba16f", "on", "2048", "1280x720").
std::string getOption(const RenderOptions& o, const std::string& name);
// Sets an option from text; false with a one-line message (naming the flag) when the name or
// value is not accepted.
bool setOption(RenderOptions& o, const std::string& name, const std::string& value, std::string& error);

const char* name(Path p);
const char* name(Method m);
const char* name(NormalFormat f);
const char* name(OctEncoding e);
const char* name(DepthFormat f);
const char* name(AccumFormat f);
const char* name(ShadowFormat f);
const char* name(StencilMask m);
const char* name(StencilLayers l);
const char* name(LightSetup l);
const char* name(FairySplat f);
const char* name(GBufferClear c);
const char* name(ClusterAssign a);
const char* name(TonemapPass t);
const char* name(GBufferKind g);
const char* name(PositionSource p);
const char* name(PositionSpace p);
const char* name(CameraMotion m);
const char* name(Jitter j);

// Parse the names above; false when the text names nothing.
bool parse(const std::string& text, Path& out);
bool parse(const std::string& text, Method& out);
bool parse(const std::string& text, NormalFormat& out);
bool parse(const std::string& text, OctEncoding& out);
bool parse(const std::string& text, DepthFormat& out);
bool parse(const std::string& text, AccumFormat& out);
bool parse(const std::string& text, ShadowFormat& out);
bool parse(const std::string& text, StencilMask& out);
bool parse(const std::string& text, StencilLayers& out);
bool parse(const std::string& text, LightSetup& out);
bool parse(const std::string& text, FairySplat& out);
bool parse(const std::string& text, GBufferClear& out);
bool parse(const std::string& text, ClusterAssign& out);
bool parse(const std::string& text, TonemapPass& out);
bool parse(const std::string& text, GBufferKind& out);
// The point lights are drawn with the per-light stencil mask (method `ran` deferred, culling on,
// per-light); with `cpuDevice`, whether they come in screen-disjoint layers (StencilLayers; auto:
// on a CPU). `ran` is the method the frame runs (RenderOptions::method unless that is auto).
bool perLightMask(const RenderOptions& o, Method ran);
bool stencilLayersOn(const RenderOptions& o, Method ran, bool cpuDevice);
bool parse(const std::string& text, PositionSource& out);
bool parse(const std::string& text, PositionSpace& out);
bool parse(const std::string& text, CameraMotion& out);
bool parse(const std::string& text, Jitter& out);

}  // namespace gb
