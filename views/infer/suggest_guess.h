// What names say about a target, for draft layouts: words in texture, pass and EXR channel names
// (Blender's passes, Unreal's buffers, OIIO's channel names, common engine words) and the quantity
// each names; storage format and target names. Names are a hint the drafting uses only where the
// geometry cannot test (views/infer/infer.h).
#pragma once
#include <set>
#include <string>
#include <vector>

#include "renderer/core/layout.h"

namespace gb {

// The quantities a name says, in order: the whole name first ("basecolor"), then its words
// ("GBuffer.AlbedoSpec" -> albedo, specular); none for a name that says nothing.
std::vector<QuantityKind> namedKinds(const std::string& name);

// The layout's storage format name for a RenderDoc format name ("R16G16B16A16_FLOAT" -> "rgba16f",
// "D32S8" -> "d32s8"); "" when a layout cannot name it (BGRA, block-compressed, ...).
std::string storageFormatName(const std::string& renderDocFormat);

// A layout target name from any text: lower case, a-z 0-9 _, unique among `used`.
std::string targetName(const std::string& text, std::set<std::string>& used);

}  // namespace gb
