// The file-name check of file_name.h.
#include "renderer/core/file_name.h"

namespace gb {

bool safeFileName(const std::string& name, std::string& why) {
  if (name.empty()) {
    why = "empty";
    return false;
  }
  if (name.size() > kMaxNameBytes) {
    why = "longer than " + std::to_string(kMaxNameBytes) + " bytes (" + std::to_string(name.size()) + ")";
    return false;
  }
  if (name[0] == '.') {
    why = "starts with '.'";
    return false;
  }
  for (char c : name) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '/' || c == '\\') {
      why = std::string("contains '") + c + "'";
      return false;
    }
    if (u < 0x20 || u == 0x7F) {
      why = "contains a control character";
      return false;
    }
  }
  return true;
}

}  // namespace gb
