// What libraries print by themselves on stderr (libpng's "libpng error: ...", OpenEXR's and
// tinygltf's messages): captured while gblens calls them, so that the user sees gblens's one line,
// with the library's words folded into it when the call fails. With showLibraryOutput(true)
// (import --verbose) or GBLENS_VERBOSE=1 they pass through as they come.
#pragma once
#include <string>

namespace gb {

// Captures fd 2 from construction to text() (or destruction). Instances may overlap (threads,
// nesting): the first redirects, the last restores; each sees what was printed in its lifetime.
class LibraryOutput {
 public:
  LibraryOutput();
  ~LibraryOutput();
  LibraryOutput(const LibraryOutput&) = delete;
  LibraryOutput& operator=(const LibraryOutput&) = delete;
  // What was printed since construction, on one line ("; " between lines, at most ~300
  // characters; "" when nothing was); ends this capture.
  std::string text();
  // " [libpng error: ...]" when something was printed, else "": for appending to a message.
  std::string suffix();

 private:
  long start_ = -1;  // offset in the shared capture file; -1: not capturing (verbose, or ended)
};

void showLibraryOutput(bool show);

}  // namespace gb
