// Bench rows -> frontier, defaults check, bench.json, bench.csv, bench.md (plots: bench_plot.cpp).
#include "app/bench/bench_report.h"

#include "app/bench/bench_attach.h"
#include "app/bench/bench_temporal.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "app/bench/bench_format.h"
#include "renderer/core/statistics.h"
#include "views/analysis/error.h"
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
    if (d && d->errorDetail.contains("position")) {
      // What storage and reconstruction add to the eye depth, beyond where the GPU's float
      // arithmetic places the surface (placementAllowance; the raw max in error_detail).
      double b = d->errorDetail["position"]["eye_depth"].value("beyond_placement", nlohmann::json::object()).value("max", -1.0);
      double raw = d->errorDetail["position"]["eye_depth"]["relative"].value("max", -1.0);
      t.push_back({{"target", "position from eye depth: max |dP|/depth beyond the float placement of triangles <= 1e-6 "
                              "(raw max " + num(raw) + ")"},
                   {"scene", scene}, {"measured", b}, {"bound", 1e-6}, {"met", b >= 0.0 && b <= 1e-6}});
    }
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
    // One rounding of the sum in the format, plus the specular lobe's 32x of n.h's float rounding
    // (lightingBoundPerContribution, views/analysis/error.h).
    if (const BenchRow* h = accum(AccumFormat::Rgba16f)) {
      double l = h->error.at("lighting_per_contribution_max"), b = lightingBoundPerContribution(AccumFormat::Rgba16f);
      t.push_back({{"target", "HDR (lighting passes, silhouettes excluded) per light contribution <= 2^-10 + "
                              "32 x 6 x 2^-24 with fp16"},
                   {"scene", scene}, {"measured", l}, {"bound", b}, {"met", l <= b}});
    }
    if (const BenchRow* f = accum(AccumFormat::Rgba32f)) {
      double l = f->error.at("lighting_per_contribution_max"), b = lightingBoundPerContribution(AccumFormat::Rgba32f);
      t.push_back({{"target", "HDR (lighting passes, silhouettes excluded) per light contribution <= 2^-23 + "
                              "32 x 6 x 2^-24 with fp32"},
                   {"scene", scene}, {"measured", l}, {"bound", b}, {"met", l <= b}});
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
    else {
      pj["ms"] = timingJson(p.ms);
      pj["before_ms"] = timingJson(p.beforeMs);
    }
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
      if (row.ab.pairs())
        o["ab_vs_defaults"] = {{"time_ratio", row.ab.median},
                               {"time_ratio_lower_quartile", row.ab.lowerQuartile},
                               {"time_ratio_upper_quartile", row.ab.upperQuartile},
                               {"time_ratio_ci", {row.ab.ciLow, row.ab.ciHigh}},
                               {"ci_confidence", row.ab.confidence},
                               {"ratios", row.ab.ratios},
                               {"pairs", row.ab.pairs()},
                               {"verdict", abVerdict(row.ab, r.tolerances.time)}};
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
  if (!r.attach.is_null()) j["attach"] = r.attach;
  if (!r.attachApplication.is_null()) j["attach_application"] = r.attachApplication;
  if (!r.temporal.is_null()) j["motion"] = r.temporal;
  nlohmann::json dt = nlohmann::json::array();
  for (const DepthTestRow& d : r.depthTest)
    dt.push_back({{"source", d.source}, {"gap", d.gap}, {"znear", d.znear}, {"zfar", d.zfar}, {"depth", d.depth},
                  {"fighting", d.fighting}});
  j["depth_test"] = dt;
  j["methods"] = methodsJson(r);
  nlohmann::json skips = nlohmann::json::array();
  for (const SkipRow& s : r.skips)
    skips.push_back({{"pass", s.pass}, {"skipped_when", s.skippedWhen}, {"measured_as", s.measuredAs},
                     {"saved_frame_ms", s.savedMs}, {"pass_ms", s.passMs}, {"pairs", s.pairs}});
  j["skips"] = skips;
  nlohmann::json defaults = nlohmann::json::array();
  for (const DefaultsCheck& c : r.defaults)
    defaults.push_back(
        {{"scene", c.scene}, {"on_frontier", c.onFrontier}, {"dominated_by", c.dominatedBy}, {"undecided", c.undecided}});
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

// Per gap and depth format: how many cards z-fight (the twin behind shows on more than 1% of the
// card), and the nearest card that does.
static std::string depthTestMarkdown(const BenchReport& r) {
  if (r.depthTest.empty()) return "";
  std::ostringstream md;
  md << "## Depth test resolution (builtin:depth-range, far/near " << num(r.depthTest[0].zfar / r.depthTest[0].znear)
     << ", a twin card behind each at depth x (1 + gap))\n\n"
     << "Cards z-fighting (the twin shows on more than 1% of the card's pixels) / cards; the nearest such card's "
        "depth in units of the near plane.\n\n| gap | source | cards z-fighting | nearest z-fighting depth / near |\n"
        "| --- | --- | --- | --- |\n";
  std::vector<std::pair<double, std::string>> keys;
  for (const DepthTestRow& d : r.depthTest)
    if (std::find(keys.begin(), keys.end(), std::pair{d.gap, d.source}) == keys.end()) keys.push_back({d.gap, d.source});
  for (const auto& [gap, source] : keys) {
    int fighting = 0, cards = 0;
    double nearest = 0.0;
    for (const DepthTestRow& d : r.depthTest) {
      if (d.gap != gap || d.source != source) continue;
      ++cards;
      if (d.fighting > 0.01) {
        ++fighting;
        if (nearest == 0.0 || d.depth / d.znear < nearest) nearest = d.depth / d.znear;
      }
    }
    md << "| " << num(gap) << " | " << source << " | " << fighting << " / " << cards << " | "
       << (fighting ? num(nearest) : std::string("-")) << " |\n";
  }
  md << "\n";
  return md.str();
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
    md << "| group | variant | frame ms (median [min-max]) | frames | error figure | value | frontier | A/B vs defaults: median [CI] |\n";
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
         << (row.ab.pairs() ? num(row.ab.median) + "x [" + num(row.ab.ciLow) + "-" + num(row.ab.ciHigh) + "] " +
                                  abVerdict(row.ab, r.tolerances.time) + " (" + std::to_string(row.ab.pairs()) + " pairs)"
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
        if (!c.undecided.empty()) {
          md << "; undecided (lower error, time not shown within " << r.tolerances.time * 100 << "%):";
          for (const std::string& v : c.undecided) md << " " << v;
        }
        md << ". Time from the interleaved A/B only: the median ratio variant/defaults with its "
              "distribution-free confidence interval (order statistics; about 96% for 12 pairs); "
              "faster = the interval below 1, not slower = its top at most "
           << 1.0 + r.tolerances.time << "; error tolerance " << r.tolerances.error * 100 << "% plus floors.\n\n";
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
  md << depthTestMarkdown(r);
  md << attachMarkdown(r.attach) << "\n";
  md << attachApplicationMarkdown(r.attachApplication);
  md << temporalMarkdown(r.temporal) << "\n";
  md << "## Targets\n\n| target | scene | measured | bound | met |\n| --- | --- | --- | --- | --- |\n";
  for (const auto& t : targetsJson(r))
    md << "| " << t.value("target", "") << " | " << t.value("scene", "") << " | " << num(t.value("measured", 0.0)) << " | "
       << (t.contains("bound") ? num(t["bound"].get<double>()) : "-") << " | "
       << (t.contains("met") ? (t["met"].get<bool>() ? "yes" : "NO") : "-") << " |\n";
  return md.str();
}

}  // namespace gb
