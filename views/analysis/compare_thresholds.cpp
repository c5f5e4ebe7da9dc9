// Compare's thresholds and decision rule, after OpenImageIO idiff: global, per-target and
// per-quantity settings, the most specific winning; pass/warn/fail from the fractions over them.
#include <cmath>
#include <cstdlib>

#include "views/analysis/compare.h"

namespace gb {

bool ThresholdSettings::add(const std::string& param, const std::string& text, std::string& error) {
  std::string key, number = text;
  size_t eq = text.find('=');
  if (eq != std::string::npos) {
    key = text.substr(0, eq);
    number = text.substr(eq + 1);
    // Imported layouts name their own targets: which exist is known only when both captures are
    // loaded (compareCaptures checks it); here only the shape of a key.
    const std::string target = key.substr(0, key.find('.'));
    if (target.empty() || target.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos) {
      error = "--" + param + " " + text + ": \"" + key + "\" names no target";
      return false;
    }
  }
  char* end = nullptr;
  double v = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || std::isnan(v) || v < 0.0) {
    error = "--" + param + " " + text + ": expected a non-negative number" + (key.empty() ? "" : " after =");
    return false;
  }
  byKey[key][param] = v;
  return true;
}

Thresholds ThresholdSettings::resolve(const std::string& target, const std::string& key) const {
  Thresholds t;
  for (const std::string& k : {std::string(), target, key}) {
    auto it = byKey.find(k);
    if (it == byKey.end()) continue;
    for (auto& [param, v] : it->second) {
      if (param == "fail") t.fail = v;
      if (param == "failpercent") t.failPercent = v;
      if (param == "hardfail") t.hardFail = v;
      if (param == "warn") t.warn = v;
      if (param == "warnpercent") t.warnPercent = v;
    }
  }
  return t;
}

Verdict decide(const Thresholds& t, uint64_t pixels, uint64_t overWarn, uint64_t overFail, double maxError) {
  if (double(overFail) > t.failPercent / 100.0 * double(pixels) || maxError > t.hardFail) return Verdict::Fail;
  if (double(overWarn) > t.warnPercent / 100.0 * double(pixels)) return Verdict::Warn;
  return Verdict::Pass;
}

}  // namespace gb
