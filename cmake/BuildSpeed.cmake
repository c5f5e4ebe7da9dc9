# What makes the build fast (docs/build.md has the figures): ccache when present, shared by every
# clone (paths hashed relative to the source folder), precompiled headers for the third-party headers
# most files include, and test code compiled at -O1 (test sources cost the compiler, not the run).
find_program(GBLENS_CCACHE ccache)
if(GBLENS_CCACHE)
  # pch_defines,time_macros: ccache may serve files that use a precompiled header (ccache's manual,
  # "Precompiled headers"); the base dir makes a fresh clone elsewhere hit what another clone built.
  set(launcher ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${CMAKE_SOURCE_DIR}
      CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime ${GBLENS_CCACHE})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${launcher})
  set(CMAKE_C_COMPILER_LAUNCHER ${launcher})
endif()

# Unity builds: the files of a target compiled 16 at a time, so that the headers and templates they
# share (nlohmann-json, CLI11, gtest, glm) are parsed and instantiated once per batch, not once per
# file (docs/build.md: 4x less compiler time for the gblens executable). Helpers in anonymous
# namespaces therefore need names unique within their target. -DGBLENS_UNITY=OFF for an edit-compile
# loop that recompiles one file at a time.
option(GBLENS_UNITY "compile each target's sources in batches (unity build)" ON)
set(CMAKE_UNITY_BUILD ${GBLENS_UNITY})
set(CMAKE_UNITY_BUILD_BATCH_SIZE 16)

# A static or object library's files compile without waiting for the libraries it links to be built
# (only for those with generated sources): both cores stay busy to the end of the build.
set(CMAKE_OPTIMIZE_DEPENDENCIES ON)

# The headers nearly every translation unit parses (measured: nlohmann-json in 178 of 314, glm in 254,
# gtest in every test file, CLI11 in every command; docs/build.md).
set(GBLENS_PCH_COMMON <algorithm> <array> <cmath> <cstdint> <cstring> <functional> <map> <memory> <optional>
    <set> <sstream> <string> <unordered_map> <vector> <nlohmann/json.hpp>)
set(GBLENS_PCH_GLM <glm/glm.hpp> <glm/gtc/matrix_transform.hpp>)

# gblens_pch(TARGET KIND): KIND library (one header shared by every gblens library: same flags),
# cold (code whose speed no figure depends on: the command line, the viewer's windows, the bench
# harness, the report writer; compiled at -O1, which halves its code generation, sharing one header
# with CLI11 in it), tests (the test executables: gtest too, at -O1), own (a target with flags of its
# own, e.g. the Vulkan layer: its own header).
function(gblens_pch TARGET KIND)
  if(KIND STREQUAL "library")
    if(NOT "${TARGET}" STREQUAL "gblens_core")
      target_precompile_headers(${TARGET} REUSE_FROM gblens_core)
    else()
      target_precompile_headers(${TARGET} PRIVATE ${GBLENS_PCH_COMMON} ${GBLENS_PCH_GLM})
    endif()
  elseif(KIND STREQUAL "cold")
    target_compile_options(${TARGET} PRIVATE -O1)
    get_property(first GLOBAL PROPERTY GBLENS_COLD_PCH)
    if(first)
      target_precompile_headers(${TARGET} REUSE_FROM ${first})
    else()
      set_property(GLOBAL PROPERTY GBLENS_COLD_PCH ${TARGET})
      target_precompile_headers(${TARGET} PRIVATE ${GBLENS_PCH_COMMON} ${GBLENS_PCH_GLM} <CLI/CLI.hpp>)
    endif()
  elseif(KIND STREQUAL "tests")
    target_compile_options(${TARGET} PRIVATE -O1)
    get_property(first GLOBAL PROPERTY GBLENS_TEST_PCH)
    if(first)
      target_precompile_headers(${TARGET} REUSE_FROM ${first})
    else()
      set_property(GLOBAL PROPERTY GBLENS_TEST_PCH ${TARGET})
      target_precompile_headers(${TARGET} PRIVATE ${GBLENS_PCH_COMMON} ${GBLENS_PCH_GLM} <gtest/gtest.h>)
    endif()
  else()
    target_precompile_headers(${TARGET} PRIVATE ${GBLENS_PCH_COMMON})
  endif()
endfunction()
