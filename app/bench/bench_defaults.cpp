// The defaults check (see bench_report.h): interleaved A/B statistics (the median ratio's
// distribution-free confidence interval), the time-vs-error frontier per quality group, and
// whether a variant dominates the defaults (errors no worse, time not slower, better somewhere).
#include "app/bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "app/bench/bench_format.h"
#include "renderer/core/statistics.h"

namespace gb {

// ---- A/B statistics ----------------------------------------------------------------------------

AbResult abStatistics(std::vector<double> ratios) {
  AbResult ab;
  std::sort(ratios.begin(), ratios.end());
  const size_t n = ratios.size();
  if (n == 0) return ab;
  ab.median = median(ratios);
  ab.lowerQuartile = ratios[(n - 1) / 4];
  ab.upperQuartile = ratios[std::min(n - 1, n * 3 / 4)];
  // Distribution-free interval of the median: the number of ratios below the true median is
  // Binomial(n, 1/2), so [r(k), r(n+1-k)] (1-based) covers it with 1 - 2 P(B < k). k: the largest
  // with P(B < k) <= 2.5% (at least 1: the whole range).
  double term = std::ldexp(1.0, -int(n));  // P(B = i), from i = 0
  size_t k = 1;
  double tail = term;  // P(B < k) for k = 1
  for (size_t i = 1; i < n; ++i) {
    term *= double(n - i + 1) / double(i);
    if (tail + term > 0.025) break;
    tail += term;
    k = i + 1;
  }
  ab.ciLow = ratios[k - 1];
  ab.ciHigh = ratios[n - k];
  ab.confidence = 1.0 - 2.0 * tail;
  ab.ratios = std::move(ratios);
  return ab;
}

std::string abVerdict(const AbResult& ab, double tolerance) {
  if (ab.pairs() == 0) return "";
  if (ab.ciHigh < 1.0) return "faster";
  if (ab.ciLow > 1.0) return "slower";
  if (ab.ciLow >= 1.0 - tolerance && ab.ciHigh <= 1.0 + tolerance) return "same within " + num(100.0 * tolerance, 2) + "%";
  return "undecided";
}

// ---- frontier and defaults ----------------------------------------------------------------------

static const BenchRow* defaultRow(const std::vector<BenchRow>& rows, const std::string& scene) {
  for (const BenchRow& r : rows)
    if (r.scene == scene && r.group == "default" && r.measured) return &r;
  return nullptr;
}

void markFrontiers(std::vector<BenchRow>& rows) {
  std::set<std::string> scenes;
  for (const BenchRow& r : rows) scenes.insert(r.scene);
  for (BenchRow& r : rows) r.frontier = false;
  for (const std::string& scene : scenes)
    for (const BenchGroup& g : benchGroups()) {
      if (g.metric.empty()) continue;
      std::vector<BenchRow*> pts;
      for (BenchRow& r : rows)
        if (r.scene == scene && r.measured && (r.group == g.name || r.group == "default") && r.error.count(g.metric))
          pts.push_back(&r);
      for (BenchRow* a : pts) {
        bool dominated = false;
        for (BenchRow* b : pts) {
          if (a == b) continue;
          double ea = a->error[g.metric], eb = b->error[g.metric];
          double ta = a->frameMs.median, tb = b->frameMs.median;
          if (eb <= ea && tb <= ta && (eb < ea || tb < ta)) dominated = true;
        }
        if (!dominated) a->frontier = true;
      }
    }
}

const std::vector<std::pair<std::string, double>>& dominanceObjectives() {
  static const std::vector<std::pair<std::string, double>> objectives = {
      {"normal_deg_mean", 1e-5},    // 1.7e-7 rad: the float arithmetic around a stored normal
      {"normal_deg_max", 1e-5},     // the worst case (what precise octahedral encoding lowers)
      {"position_rel_mean", 1e-7},  // about one float32 ulp of relative precision
      {"shadow_mismatch", 1e-4},    // a hundredth of a percent of the compared pixels
      {"lighting_rel_mean", 1e-6},
      {"hdr_rel_mean", 1e-4},
  };
  return objectives;
}

// Every compared error figure of v within tolerance of d's; `better`: one beyond it.
static bool errorsNoWorse(const BenchRow& v, const BenchRow& d, const BenchTolerances& tol, bool& better) {
  bool noWorse = true;
  better = false;
  for (const auto& [k, floor] : dominanceObjectives()) {
    auto iv = v.error.find(k), id = d.error.find(k);
    if (iv == v.error.end() || id == d.error.end()) continue;
    noWorse &= iv->second <= id->second * (1.0 + tol.error) + floor;
    better |= iv->second < id->second * (1.0 - tol.error) - floor;
  }
  return noWorse;
}

static bool qualityVariant(const BenchRow& v) {
  const BenchGroup* g = findBenchGroup(v.group);
  return v.measured && g && !g->metric.empty() && v.group != "default";
}

std::vector<std::string> errorNoWorseThanDefaults(const std::vector<BenchRow>& rows, const std::string& scene,
                                                  const BenchTolerances& tol) {
  std::vector<std::string> out;
  const BenchRow* d = defaultRow(rows, scene);
  if (!d) return out;
  for (const BenchRow& v : rows) {
    bool better;
    if (v.scene == scene && qualityVariant(v) && errorsNoWorse(v, *d, tol, better)) out.push_back(v.name);
  }
  return out;
}

std::vector<DefaultsCheck> checkDefaults(const std::vector<BenchRow>& rows, const BenchTolerances& tol) {
  std::vector<DefaultsCheck> out;
  std::set<std::string> scenes;
  for (const BenchRow& r : rows) scenes.insert(r.scene);
  for (const std::string& scene : scenes) {
    const BenchRow* d = defaultRow(rows, scene);
    if (!d) continue;
    DefaultsCheck c;
    c.scene = scene;
    for (const BenchRow& v : rows) {
      if (&v == d || v.scene != scene || !qualityVariant(v)) continue;
      bool errorBetter;
      if (!errorsNoWorse(v, *d, tol, errorBetter)) continue;
      // Time only from the A/B's interval: a variant without one (no time left) is not judged.
      if (v.ab.pairs() == 0) {
        if (errorBetter) c.undecided.push_back(v.name);
        continue;
      }
      const bool notSlower = v.ab.ciHigh <= 1.0 + tol.time, faster = v.ab.ciHigh < 1.0;
      if (notSlower && (errorBetter || faster))
        c.dominatedBy.push_back(v.name);
      else if (errorBetter && v.ab.ciLow <= 1.0 + tol.time)
        c.undecided.push_back(v.name);  // better, and not shown slower beyond the tolerance either
    }
    c.onFrontier = c.dominatedBy.empty();
    out.push_back(c);
  }
  return out;
}

}  // namespace gb
