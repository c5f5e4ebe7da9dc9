// --param NAME=VALUE (import, attach): the option values a parameterised layout is resolved with.
// Apart from cli.h (which brings the renderer) so that the attach command line can be fuzzed alone.
#pragma once
#include <string>
#include <vector>

#include "renderer/core/options.h"

namespace gb {

// --param NAME=VALUE... -> `options` (option names as in the option table, or as flags); `given`
// (when not null) receives each option's table name, the ones the user stated. False with a
// message naming the --param.
bool parseLayoutParameters(const std::vector<std::string>& params, RenderOptions& options, std::string& error,
                           std::vector<std::string>* given = nullptr);

}  // namespace gb
