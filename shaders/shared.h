// Structs, binding indices and enums shared by C++ and GLSL: one definition for both sides.
// Layout rule: only vec4/uvec4/ivec4/mat4 members, so std140/std430 and C++ agree byte for byte.
#ifndef GBLENS_SHARED_H
#define GBLENS_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace gb::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
using uint = uint32_t;
#define GB_CONST(type, name, value) constexpr type name = value
#define GB_STRUCT(name) struct alignas(16) name
#else
#define GB_CONST(type, name, value) const type name = value
#define GB_STRUCT(name) struct name
#endif

// ---- descriptor set 0: the scene and the frame (one set, written when the scene loads) ----
GB_CONST(uint, kSetScene, 0);
GB_CONST(uint, kBindingFrame, 0);      // uniform FrameData
GB_CONST(uint, kBindingDraws, 1);      // buffer DrawData[]
GB_CONST(uint, kBindingMaterials, 2);  // buffer Material[]
GB_CONST(uint, kBindingLights, 3);     // buffer PointLight[] (eye space, this frame)
GB_CONST(uint, kBindingVisible, 4);    // buffer uint[]: indices of the lights drawn this frame
GB_CONST(uint, kBindingLightCounts, 5); // buffer LightCounts: the visible count (written by the CPU or light_setup)
GB_CONST(uint, kBindingVisiblePositions, 6);  // buffer vec4[]: the visible lights' eyePositionRadius, in visible-list order

// ---- descriptor set 1: the pass's inputs (push descriptors) ----
GB_CONST(uint, kSetPass, 1);
GB_CONST(uint, kBindingAlbedo, 0);      // albedo_specular (texture or input attachment)
GB_CONST(uint, kBindingNormal, 1);      // normal_shadow
GB_CONST(uint, kBindingDepth, 2);       // the position source: depth (eye depth), depth_stencil's depth or position
GB_CONST(uint, kBindingShadowMap, 3);   // shadow_map with compare sampler
GB_CONST(uint, kBindingHdr, 4);         // hdr (tone-map input)
GB_CONST(uint, kBindingCoverage, 5);    // coverage_masked / coverage_full: r32ui storage image
GB_CONST(uint, kBindingTileLights, 6);  // a storage buffer for compute passes (sRGB decode probe)
// Material textures, pushed per draw: a constant binding samples far faster on a CPU device
// than an index into a descriptor array (lavapipe: 2.5x for the G-buffer pass).
GB_CONST(uint, kBindingBaseColorTexture, 7);
GB_CONST(uint, kBindingNormalTexture, 8);
GB_CONST(uint, kBindingHdrStorage, 9);  // hdr as a storage image (tiled lighting writes it)
// Clustered shading's buffers (renderer/gpu/cluster_buffers.h), pushed to the compute passes.
GB_CONST(uint, kBindingClusterHeader, 10);  // ClusterHeader
GB_CONST(uint, kBindingClusters, 11);       // Cluster[]: the occupied clusters
GB_CONST(uint, kBindingPixelClusters, 12);  // uint per pixel: its cluster (kNoCluster: sky or no room)
GB_CONST(uint, kBindingLightLists, 13);     // uint[]: light indices, each cluster's in visible-list order
GB_CONST(uint, kBindingBinBits, 14);        // uint[]: per light bin, a bit per visible-list position
GB_CONST(uint, kBindingBinBoxes, 15);       // uvec4[2] per light bin: the box of its surface points
// Light setup on the GPU (renderer/gpu/gpu_lights.h): the scene's lights and per-light scratch.
GB_CONST(uint, kBindingLightDescs, 16);     // LightDesc[]: world space, doubles
GB_CONST(uint, kBindingLightScratch, 17);   // uint per light (its place among its group's visible), then uvec4 per group
GB_CONST(uint, kBindingGridCells, 20);      // uvec2 per grid cell: offset, count in kBindingGridLights (cluster grid)
GB_CONST(uint, kBindingGridLights, 21);     // PointLight[]: each cell's lights, in visible-list order
GB_CONST(uint, kPassBindingCount, 22);
GB_CONST(uint, kLightSetupGroup, 256);      // lights per light_setup workgroup
// Fairy sprites splatted in compute (fairy_bins, fairy_splat): the light bins' layout, own masks.
GB_CONST(uint, kBindingFairyBits, 18);      // uint[]: per light bin, a bit per visible-list position
GB_CONST(uint, kBindingClearTarget, 19);    // clear_gbuffer: a G-buffer target's unsigned storage view
GB_CONST(uint, kFairyListMax, 1024);        // sprites a 16x16 tile lists in shared memory (more: read from the bin)

// ---- gbuffer_resolve (--gbuffer visibility): its own set 1 (pushed) and set 2 (the scene, written once) ----
GB_CONST(uint, kResolveBindingShadowMap, 0);    // shadow_map with compare sampler
GB_CONST(uint, kResolveBindingVisibility, 1);   // visibility (usampler2D)
GB_CONST(uint, kResolveBindingAlbedo, 2);       // the G-buffer targets through their unsigned storage views
GB_CONST(uint, kResolveBindingNormal, 3);
GB_CONST(uint, kResolveBindingDepth, 4);
GB_CONST(uint, kResolveBindingPrimitiveId, 5);
GB_CONST(uint, kResolveBindingPosition, 6);
GB_CONST(uint, kResolveBindingMotion, 7);
GB_CONST(uint, kResolveBindingBaseTexture, 8);   // the dispatch's texture group: base colour ...
GB_CONST(uint, kResolveBindingNormalTexture, 9); // ... and normal texture (stand-ins where the group has none)
GB_CONST(uint, kSetResolveScene, 2);
GB_CONST(uint, kResolveBindingVertices, 0);     // float[]: the scene's Vertex array (renderer/core/vertex.h), 14 floats each
GB_CONST(uint, kResolveBindingIndices, 1);      // uint[]: the scene's index buffer
GB_CONST(uint, kResolveBindingGeometry, 2);     // DrawGeometry[] per draw (instance)
GB_CONST(uint, kVertexFloats, 14);
GB_CONST(uint, kResolveGroup, 8);               // gbuffer_resolve's workgroup side (8x8 pixels)

// Input attachment indices of the single-pass path (subpass inputs, in this order).
GB_CONST(uint, kInputAlbedo, 0);
GB_CONST(uint, kInputNormal, 1);
GB_CONST(uint, kInputDepth, 2);
GB_CONST(uint, kInputHdr, 0);           // tone-map subpass

// ---- specialization constants ----
GB_CONST(uint, kSpecEyeDepth, 0);       // 1: position from the eye-depth target; 0: from hardware depth
GB_CONST(uint, kSpecAlphaTest, 1);      // 1: the material may cut out fragments
GB_CONST(uint, kSpecCoverage, 2);       // 1: count fragment invocations into kBindingCoverage
GB_CONST(uint, kSpecReversedZ, 3);      // 1: depth 1 at the near plane
GB_CONST(uint, kSpecNormalEncoding, 4); // kNormal* below
GB_CONST(uint, kSpecNormalMap, 5);      // 1: the material has a normal texture
GB_CONST(uint, kSpecPosition, 6);       // kPosition* below: where lighting gets the surface position
GB_CONST(uint, kSpecOutputSrgb, 7);     // 1: the view pipeline writes an sRGB attachment (hardware encodes)
GB_CONST(uint, kSpecOctPrecise, 8);     // 1: octahedral normals keep the best of the 4 neighbouring codes
GB_CONST(uint, kSpecBaseColorTexture, 9);  // 0: the material has no base-colour texture (not sampled)
GB_CONST(uint, kSpecViewMapping, 10);   // the view pipeline's kViewMap* (a pipeline per mapping: see view_map.frag)
GB_CONST(uint, kSpecVisibilityBits, 11);  // the visibility id's triangle bits (renderer/core/visibility.h)
GB_CONST(uint, kSpecResolvePosition32, 12);  // gbuffer_resolve: 1 when the position target is rgba32f (else rgba16f)

// The lighting passes' position source.
GB_CONST(uint, kPositionDepth, 0);      // reconstructed from eye depth or hardware depth (kSpecEyeDepth)
GB_CONST(uint, kPositionWorld, 1);      // the position target, world space
GB_CONST(uint, kPositionCamera, 2);     // the position target, world axes with the camera at the origin

// How normal_shadow stores the eye-space normal.
GB_CONST(uint, kNormalRgba16f, 0);
GB_CONST(uint, kNormalRgba8Snorm, 1);
GB_CONST(uint, kNormalOctRg16, 2);
GB_CONST(uint, kNormalRgb10a2, 3);

GB_CONST(uint, kAlphaOpaque, 0);
GB_CONST(uint, kAlphaMask, 1);
GB_CONST(uint, kAlphaBlend, 2);

GB_CONST(uint, kStencilGeometry, 128);  // G-buffer writes this where geometry is (as the sample)
GB_CONST(uint, kTileSize, 16);

// ---- clustered shading (Olsson, Billeter, Assarsson, HPG 2012) ----
// A cluster is a screen tile x an exponential depth slice holding surface points; only occupied
// ones exist. Lights are first binned light by light into coarse screen bins (a bit per light
// per bin: order-free, so each cluster's list comes out in visible-list order), then each
// cluster keeps the bin's lights whose sphere reaches the box of its own surface points.
GB_CONST(uint, kClusterTile, 16);          // pixels; one cluster_bounds workgroup per tile
GB_CONST(uint, kClusterMaxSlices, 256);    // depth slices at most (a tile's slice mask: 8 words)
GB_CONST(uint, kBinTile, 64);              // pixels per light bin side (4x4 cluster tiles)
GB_CONST(uint, kClusterListGroup, 64);     // invocations per cluster in cluster_lists
GB_CONST(uint, kNoCluster, 0xFFFFFFFFu);   // a pixel with no cluster: sky, or the clusters ran out
GB_CONST(uint, kListOverflow, 0xFFFFFFFFu);  // Cluster.info.z: its list did not fit (shaded from the bin)
// The cluster grid (--cluster-assign cpu; renderer/core/cluster_grid.h): every cell of a fixed
// view-space grid (screen tiles x exponential depth slices from the near to the far plane) gets
// its lights on the CPU, and one full-screen fragment pass shades each pixel from its cell.
GB_CONST(uint, kGridTile, 32);    // pixels per grid tile side
GB_CONST(uint, kGridSlices, 64);  // depth slices between the near and the far plane

GB_STRUCT(FrameData) {
  mat4 clipFromEye;
  mat4 eyeFromClip;
  mat4 worldFromEye;      // rotation part turns eye rays into sky directions
  mat4 lightClipFromEye;  // shadow-map clip space from eye space (point lights, probes)
  vec4 viewport;          // width, height, 1/width, 1/height
  vec4 eyeRay;            // 1/P00, 1/P11, P20, P21: eye-depth reconstruction
  vec4 sunEyeDirection;   // xyz: unit vector toward the sun, eye space; w: 1 when there is a sun
  vec4 sunColor;          // rgb radiance
  vec4 ambientColor;      // rgb
  vec4 skyZenith;         // rgb
  vec4 skyHorizon;        // rgb; w 1 when the sky is drawn (sky.glsl skyEnabled)
  vec4 skyGround;         // rgb
  vec4 params;            // x exposure, y fairy size (fraction of radius), z shadow-map texel size, w time
  uvec4 counts;           // x visible lights, y lights drawn in the "inside" class, z, w unused
  uvec4 clusterGrid;      // x cluster tiles across, y down, z light bins across, w words of a bin's light mask
  vec4 clusterSlices;     // slice = floor(log2(eye depth) * x + y), clamped to [0, kClusterMaxSlices)
  uvec4 gridShape;        // the cluster grid: x tiles across, y down, z depth slices, w tile size (pixels)
  vec4 gridSlices;        // its slice = floor(log2(eye depth) * x + y), clamped to [0, gridShape.z)
  // Light setup on the GPU, in double as the CPU path does it (doubles as bit pairs, packDouble2x32):
  uvec4 eyeFromWorld64[6];  // rows 0-2 of eyeFromWorld, two doubles per uvec4
  uvec4 projection64[2];    // clipFromEye [0][0], [1][1] | [2][0], [2][1]
  uvec4 depthRange64;       // znear, zfar
  uvec4 time64;             // xy time (s); z scene lights; w 0
  // The motion target (--motion on; zero otherwise): the previous frame's unjittered clip space
  // from this frame's eye space (formed in double: camera-relative), and this frame's unjittered one.
  mat4 prevClipFromEye;
  mat4 unjitteredClipFromEye;
  vec4 jitter;              // xy the projection's offset in pixels (+x right, +y down), zw in NDC
};

GB_STRUCT(DrawData) {
  mat4 eyeFromObject;         // computed in double on the CPU: camera-relative, precise far from the origin
  mat4 normalEyeFromObject;   // inverse transpose of eyeFromObject's 3x3
  mat4 lightClipFromObject;   // the sun's shadow-map clip space
  uvec4 info;                 // x material index, y 1 if the winding is flipped, z first primitive_id
};

// Where a draw's triangles are (gbuffer_resolve): its mesh's place in the index and vertex buffers.
GB_STRUCT(DrawGeometry) {
  uvec4 info;      // x first index, y vertex offset, z triangles, w primitive_id of its triangle 0 (DrawData.info.z)
  ivec4 textures;  // x base-colour texture (-1 none), y normal texture (-1 none), z texture group, w 0
};

GB_STRUCT(Material) {
  vec4 baseColor;     // linear rgba factor
  vec4 params;        // x specular intensity, y alpha cut-off, z normal scale, w unused
  ivec4 textures;     // x base-colour texture (-1 none), y normal texture, z base UV set, w normal UV set
  uvec4 flags;        // x alpha mode, y double sided, z unlit (KHR_materials_unlit)
  vec4 baseUv0;       // KHR_texture_transform as a 2x3 matrix: row 0
  vec4 baseUv1;       // row 1
  vec4 normalUv0;
  vec4 normalUv1;
};

GB_STRUCT(PointLight) {
  vec4 eyePositionRadius;  // xyz eye space, w radius (attenuation is exactly zero at the radius)
  vec4 color;              // rgb colour * intensity
};

// A light as the scene describes it (PointLightDesc), for light setup on the GPU: doubles as
// bit pairs (unpackDouble2x32), so the layout rule above holds.
GB_STRUCT(LightDesc) {
  uvec4 centerXY;      // center.x, center.y
  uvec4 centerZOrbit;  // center.z, orbitRadius
  uvec4 speedPhase;    // orbitSpeed (rad/s), phase
  uvec4 bobRadius;     // bob, radius
  vec4 color;          // rgb colour * intensity (rounded to float as the CPU path does); w 1: adds nothing (culled)
};

// This frame's light counts on the GPU (written by the CPU, or by light_setup).
GB_STRUCT(LightCounts) {
  uvec4 counts;     // x visible lights, y culled outside the frustum, z culled empty, w culled sub-pixel
  uvec4 fairyDraw;  // VkDrawIndirectCommand of the fairy sprites: 6 vertices, x visible instances
};

// Clustered shading: counters and indirect arguments, then the occupied clusters.
GB_STRUCT(ClusterHeader) {
  uvec4 counts;    // x occupied clusters, y light-list entries taken, z clusters whose list overflowed, w tiles out of room
  uvec4 capacity;  // x clusters, y light-list entries (the buffers' sizes, set by the CPU)
  uvec4 dispatch;  // VkDispatchIndirectCommand of cluster_lists: x workgroups (one per cluster, at most 65535)
};
GB_STRUCT(Cluster) {
  vec4 lo;     // xyz: smallest eye-space coordinates of the cluster's surface points
  vec4 hi;     // xyz: largest
  uvec4 info;  // x cluster tile, y depth slice, z light-list offset (kListOverflow: none), w list length
};

// ---- the viewer's view mapping (renderer/view_map.cpp draws, views/view_params.cpp decides) ----
// How a view turns a target's texel into a display colour (views/analysis/view_table.h: one
// visualisation per quantity kind; the colour maps are shaders/view_colors.h).
GB_CONST(uint, kViewMapColor, 0);     // selected channels as colour (others 0), range -> [0, 1] (colour, position, vector)
GB_CONST(uint, kViewMapGrey, 1);      // the lowest selected channel as grey (or false colour), range -> [0, 1]
GB_CONST(uint, kViewMapNormal, 2);    // the unit normal's selected components, range -> [0, 1]
GB_CONST(uint, kViewMapDepth, 3);     // one channel, near bright (1 - 0.9 t) or false colour; invalid texels black
GB_CONST(uint, kViewMapHeat, 4);      // one channel as a count, heat map over [0, white point]
GB_CONST(uint, kViewMapDiff, 5);      // |A - B|: max over selected channels, heat map over [0, white point]
GB_CONST(uint, kViewMapId, 6);        // integer ids, a hashed colour each (view_colors.h idColor)
GB_CONST(uint, kViewMapStencil, 7);   // stencil values (masked by extra.x), a colour each (stencilColor)
GB_CONST(uint, kViewMapMotion, 8);    // a 2D vector: direction as hue, length / white point as saturation
// ViewParams.mode.z flags.
GB_CONST(uint, kViewFlagSrgb, 1);      // the data is linear colour: display it sRGB-encoded
GB_CONST(uint, kViewFlagSpecials, 2);  // NaN and +-Inf in a selected channel get their own colours
GB_CONST(uint, kViewFlagNegative, 4);  // negative values (where none belong) get their own colour
GB_CONST(uint, kViewFlagGrid, 8);      // texel grid (high zoom)
GB_CONST(uint, kViewFlagMark, 16);     // mark texels whose shadow lookup uses shadow-map texel mark.xy
GB_CONST(uint, kViewFlagFalseColor, 32);  // grey and depth mappings use viridis instead of grey
GB_CONST(uint, kViewFlagLog, 64);         // grey and depth mappings: log of the value over log of the range
GB_CONST(uint, kViewFlagNativeNormal, 128);  // gblens's live normal target: decode NORMAL_ENCODING
GB_CONST(uint, kViewFlagDecoded, 256);    // a decoded view image: texels holding kEmptyTexel are empty (black)
// Which texels count for an automatic range (and which a depth view paints black).
GB_CONST(uint, kRangeAll, 0);
GB_CONST(uint, kRangePositive, 1);  // eye depth: > 0 where geometry was drawn
GB_CONST(uint, kRangeBelowOne, 2);  // shadow map: cleared to 1
GB_CONST(uint, kRangeNotFar, 3);    // hardware depth: not the far-plane value
GB_CONST(uint, kRangeNotValue, 4);  // not the layout's background value (extra.y: its float bits)
// The bits of a decoded view image's texel where the view has no value (no surface, not held): a
// quiet NaN whose payload no decoding produces (decoded NaNs are stored as 0x7FC00000).
GB_CONST(uint, kEmptyTexel, 0x7FC0DEADu);
// Highlight colours (the legend in views/ names the same ones).
#define GB_COLOR_NAN vec4(1.0, 0.0, 1.0, 1.0)
#define GB_COLOR_INF vec4(0.0, 1.0, 1.0, 1.0)
#define GB_COLOR_NEGATIVE vec4(1.0, 0.35, 0.0, 1.0)
#define GB_COLOR_MARK vec4(1.0, 0.0, 1.0, 1.0)

// Push constants of the view pipeline: one view drawn into a rectangle of the window.
GB_STRUCT(ViewParams) {
  vec4 transform;  // xy framebuffer position of texel (0,0)'s top-left corner, z framebuffer pixels per texel
  vec4 range;      // x black point, y white point, z grid opacity, w exposure multiplier (2^EV, colour)
  uvec4 mode;      // x kViewMap*, y channel mask (bit c = channel c), z kViewFlag*, w kRange* (valid texels)
  ivec4 mark;      // xy shadow-map texel (kViewFlagMark), zw shadow-map size
  uvec4 extra;     // x stencil bits shown (kViewMapStencil; 0 all), y background bits (kRangeNotValue), z, w unused
};

// Push constants of the range reduction (view_range.comp).
GB_STRUCT(RangeParams) {
  uvec4 select;  // x channel, y kRange* predicate, z result slot, w background bits (kRangeNotValue)
};
// One result slot: ordered-uint min/max of valid finite values (see orderedFromFloat), counts.
GB_STRUCT(RangeResult) {
  uvec4 minMax;  // x ordered min, y ordered max, z valid finite count, w NaN count
  uvec4 counts;  // x Inf count, y negative count
};

// ---- the viewer's views decoded on the GPU from a frame's stored texels (view_decode.comp) ----
// What a view's texel holds (views/analysis/visualize.h viewValue, kind for kind).
GB_CONST(uint, kDecodeColor, 0);     // linear colour, RGBA (alpha 1 without a fourth channel)
GB_CONST(uint, kDecodeScalar, 1);    // channel 0 * scale + bias
GB_CONST(uint, kDecodeVector, 2);    // each channel * scale + bias
GB_CONST(uint, kDecodeNormal, 3);    // the stored vector decoded (encoding.x), unit, its length in w; surfaces only
GB_CONST(uint, kDecodeDepth, 4);     // the stored depth (camera distances scaled); where something was drawn
GB_CONST(uint, kDecodePosition, 5);  // the stored position, the eye distance in w; surfaces only
GB_CONST(uint, kDecodeMotion, 6);    // pixels toward the previous frame, +y down
GB_CONST(uint, kDecodeInteger, 7);   // the stored integer (float channels rounded, 0 when not above 0)
// ViewDecodeParams.mode.z flags.
GB_CONST(uint, kDecodeFlagSrgb, 1);        // colour: sRGB-encoded values
GB_CONST(uint, kDecodeFlagSun, 2);         // depth: the shadow map's (stored as is; only the background empty)
GB_CONST(uint, kDecodeFlagMotionYUp, 4);   // motion: +y up the image
GB_CONST(uint, kDecodeFlagToNext, 8);      // motion: toward the next frame (negated)
GB_CONST(uint, kDecodeFlagHardware, 16);   // depth (and surface depth: kDecodeFlagSurfaceHardware): hardware depth
GB_CONST(uint, kDecodeFlagSurfaceHardware, 32);
// ViewDecodeParams.mode.w: which pixels hold a surface (decode.h hasSurface).
GB_CONST(uint, kDecodeSurfaceAll, 0);    // the layout has no camera depth
GB_CONST(uint, kDecodeSurfaceNone, 1);   // it has one and the frame holds none
GB_CONST(uint, kDecodeSurfaceDepth, 2);  // where the surface depth (binding 1) holds a drawn value
// renderer/core/image.h's PixelType and Encoding, as numbered there (checked in view_decode.cpp).
GB_CONST(uint, kPixelU8, 0);
GB_CONST(uint, kPixelI8, 1);
GB_CONST(uint, kPixelU16, 2);
GB_CONST(uint, kPixelI16, 3);
GB_CONST(uint, kPixelU32, 4);
GB_CONST(uint, kPixelF16, 5);
GB_CONST(uint, kPixelF32, 6);
GB_CONST(uint, kEncodingUnorm, 0);
GB_CONST(uint, kEncodingSnorm, 1);
GB_CONST(uint, kEncodingSrgb, 2);
GB_CONST(uint, kEncodingFloat, 3);
GB_CONST(uint, kEncodingUint, 4);
GB_CONST(uint, kEncodingUnorm10, 5);
GB_CONST(uint, kEncodingUnorm24, 6);
// A target's texels in a storage buffer, as the CPU holds them (CpuImage: channels of one type, packed).
GB_STRUCT(DecodeTexels) {
  uvec4 size;    // x width, y height, zw target coordinates of texel (0, 0)
  uvec4 format;  // x kPixel*, y kEncoding*, z channels a texel has, w bytes a texel takes
};
// A stored value that marks "nothing drawn" (a background, the far plane), matched as the CPU's
// double comparison would: float types by value (`value`, when the double is a float), integer codes
// by code (up to two: snorm's -1), nothing when no stored value equals it.
GB_STRUCT(DecodeMatch) {
  uvec4 codes;  // x 1: compare floats, 2: compare codes, 0: never; y, z the codes; w unused
  vec4 value;   // x the float
};
GB_STRUCT(ViewDecodeParams) {
  DecodeTexels texels;   // the view's target (binding 0)
  DecodeTexels surface;  // the surface depth's target (binding 1; mode.w kDecodeSurfaceDepth)
  uvec4 channels;        // the quantity's channels of its target, in component order
  uvec4 mode;            // x kDecode*, y the quantity's channel count, z kDecodeFlag*, w kDecodeSurface*
  uvec4 encoding;        // x normal encoding (layout.h order), y the surface depth's channel, z first range slot, w components with range statistics (0: none)
  vec4 values;           // x scale, y bias; z, w the surface depth's scale and bias
  vec4 camera;           // x width, y height of the frame's camera (motion units)
  // Depths: the stored value where nothing was drawn (the layout's background; a hardware depth
  // without one: the far plane), of the view's quantity and of the surface depth.
  DecodeMatch background, surfaceBackground;
  mat4 eyeFromStored;    // positions: the stored point into eye space (its distance, w)
};

#ifdef __cplusplus
static_assert(sizeof(FrameData) == 6 * 64 + 25 * 16);
static_assert(sizeof(LightDesc) == 80);
static_assert(sizeof(LightCounts) == 32);
static_assert(sizeof(Cluster) == 48);
static_assert(sizeof(DrawData) == 3 * 64 + 16);
static_assert(sizeof(Material) == 8 * 16);
static_assert(sizeof(DrawGeometry) == 32);
static_assert(sizeof(PointLight) == 32);
static_assert(sizeof(ViewParams) == 80);
static_assert(sizeof(ViewDecodeParams) == 32 * 2 + 16 * 5 + 32 * 2 + 64);
}  // namespace gb::gpu
#endif

#endif
