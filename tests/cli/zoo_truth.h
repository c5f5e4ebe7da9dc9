// A drafted layout held to the gbuffer_zoo subject's truth file (tests/subjects/gbuffer_zoo/truth/
// MODE.json, written by hand from its shaders): every quantity the truth lists is drafted as it says,
// or as unknown (stored values), never as another quantity or with another field; what the geometry
// and the frame's structure decide (positions, normals, depths, albedo, lit colour, stencil) must be
// decided. Shared by the RenderDoc (import) and live (attach) tests.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gb::zoo {

extern const char* const kModes[7];

std::string truthPath(const std::string& mode);
nlohmann::json readJson(const std::string& path);

struct Verdict {
  int right = 0, unknown = 0;
  std::vector<std::string> wrong;  // a quantity drafted as something else, a field that differs, one missing
  std::string text() const;
};

// Finds a truth attachment's target in the draft: (pass, "color N" | "depth") -> the draft's target, or null.
using TargetOf = std::function<const nlohmann::json*(int pass, const std::string& attachment)>;
// An import draft's targets by the "guess" each carries ({"pass", "attachment"}); a live draft's by
// its live source ({"pass": P, "color": C} or {"depth": true}).
TargetOf importTargets(const nlohmann::json& draft);
TargetOf liveTargets(const nlohmann::json& draft);

Verdict compare(const nlohmann::json& truth, const nlohmann::json& draft, const TargetOf& targetOf);
// The camera block against the truth's buffer members, conventions and up axis ("" : as the truth).
std::string compareCamera(const nlohmann::json& truth, const nlohmann::json& draft);

}  // namespace gb::zoo
