// Where the tests find the source tree, the build and the programs they run (GBLENS_SOURCE_DIR, ...).
// Functions, not compile definitions: a path on the compiler's command line would make every test
// file's ccache entry belong to one clone (docs/build.md); only the generated test_paths.cpp differs.
#pragma once
#include <string>

namespace gbtest {
std::string sourceDir();
std::string buildDir();
std::string gblensBinary();
std::string zooBinary();
std::string foreignBinary();
}  // namespace gbtest

#define GBLENS_SOURCE_DIR (::gbtest::sourceDir())
#define GBLENS_BUILD_DIR (::gbtest::buildDir())
#define GBLENS_BINARY (::gbtest::gblensBinary())
#define ZOO_BINARY (::gbtest::zooBinary())
#define GBUFFER_ZOO_BINARY (::gbtest::zooBinary())
#define FOREIGN_DEFERRED_BINARY (::gbtest::foreignBinary())
#define ZOO_DIR (::gbtest::sourceDir() + "/tests/subjects/gbuffer_zoo")
#define GBUFFER_ZOO_DIR ZOO_DIR
#define FOREIGN_DEFERRED_DIR (::gbtest::sourceDir() + "/tests/subjects/foreign_deferred")
