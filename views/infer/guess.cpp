// The "guess" object of a drafted quantity (guess.h).
#include "views/infer/guess.h"

#include <algorithm>
#include <cmath>

namespace gb {

nlohmann::json Guess::json() const {
  nlohmann::json j = {{"quantity", quantity}, {"evidence", evidence},
                      {"confidence", std::round(confidence * 1000.0) / 1000.0}};
  if (!rejected.empty()) {
    nlohmann::json r = nlohmann::json::array();
    for (const Rejected& x : rejected) r.push_back({{"hypothesis", x.hypothesis}, {"evidence", x.evidence}});
    j["rejected"] = r;
  }
  if (!undecided.empty()) j["undecided"] = undecided;
  return j;
}

double marginConfidence(double best, double next) {
  if (!std::isfinite(best)) return 0.0;
  if (!(next > 0.0)) return best <= 0.0 && next <= 0.0 ? 0.0 : 1.0;
  if (!std::isfinite(next)) return 1.0;
  return std::clamp(1.0 - best / next, 0.0, 1.0);
}

}  // namespace gb
