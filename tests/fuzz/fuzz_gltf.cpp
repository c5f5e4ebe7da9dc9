// libFuzzer entry point: any bytes, as a .gltf or .glb, must load or be refused with a SceneError;
// anything else (a crash, an assert, another exception, a sanitizer report, a hang) is a bug.
// External URIs resolve in tests/data/gltf/valid, so seeds with .bin files are explored too.
#include <cstddef>
#include <cstdint>

#include "renderer/scene/builtin.h"
#include "renderer/scene/gltf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    gb::Scene scene = gb::loadGltfMemory(data, size, "fuzz.gltf", GBLENS_FUZZ_BASE_DIR, 2);
    (void)scene;
  } catch (const gb::SceneError&) {
    // A clear refusal: the expected outcome for most inputs.
  }
  return 0;
}
