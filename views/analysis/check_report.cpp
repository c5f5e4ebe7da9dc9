// `gblens check`'s report for people and as JSON, and its policy: which findings are faults, which
// warnings, which are not reported (check.h).
#include <cmath>
#include <cstdio>
#include <set>

#include "views/analysis/check.h"

namespace gb {

namespace {

std::string valueText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}


}  // namespace

std::string positionText(const PositionCheck& p) {
  char line[512];
  // The verdict, not the class's level: "[fault]" only where pixels are beyond their bound.
  const std::string verdict = p.overBound == 0 ? "within the bound"
                              : p.severity == Severity::Ignore ? "ignored by the policy"
                                                               : name(p.severity);
  std::snprintf(line, sizeof(line),
                "positions: %s rebuilt from depth vs the stored %s (%s) at %llu surface pixels: %llu beyond the bound "
                "(largest %.3g scene units, %.3g x the bound at %u,%u; median %.3g x) [%s]\n",
                p.depth.c_str(), p.stored.c_str(), p.storedFormat.c_str(), (unsigned long long)p.pixels,
                (unsigned long long)p.overBound, p.maxDistance, p.maxRatio, p.x, p.y, p.medianRatio, verdict.c_str());
  std::string out = line;
  if (p.cameraSuspect)
    out += "  the camera looks wrong: most pixels rebuild far from the stored positions (check the matrices, their "
           "buffer offsets, matrix_order, convention, up and handedness)\n";
  return out;
}

std::string normalText(const NormalCheck& c) {
  std::string out = "normals: " + c.normal + " (" + c.declared + ") vs the surface " + c.depth + " rebuilds: " + c.stats.text();
  if (!c.better.empty())
    out += "; fits far better with " + c.better + " (" + c.betterStats.text() + "): the layout's decoding looks wrong";
  if (c.facesAway)
    out += "; " + std::to_string(int(std::round(100.0 * (1.0 - c.stats.sameSide)))) +
           " % point away from the camera (negated?)";
  out += std::string(" [") + (!c.wrong() ? "consistent" : c.severity == Severity::Ignore ? "ignored" : name(c.severity)) + "]\n";
  return out;
}

std::string checkText(const CheckReport& r) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof(line), "%-18s %-14s %-9s %8s  %-16s %-16s %-16s %-16s %-16s %s\n", "target", "quantity", "kind",
                "texels", "NaN", "+Inf", "-Inf", "denormal", "out of range", "range");
  out += line;
  for (const CheckRow& row : r.rows) {
    std::string cells[kAnomalyCount];
    for (size_t a = 0; a < kAnomalyCount; ++a) {
      const AnomalyCount& c = row.found[a];
      cells[a] = row.severity[a] == Severity::Ignore ? "-"
                 : c.count ? std::to_string(c.count) + " @" + std::to_string(c.x) + "," + std::to_string(c.y) +
                                 (row.severity[a] == Severity::Warn ? " w" : "")
                           : "0";
    }
    std::string range = row.range + (row.surfacesOnly ? (row.range.empty() ? "" : ", ") + std::string("surfaces only") : "");
    std::snprintf(line, sizeof(line), "%-18s %-14s %-9s %8llu  %-16s %-16s %-16s %-16s %-16s %s\n", row.target.c_str(),
                  row.quantity.c_str(), row.kind.c_str(), (unsigned long long)row.texels, cells[0].c_str(),
                  cells[1].c_str(), cells[2].c_str(), cells[3].c_str(), cells[4].c_str(), range.c_str());
    out += line;
  }
  if (!r.surfaces.empty()) out += r.surfaces + "\n";
  for (const PositionCheck& p : r.positions) out += positionText(p);
  for (const NormalCheck& c : r.normals) out += normalText(c);
  for (const auto& [target, why] : r.absent) out += "absent: " + target + " (" + why + ")\n";
  const uint64_t faults = r.count(Severity::Fault), warnings = r.count(Severity::Warn);
  if (faults == 0)
    out += "clean: no fault in " + std::to_string(r.rows.size()) + " quantities" +
           (warnings ? " (" + std::to_string(warnings) + " warnings, marked w: allowed by the policy)" : "") + "\n";
  else
    out += "found " + std::to_string(faults) + " faults" + (warnings ? ", " + std::to_string(warnings) + " warnings" : "") + "\n";
  bool any = false;
  for (const CheckRow& row : r.rows)
    for (size_t a = 0; a < kAnomalyCount; ++a) any = any || (row.found[a].count && row.severity[a] != Severity::Ignore);
  if (!any) return out;
  out += "first of each (level class  target quantity: x,y what = value):\n";
  for (const CheckRow& row : r.rows)
    for (size_t a = 0; a < kAnomalyCount; ++a)
      if (const AnomalyCount& c = row.found[a]; c.count && row.severity[a] != Severity::Ignore)
        out += "  " + std::string(name(row.severity[a])) + " " + name(Anomaly(a)) + "  " + row.target + " " + row.quantity + ": " +
               std::to_string(c.x) + "," + std::to_string(c.y) + " " + c.channel + " = " + valueText(c.value) + "\n";
  return out;
}

nlohmann::json checkJson(const CheckReport& r) {
  nlohmann::json rows = nlohmann::json::array(), counts = nlohmann::json::object(), absent = nlohmann::json::array();
  for (size_t a = 0; a < kAnomalyCount; ++a) counts[name(Anomaly(a))] = r.count(Anomaly(a));
  for (const CheckRow& row : r.rows) {
    nlohmann::json j = {{"target", row.target}, {"quantity", row.quantity},     {"kind", row.kind},
                        {"range", row.range},   {"surfaces_only", row.surfacesOnly}, {"texels", row.texels}};
    for (size_t a = 0; a < kAnomalyCount; ++a) {
      const AnomalyCount& c = row.found[a];
      nlohmann::json e = {{"count", c.count}, {"level", name(row.severity[a])}};
      if (c.count) {
        nlohmann::json value = std::isfinite(c.value) ? nlohmann::json(c.value) : nlohmann::json(valueText(c.value));
        e["first"] = {{"x", c.x}, {"y", c.y}, {"channel", c.channel}, {"value", value}};
      }
      j[name(Anomaly(a))] = e;
    }
    rows.push_back(j);
  }
  nlohmann::json positions = nlohmann::json::array();
  for (const PositionCheck& p : r.positions)
    positions.push_back({{"depth", p.depth}, {"stored", p.stored}, {"stored_format", p.storedFormat}, {"pixels", p.pixels},
                         {"over_bound", p.overBound}, {"max_distance", p.maxDistance}, {"max_ratio", p.maxRatio},
                         {"median_ratio", p.medianRatio}, {"worst", {p.x, p.y}}, {"camera_suspect", p.cameraSuspect},
                         {"level", name(p.severity)}});
  nlohmann::json normals = nlohmann::json::array();
  auto angles = [](const AngleStats& a) {
    return nlohmann::json{{"pixels", a.count}, {"median_deg", a.median}, {"p90_deg", a.p90}, {"p99_deg", a.p99}};
  };
  for (const NormalCheck& c : r.normals) {
    nlohmann::json j = {{"normal", c.normal}, {"depth", c.depth}, {"declared", c.declared}, {"angles", angles(c.stats)},
                        {"faces_away", c.facesAway}, {"wrong", c.wrong()}, {"level", name(c.severity)}};
    if (!c.better.empty()) j["better"] = {{"hypothesis", c.better}, {"angles", angles(c.betterStats)}};
    normals.push_back(j);
  }
  for (const auto& [target, why] : r.absent) absent.push_back({{"target", target}, {"reason", why}});
  // version 2: "normals" (the normal class) and "surfaces" (which pixels were counted) added.
  return {{"format", "gblens-check"}, {"version", 2}, {"clean", r.clean()}, {"faults", r.count(Severity::Fault)},
          {"warnings", r.count(Severity::Warn)}, {"counts", counts}, {"rows", rows}, {"positions", positions},
          {"normals", normals}, {"surfaces", r.surfaces}, {"absent", absent}};
}

// ---- the policy ----------------------------------------------------------------------------------

const char* name(Severity s) {
  static const char* n[] = {"fault", "warn", "ignore"};
  return n[size_t(s)];
}

const char* anomalyClass(Anomaly a) {
  static const char* n[] = {"nan", "inf", "inf", "denormal", "out_of_range"};
  return n[size_t(a)];
}

Severity CheckPolicy::at(const std::string& quantity, const std::string& cls) const {
  if (auto q = quantities.find(nameKey(quantity)); q != quantities.end())
    if (auto c = q->second.find(cls); c != q->second.end()) return c->second;
  auto c = classes.find(cls);
  return c == classes.end() ? Severity::Fault : c->second;
}

CheckPolicy defaultCheckPolicy() {
  CheckPolicy p;
  p.classes = {{"nan", Severity::Fault}, {"inf", Severity::Fault}, {"denormal", Severity::Warn},
               {"out_of_range", Severity::Fault}, {"position", Severity::Fault}, {"normal", Severity::Fault},
               {"motion", Severity::Fault}, {"history", Severity::Fault}};
  return p;
}

static bool parseLevel(const std::string& text, Severity& out) {
  if (text == "fault") out = Severity::Fault;
  else if (text == "warn") out = Severity::Warn;
  else if (text == "ignore") out = Severity::Ignore;
  else return false;
  return true;
}

bool checkPolicy(const Layout& l, const std::vector<std::string>& rules, CheckPolicy& out, std::string& error) {
  out = defaultCheckPolicy();
  auto apply = [&](const std::string& quantity, const std::string& cls, Severity s) {
    if (quantity.empty()) out.classes[cls] = s;
    else out.quantities[nameKey(quantity)][cls] = s;
  };
  Severity s;
  for (auto& [cls, level] : l.check)
    if (parseLevel(level, s)) apply("", cls, s);
  for (const Quantity& q : l.quantities)
    for (auto& [cls, level] : q.check)
      if (parseLevel(level, s)) apply(q.name, cls, s);
  static const std::set<std::string> classes = {"nan", "inf", "denormal", "out_of_range", "position", "normal", "motion", "history"};
  for (const std::string& rule : rules) {
    const size_t eq = rule.find('=');
    std::string left = rule.substr(0, eq), quantity, cls = left;
    if (const size_t dot = left.rfind('.'); dot != std::string::npos) quantity = left.substr(0, dot), cls = left.substr(dot + 1);
    if (eq == std::string::npos || !classes.count(cls) || !parseLevel(rule.substr(eq + 1), s)) {
      error = "--policy " + rule + ": expected [QUANTITY.]CLASS=LEVEL, CLASS one of nan, inf, denormal, out_of_range, "
              "position, normal, motion, history and LEVEL one of fault, warn, ignore (e.g. denormal=fault, Normal.out_of_range=warn)";
      return false;
    }
    if (!quantity.empty() && !l.findByName(quantity)) {
      bool found = false;
      for (const Quantity& q : l.quantities) found = found || nameKey(q.name) == nameKey(quantity);
      if (!found) {
        error = "--policy " + rule + ": the layout has no quantity \"" + quantity + "\"";
        return false;
      }
    }
    apply(quantity, cls, s);
  }
  return true;
}

}  // namespace gb
