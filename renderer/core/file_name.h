// Names that become file names (a capture's <target>.exr, compare's <target>.<quantity>.png): one
// check, so that no name read from a layout or manifest can leave the folder it is written in.
#pragma once
#include <string>

namespace gb {

// The longest name (bytes) of a target or quantity: with OpenEXR's "<target>.raw.<channel>" well
// inside its 255-byte channel names, and a file name inside the 255 bytes of common file systems.
constexpr size_t kMaxNameBytes = 100;

// True when `name` can be one file name in a folder: 1..kMaxNameBytes bytes, no '/', '\\', NUL or
// control character, not "." or "..", not starting with '.' (hidden, and how ".." begins). Else
// false with why in `error` ("...: ... contains '/'").
bool safeFileName(const std::string& name, std::string& why);

}  // namespace gb
