// Set 0 (scene + frame) declarations and specialization constants used by every shader.
#include "shared.h"

layout(set = 0, binding = kBindingFrame) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = kBindingDraws, std430) readonly buffer DrawBlock { DrawData draws[]; };
layout(set = 0, binding = kBindingMaterials, std430) readonly buffer MaterialBlock { Material materials[]; };
layout(set = 0, binding = kBindingLights, std430) readonly buffer LightBlock { PointLight lights[]; };
layout(set = 0, binding = kBindingVisible, std430) readonly buffer VisibleBlock { uint visibleLights[]; };

layout(constant_id = kSpecEyeDepth) const uint EYE_DEPTH = 1;
layout(constant_id = kSpecAlphaTest) const uint ALPHA_TEST = 0;
layout(constant_id = kSpecCoverage) const uint COVERAGE = 0;
layout(constant_id = kSpecReversedZ) const uint REVERSED_Z = 0;
layout(constant_id = kSpecNormalEncoding) const uint NORMAL_ENCODING = kNormalRgba16f;
layout(constant_id = kSpecNormalMap) const uint NORMAL_MAP = 0;
layout(constant_id = kSpecPosition) const uint POSITION = kPositionDepth;

// Hardware depth of the far plane: where nothing was drawn.
float farDepth() { return REVERSED_Z != 0 ? 0.0 : 1.0; }
