// Layout files (docs/layout-format.md): JSON in, a validated Layout out, with one-line errors that
// name the file, the target or quantity and the field. Parameterised layouts (gblens.json) are
// resolved with option values first.
#pragma once
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "renderer/core/layout.h"
#include "renderer/core/options.h"

namespace gb {

// Option name -> value text (as getOption() writes it), for {"by": ..., "cases": ...} and "when".
using LayoutParameters = std::map<std::string, std::string>;
LayoutParameters layoutParameters(const RenderOptions& options);

// Replaces every {"by", "cases"} value with its case and drops array elements whose "when" does
// not hold. False with a message (naming `where` and the option) when a value has no case.
bool resolveLayoutParameters(nlohmann::json& j, const LayoutParameters& params, const std::string& where,
                             std::string& error);

// Validates and converts a (resolved) layout. `file` names it in messages and is kept in Layout::file.
bool parseLayout(const nlohmann::json& j, const std::string& file, Layout& out, std::string& error);

// A camera block on its own (a sidecar file), with the same checks; `where` names it in messages.
bool parseLayoutCamera(const nlohmann::json& j, const std::string& where, LayoutCamera& out, std::string& error);

// Reads, resolves and parses a layout file.
bool loadLayoutFile(const std::string& path, const LayoutParameters& params, Layout& out, std::string& error);

// The layout as JSON (resolved; what capture manifests embed). parseLayout(layoutJson(l)) == l.
nlohmann::json layoutJson(const Layout& layout);
nlohmann::json layoutCameraJson(const LayoutCamera& camera);
// A live source's pick as the layout writes it ({"pass": ..., "name": ...}; gblens attach's request too).
nlohmann::json livePickJson(const TargetSource::LivePick& pick);

// gblens's own frame under these options: assets/layouts/gblens.json resolved with them.
const Layout& nativeLayout(const RenderOptions& options);
// Whether a layout is gblens's own (any options; also an import through builtin:gblens): only then do
// its targets mean gblens's targets (FrameSnapshot::target, the probe's sections on gblens's frame).
bool gblensLayout(const Layout& layout);

}  // namespace gb
