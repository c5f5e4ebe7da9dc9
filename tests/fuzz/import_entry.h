// One input to the import path, for libFuzzer (fuzz_import.cpp) and for the deterministic corpus in
// `make test` (tests/unit/test_import_corpus.cpp). The first byte chooses what the rest is:
//   L  a layout (parsed, resolved, imported against small source files)   C  a camera sidecar
//   P/E/T/H  a PNG/EXR/TIFF/HDR source file of a layout of size 4x2; p/e/t/h: the file's size
//   R  a raw dump (byte 2: format, bytes 3-4: size; byte 5: 3 mod 4 writes the rest as given, else cut
//      to the dump's size)
//   M  a manifest and lights.json (split at the first NUL), read as loadCapture reads them
//   D  an .rdc listed by the RenderDoc replay (only with GBLENS_FUZZ_RDC=1: a replay takes seconds)
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace gb::fuzz {

// Runs one input; returns "" when it was accepted, else the one-line refusal. Anything else (a
// crash, an exception, a sanitizer report, a hang) is a bug. `dir` holds the small source files the
// layouts name (written on first use) and the files made from inputs.
std::string importOne(const uint8_t* data, size_t size, const std::string& dir);

}  // namespace gb::fuzz
