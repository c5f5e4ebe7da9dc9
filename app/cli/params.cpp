// --param NAME=VALUE parsing (see params.h).
#include "app/cli/params.h"

#include <algorithm>

namespace gb {

bool parseLayoutParameters(const std::vector<std::string>& params, RenderOptions& options, std::string& error,
                           std::vector<std::string>* given) {
  for (const std::string& p : params) {
    const size_t eq = p.find('=');
    std::string name = eq == std::string::npos ? "" : p.substr(0, eq);
    if (name.rfind("--", 0) == 0) name = name.substr(2);
    std::replace(name.begin(), name.end(), '-', '_');
    if (name.empty() || !findOption(name)) {
      error = "--param " + p + ": expected NAME=VALUE with NAME an option of gblens --help (e.g. normal_format=oct-rg16)";
      return false;
    }
    if (!setOption(options, name, p.substr(eq + 1), error)) {
      error = "--param " + p + ": " + error;
      return false;
    }
    if (given) given->push_back(name);
  }
  return true;
}

}  // namespace gb
