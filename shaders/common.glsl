// Set 0 (scene + frame) declarations and specialization constants used by every shader.
#include "shared.h"

layout(set = 0, binding = kBindingFrame) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = kBindingDraws, std430) readonly buffer DrawBlock { DrawData draws[]; };
layout(set = 0, binding = kBindingMaterials, std430) readonly buffer MaterialBlock { Material materials[]; };
// Light setup on the GPU writes the lights (GB_LIGHTS_WRITTEN); every other shader reads them.
#ifdef GB_LIGHTS_WRITTEN
#define GB_LIGHT_ACCESS
#else
#define GB_LIGHT_ACCESS readonly
#endif
layout(set = 0, binding = kBindingLights, std430) GB_LIGHT_ACCESS buffer LightBlock { PointLight lights[]; };
layout(set = 0, binding = kBindingVisible, std430) GB_LIGHT_ACCESS buffer VisibleBlock { uint visibleLights[]; };
// The visible lights' positions and radii in visible-list order: the culling passes walk them by
// visible-list position with one load, not two dependent ones (visibleLights, then lights).
layout(set = 0, binding = kBindingVisiblePositions, std430) GB_LIGHT_ACCESS buffer VisiblePositionBlock { vec4 visiblePositions[]; };
layout(set = 0, binding = kBindingLightCounts, std430) GB_LIGHT_ACCESS buffer LightCountBlock { LightCounts lightCounts; };

layout(constant_id = kSpecEyeDepth) const uint EYE_DEPTH = 1;
layout(constant_id = kSpecAlphaTest) const uint ALPHA_TEST = 0;
layout(constant_id = kSpecCoverage) const uint COVERAGE = 0;
layout(constant_id = kSpecReversedZ) const uint REVERSED_Z = 0;
layout(constant_id = kSpecNormalEncoding) const uint NORMAL_ENCODING = kNormalRgba16f;
layout(constant_id = kSpecNormalMap) const uint NORMAL_MAP = 0;
layout(constant_id = kSpecBaseColorTexture) const uint BASE_TEXTURE = 1;
layout(constant_id = kSpecOctPrecise) const uint OCT_PRECISE = 0;
layout(constant_id = kSpecPosition) const uint POSITION = kPositionDepth;

// A material's texture coordinates: xy base colour, zw normal texture, each from its UV set with
// its KHR_texture_transform applied. Computed per vertex: a fragment shader must not build them
// from material data, because lavapipe's helper invocations read zeros from storage buffers and
// the derivatives (texture LOD) along triangle edges would come out huge (dashed seams).
vec4 materialUvs(Material m, vec2 uv0, vec2 uv1) {
  vec3 b = vec3(m.textures.z == 0 ? uv0 : uv1, 1.0), n = vec3(m.textures.w == 0 ? uv0 : uv1, 1.0);
  return vec4(dot(m.baseUv0.xyz, b), dot(m.baseUv1.xyz, b), dot(m.normalUv0.xyz, n), dot(m.normalUv1.xyz, n));
}

// Hardware depth of the far plane: where nothing was drawn.
float farDepth() { return REVERSED_Z != 0 ? 0.0 : 1.0; }
