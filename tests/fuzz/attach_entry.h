// One input to `gblens attach`'s command line (app/cli/attach_args.h), for libFuzzer (fuzz_attach.cpp)
// and for the deterministic corpus in `make test` (tests/unit/test_attach_args.cpp): the arguments
// after "gblens attach", NUL-separated ("@NAME" names a layout file of the work folder: live.json,
// file.json, draft.json). They are parsed, checked and the layout resolved as `gblens attach` does
// before it starts anything; no application is started, no socket made.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace gb::fuzz {

// "" when the command line would start the application, else its one-line refusal. Anything else
// (a crash, an exception, a sanitizer report, a hang) is a bug.
std::string attachOne(const uint8_t* data, size_t size, const std::string& dir);

}  // namespace gb::fuzz
