// Bench rows -> frontier, defaults check, bench.json, bench.csv, bench.md (plots: bench_plot.cpp).
#include "app/bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "app/bench/bench_format.h"
#include "renderer/core/statistics.h"
#include "views/capture/report.h"

namespace gb {

const std::vector<BenchGroup>& benchGroups() {
  static const std::vector<BenchGroup> groups = {
      {"default", "", "the renderer's defaults"},
      {"normal", "normal_deg_mean", "normal storage: mean angular error (deg)"},
      {"depth", "position_rel_mean", "position source: mean |P - P_ref| / depth"},
      {"accumulation", "lighting_rel_mean", "accumulation, path, culling: lighting-pass relative error (mean)"},
      {"shadow", "shadow_mismatch", "shadow map: lit/shadowed mismatch outside the band (fraction)"},
      {"lights", "", "time vs point lights"},
      {"size", "", "time vs output size"},
      {"repeat", "", "the defaults again at the end of a scene (drift)"},
  };
  return groups;
}

const BenchGroup* findBenchGroup(const std::string& name) {
  for (const BenchGroup& g : benchGroups())
    if (g.name == name) return &g;
  return nullptr;
}

Timing timingOf(std::vector<double> v) {
  Timing t;
  if (v.empty()) return t;
  t.median = median(v);
  t.min = *std::min_element(v.begin(), v.end());
  t.max = *std::max_element(v.begin(), v.end());
  return t;
}

const std::vector<std::pair<std::string, std::string>>& errorSummaryKeys() {
  static const std::vector<std::pair<std::string, std::string>> keys = {
      {"normal_deg_mean", "normal angular error, mean (deg)"},
      {"normal_deg_max", "normal angular error, max (deg)"},
      {"eye_depth_rel_max", "eye-depth target, max relative error"},
      {"position_rel_mean", "position used by lighting, mean |dP| / depth"},
      {"position_rel_max", "position used by lighting, max |dP| / depth"},
      {"shadow_mismatch", "lit/shadowed mismatch outside the penumbra band (fraction of compared pixels)"},
      {"hdr_rel_mean", "final HDR vs reference, mean relative error (surface pixels)"},
      {"hdr_rel_rms", "final HDR vs reference, RMS relative error"},
      {"lighting_rel_mean", "lighting passes alone, mean relative error"},
      {"lighting_per_contribution_max", "lighting passes alone, max error per light contribution"},
      {"silhouette_fraction", "silhouette pixels / all pixels"},
  };
  return keys;
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
      {"normal_deg_mean", 1e-4},    // a ten-thousandth of a degree
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
    const BenchRow* first = defaultRow(rows, scene);
    if (!first) continue;
    BenchRow fastest = *first;  // the faster of the defaults' runs: drift must not favour a variant
    for (const BenchRow& r : rows)
      if (r.scene == scene && r.group == "repeat" && r.measured && r.frameMs.median < fastest.frameMs.median)
        fastest.frameMs = r.frameMs;
    const BenchRow* d = &fastest;
    DefaultsCheck c;
    c.scene = scene;
    for (const BenchRow& v : rows) {
      if (&v == first || v.scene != scene || !qualityVariant(v)) continue;
      // No worse anywhere (within tolerance), better somewhere (beyond it).
      const bool ab = v.abTimeRatio > 0.0;
      double ratio = ab ? v.abTimeRatio : v.frameMs.median / d->frameMs.median;
      bool errorBetter;
      bool noWorse = errorsNoWorse(v, *d, tol, errorBetter) && ratio <= 1.0 + tol.time;
      bool better = errorBetter || (ratio < 1.0 - tol.time && (!ab || v.abTimeRatioUpperQuartile < 1.0));
      if (noWorse && better) c.dominatedBy.push_back(v.name);
    }
    c.onFrontier = c.dominatedBy.empty();
    out.push_back(c);
  }
  return out;
}

// ---- targets ----------------------------------------------------------------------------------

static nlohmann::json targetsJson(const BenchReport& r) {
  nlohmann::json t = nlohmann::json::array();
  auto worst = [&](const std::string& source) {
    double m = -1.0, ratio = 0.0;
    for (const DepthRangeRow& d : r.depthRange)
      if (d.source == source && d.relMax > m) m = d.relMax, ratio = d.ratio;
    return std::pair{m, ratio};
  };
  if (!r.depthRange.empty()) {
    double maxRatio = 0.0;
    for (const DepthRangeRow& d : r.depthRange) maxRatio = std::max(maxRatio, d.ratio);
    auto [eye, eyeAt] = worst("eye_depth");
    auto [rev, revAt] = worst("d32_reversed");
    auto [std32, stdAt] = worst("d32_standard");
    t.push_back({{"target", "position from eye depth: max |dP|/depth <= 1e-6, far/near up to " + std::to_string(int64_t(maxRatio))},
                 {"scene", "builtin:depth-range"}, {"measured", eye}, {"bound", 1e-6}, {"met", eye >= 0 && eye <= 1e-6}, {"worst_ratio", eyeAt}});
    t.push_back({{"target", "position from reversed-Z D32F: within 2x of eye depth's 1e-6"},
                 {"scene", "builtin:depth-range"}, {"measured", rev}, {"bound", 2e-6}, {"met", rev >= 0 && rev <= 2e-6}, {"worst_ratio", revAt},
                 {"vs_eye_depth", eye > 0 ? rev / eye : 0.0}});
    t.push_back({{"target", "position from standard-Z D32F (contrast, no bound)"}, {"scene", "builtin:depth-range"}, {"measured", std32}, {"worst_ratio", stdAt}});
  }
  std::set<std::string> scenes;
  for (const BenchRow& row : r.rows) scenes.insert(row.scene);
  for (const std::string& scene : scenes) {
    auto find = [&](const std::string& name) -> const BenchRow* {
      for (const BenchRow& row : r.rows)
        if (row.scene == scene && row.name == name && row.measured) return &row;
      return nullptr;
    };
    const BenchRow* d = find("default");
    if (d) {
      double n = d->error.at("normal_deg_mean");
      t.push_back({{"target", "normal mean angular error <= 0.03 deg with the default format (" +
                                  std::string(name(d->options.normalFormat)) + ")"},
                   {"scene", scene}, {"measured", n}, {"bound", 0.03}, {"met", n <= 0.03}});
    }
    // The defaults' row or the accum_format variant, whichever has the format.
    auto accum = [&](AccumFormat f) -> const BenchRow* {
      if (d && d->options.accumFormat == f) return d;
      return find(std::string("accum_format=") + name(f));
    };
    if (const BenchRow* h = accum(AccumFormat::Rgba16f)) {
      double l = h->error.at("lighting_per_contribution_max");
      t.push_back({{"target", "HDR (lighting passes, silhouettes excluded) per light contribution <= 2^-10 with fp16"},
                   {"scene", scene}, {"measured", l}, {"bound", std::ldexp(1.0, -10)}, {"met", l <= std::ldexp(1.0, -10)}});
    }
    if (const BenchRow* f = accum(AccumFormat::Rgba32f)) {
      double l = f->error.at("lighting_per_contribution_max");
      t.push_back({{"target", "HDR (lighting passes, silhouettes excluded) per light contribution <= 1e-5 with fp32"},
                   {"scene", scene}, {"measured", l}, {"bound", 1e-5}, {"met", l <= 1e-5}});
    }
  }
  for (const auto& m : methodTargets(r)) t.push_back(m);
  return t;
}

// ---- files ------------------------------------------------------------------------------------

nlohmann::json timingJson(const Timing& t) { return {{"median", t.median}, {"min", t.min}, {"max", t.max}}; }

nlohmann::json passesJson(const std::vector<PassTiming>& passes) {
  nlohmann::json out = nlohmann::json::array();
  for (const PassTiming& p : passes) {
    nlohmann::json pj = {{"name", p.name}, {"skipped", p.skipped}};
    if (p.skipped)
      pj["reason"] = p.reason;
    else
      pj["ms"] = timingJson(p.ms);
    out.push_back(pj);
  }
  return out;
}

void collectPassNames(const std::vector<PassTiming>& passes, std::vector<std::string>& names) {
  for (const PassTiming& p : passes)
    if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
}

void writePassCells(std::ostream& out, const std::vector<PassTiming>& passes, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    out << ",";
    for (const PassTiming& p : passes)
      if (p.name == name && !p.skipped) out << p.ms.median;
  }
}

nlohmann::json benchJson(const BenchReport& r) {
  nlohmann::json j = r.meta;
  nlohmann::json rows = nlohmann::json::array();
  for (const BenchRow& row : r.rows) {
    nlohmann::json o = {{"scene", row.scene}, {"group", row.group}, {"variant", row.name}, {"measured", row.measured}};
    if (!row.note.empty()) o["note"] = row.note;
    o["options"] = optionsJson(row.options);
    if (row.measured) {
      o["frames"] = row.frames;
      o["frame_ms"] = timingJson(row.frameMs);
      o["gpu_ms"] = timingJson(row.gpuMs);
      o["passes"] = passesJson(row.passes);
      o["error"] = row.error;
      o["error_detail"] = row.errorDetail;
      o["frontier"] = row.frontier;
      if (row.abPairs)
        o["ab_vs_defaults"] = {{"time_ratio", row.abTimeRatio},
                               {"time_ratio_upper_quartile", row.abTimeRatioUpperQuartile},
                               {"pairs", row.abPairs}};
    }
    rows.push_back(o);
  }
  j["rows"] = rows;
  nlohmann::json groups = nlohmann::json::array();
  for (const BenchGroup& g : benchGroups()) groups.push_back({{"name", g.name}, {"metric", g.metric}, {"title", g.title}});
  j["groups"] = groups;
  nlohmann::json dr = nlohmann::json::array();
  for (const DepthRangeRow& d : r.depthRange)
    dr.push_back({{"far_over_near", d.ratio}, {"znear", d.znear}, {"zfar", d.zfar}, {"source", d.source},
                  {"relative_max", d.relMax}, {"relative_mean", d.relMean}});
  j["depth_range"] = dr;
  j["methods"] = methodsJson(r);
  nlohmann::json skips = nlohmann::json::array();
  for (const SkipRow& s : r.skips)
    skips.push_back({{"pass", s.pass}, {"skipped_when", s.skippedWhen}, {"measured_as", s.measuredAs},
                     {"saved_frame_ms", s.savedMs}, {"pass_ms", s.passMs}, {"pairs", s.pairs}});
  j["skips"] = skips;
  nlohmann::json defaults = nlohmann::json::array();
  for (const DefaultsCheck& c : r.defaults)
    defaults.push_back({{"scene", c.scene}, {"on_frontier", c.onFrontier}, {"dominated_by", c.dominatedBy}});
  j["defaults"] = defaults;
  nlohmann::json floors;
  for (const auto& [k, f] : dominanceObjectives()) floors[k] = f;
  j["dominance_tolerance"] = {{"time", r.tolerances.time}, {"error", r.tolerances.error}, {"error_floors", floors}};
  j["targets"] = targetsJson(r);
  return j;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string benchCsv(const BenchReport& r) {
  std::vector<std::string> passNames;
  for (const BenchRow& row : r.rows) collectPassNames(row.passes, passNames);
  std::ostringstream out;
  out.precision(9);
  out << "scene,group,variant,measured,size,lights,frames,frame_ms,frame_ms_min,frame_ms_max,gpu_ms,gpu_ms_min,gpu_ms_max";
  for (const std::string& p : passNames) out << "," << p << "_ms";
  for (auto& [k, what] : errorSummaryKeys()) out << "," << k;
  out << ",frontier,note\n";
  for (const BenchRow& row : r.rows) {
    out << csvField(row.scene) << "," << row.group << "," << csvField(row.name) << "," << (row.measured ? 1 : 0) << ","
        << getOption(row.options, "size") << "," << row.options.lights << "," << row.frames << "," << row.frameMs.median
        << "," << row.frameMs.min << "," << row.frameMs.max << "," << row.gpuMs.median << "," << row.gpuMs.min << ","
        << row.gpuMs.max;
    writePassCells(out, row.passes, passNames);
    for (auto& [k, what] : errorSummaryKeys()) {
      out << ",";
      auto it = row.error.find(k);
      if (it != row.error.end()) out << it->second;
    }
    out << "," << (row.frontier ? 1 : 0) << "," << csvField(row.note) << "\n";
  }
  return out.str();
}

std::string num(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

std::string benchMarkdown(const BenchReport& r) {
  std::ostringstream md;
  md << "# gblens bench\n\n";
  md << "Device: " << r.meta.value("device", "?") << " (" << r.meta.value("driver", "?") << "), commit "
     << r.meta.value("git", "?") << ". " << r.meta.value("frames_note", "") << "\n\n";
  std::set<std::string> scenes;
  for (const BenchRow& row : r.rows) scenes.insert(row.scene);
  for (const std::string& scene : scenes) {
    md << "## " << scene << "\n\n";
    md << "| group | variant | frame ms (median [min-max]) | frames | error figure | value | frontier | A/B vs defaults |\n";
    md << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const BenchRow& row : r.rows) {
      if (row.scene != scene) continue;
      const BenchGroup* g = findBenchGroup(row.group);
      std::string metric = g && !g->metric.empty() ? g->metric : "hdr_rel_mean";
      md << "| " << row.group << " | " << row.name << " | ";
      if (!row.measured) {
        md << "skipped: " << row.note << " | | | | | |\n";
        continue;
      }
      md << num(row.frameMs.median, 4) << " [" << num(row.frameMs.min, 4) << "-" << num(row.frameMs.max, 4) << "] | "
         << row.frames << " | " << metric << " | " << (row.error.count(metric) ? num(row.error.at(metric)) : "") << " | "
         << (row.frontier ? "yes" : "") << " | "
         << (row.abPairs ? num(row.abTimeRatio) + "x, q3 " + num(row.abTimeRatioUpperQuartile) + "x (" +
                               std::to_string(row.abPairs) + " pairs)"
                         : "")
         << " |\n";
    }
    for (const DefaultsCheck& c : r.defaults)
      if (c.scene == scene) {
        md << "\nDefaults on the frontier: " << (c.onFrontier ? "yes" : "no");
        if (!c.onFrontier) {
          md << " (dominated by";
          for (const std::string& v : c.dominatedBy) md << " " << v;
          md << ")";
        }
        md << " (time tolerance " << r.tolerances.time * 100 << "%, error tolerance " << r.tolerances.error * 100
           << "%).\n\n";
      }
  }
  md << methodsMarkdown(r);
  if (!r.depthRange.empty()) {
    md << "## Depth range (builtin:depth-range): max |P - P_ref| / depth\n\n| far/near |";
    std::vector<std::string> sources;
    for (const DepthRangeRow& d : r.depthRange)
      if (std::find(sources.begin(), sources.end(), d.source) == sources.end()) sources.push_back(d.source);
    for (const std::string& s : sources) md << " " << s << " |";
    md << "\n| --- |";
    for (size_t i = 0; i < sources.size(); ++i) md << " --- |";
    md << "\n";
    std::set<double> ratios;
    for (const DepthRangeRow& d : r.depthRange) ratios.insert(d.ratio);
    for (double ratio : ratios) {
      md << "| " << num(ratio) << " |";
      for (const std::string& s : sources)
        for (const DepthRangeRow& d : r.depthRange)
          if (d.ratio == ratio && d.source == s) md << " " << num(d.relMax) << " |";
      md << "\n";
    }
    md << "\n";
  }
  md << "## Targets\n\n| target | scene | measured | bound | met |\n| --- | --- | --- | --- | --- |\n";
  for (const auto& t : targetsJson(r))
    md << "| " << t.value("target", "") << " | " << t.value("scene", "") << " | " << num(t.value("measured", 0.0)) << " | "
       << (t.contains("bound") ? num(t["bound"].get<double>()) : "-") << " | "
       << (t.contains("met") ? (t["met"].get<bool>() ? "yes" : "NO") : "-") << " |\n";
  return md.str();
}

}  // namespace gb
