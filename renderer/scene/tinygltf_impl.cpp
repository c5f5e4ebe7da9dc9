// tinygltf's implementation, compiled once, configured as renderer/gltf_internal.h says: JSON
// through the system nlohmann-json, no stb (the loader keeps images encoded and decodes them with
// OpenImageIO), no default file system callbacks (the loader supplies its own: no shell expansion
// of URIs), no image writing.
#include <fstream>  // tinygltf's writer needs it and includes it only with its own file system

#define TINYGLTF_IMPLEMENTATION
#include "renderer/scene/gltf_internal.h"
