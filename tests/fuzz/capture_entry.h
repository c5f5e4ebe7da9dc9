// One input to the capture readers (loadCapture: the manifest, lights.json, the file list, the
// EXRs), for libFuzzer (fuzz_capture.cpp) and for the deterministic corpus in `make test`
// (tests/unit/test_capture_corpus.cpp). An input is: a mode byte, manifest.json, NUL, lights.json,
// NUL, then the bytes of every other file the manifest lists (an EXR). Mode 'S' (signed): the entry
// writes the manifest's file list with the true sizes and SHA-256 of what it wrote, so that inputs
// reach the manifest's fields and the EXR reader; 'U': the manifest as given.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace gb::fuzz {

// Runs one input in a fresh capture folder under `dir`; returns "" when loadCapture accepted it,
// else its one-line refusal. Anything else (a crash, an exception, a sanitizer report, a hang) is a bug.
std::string captureOne(const uint8_t* data, size_t size, const std::string& dir);

}  // namespace gb::fuzz
