// Compare's targets and the run (compare.h, compare()): the targets of both layouts matched by name,
// what happens to each (compared, skipped, a mismatch), the names the settings give checked before any
// work, the mask made first, every group compared (compare.cpp), FLIP, the exit code; and the
// manifests' fields that differ.
#include <algorithm>

#include "views/analysis/compare.h"
#include "views/analysis/compare_internal.h"

namespace gb {

namespace {

// Manifest fields whose difference a reader should know about: every option, the scene, the
// lights, the device and the build, and for imports where they were recorded and replayed. A field
// only one side holds (the other's source does not say it: an import's lights, a streamed frame's
// options) goes to `onlyA` / `onlyB`, apart from the fields both hold that differ.
void manifestDifferences(const nlohmann::json& a, const nlohmann::json& b, nlohmann::json& out, nlohmann::json& onlyA,
                         nlohmann::json& onlyB) {
  nlohmann::json fa = nlohmann::json::object(), fb = nlohmann::json::object();
  for (const char* key : {"options", "scene", "device", "driver", "gblens", "lights", "sun", "source"}) {
    fa[key] = a.is_object() ? a.value(key, nlohmann::json()) : nlohmann::json();
    fb[key] = b.is_object() ? b.value(key, nlohmann::json()) : nlohmann::json();
  }
  for (nlohmann::json* j : {&fa, &fb})
    if ((*j)["lights"].is_object()) (*j)["lights"].erase("file");
  nlohmann::json flatA = fa.flatten(), flatB = fb.flatten();
  // A whole section one side lacks flattens to null: its fields are that side's alone.
  auto holds = [](const nlohmann::json& flat, const std::string& k) { return flat.contains(k) && !flat[k].is_null(); };
  for (auto& [k, v] : flatA.items()) {
    if (v.is_null()) continue;
    if (!holds(flatB, k)) onlyA.push_back({{"name", k.substr(1)}, {"value", v}});
    else if (flatB[k] != v) out.push_back({{"name", k.substr(1)}, {"a", v}, {"b", flatB[k]}});
  }
  for (auto& [k, v] : flatB.items())
    if (!v.is_null() && !holds(flatA, k)) onlyB.push_back({{"name", k.substr(1)}, {"value", v}});
  for (nlohmann::json* list : {&out, &onlyA, &onlyB})
    for (auto& d : *list) std::replace(d["name"].get_ref<std::string&>().begin(), d["name"].get_ref<std::string&>().end(), '/', '.');
}

// Target names of both layouts: A's in order, then B's that A lacks.
std::vector<std::string> targetNames(const Layout& a, const Layout& b) {
  std::vector<std::string> names;
  for (const LayoutTarget& t : a.targets) names.push_back(t.name);
  for (const LayoutTarget& t : b.targets)
    if (a.findTarget(t.name) < 0) names.push_back(t.name);
  return names;
}

std::string whyAbsent(const FrameSnapshot& f, int index) {
  return index < 0 ? "not in its layout" : absentText(f.absences[size_t(index)]);
}

// Why two present targets of one name cannot be compared ("" when they can).
std::string targetMismatch(const FrameSnapshot& fa, int ia, const FrameSnapshot& fb, int ib) {
  const TargetImage &a = fa.images[size_t(ia)], &b = fb.images[size_t(ib)];
  if (a.image.width != b.image.width || a.image.height != b.image.height || a.x0 != b.x0 || a.y0 != b.y0)
    return "size " + std::to_string(a.image.width) + "x" + std::to_string(a.image.height) + " vs " +
           std::to_string(b.image.width) + "x" + std::to_string(b.image.height);
  for (const Quantity* q : fa.layout.quantitiesOf(uint32_t(ia))) {
    const Quantity* other = fb.layout.findByName(q->name);
    if (!other || int(other->target) != ib) return "quantity " + q->name + " only in A";
    if (metricOf(other->kind) != metricOf(q->kind))
      return "quantity " + q->name + " is " + name(q->kind) + " in A, " + name(other->kind) + " in B";
  }
  for (const Quantity* q : fb.layout.quantitiesOf(uint32_t(ib))) {
    const Quantity* other = fa.layout.findByName(q->name);
    if (!other || int(other->target) != ia) return "quantity " + q->name + " only in B";
  }
  return "";
}

// What happens to each target of the two layouts: compared, skipped (why) or a mismatch (why).
struct TargetPlan {
  std::string name;
  int ia = -1, ib = -1;
  enum class Do { Compare, Skip, Mismatch } what = Do::Compare;
  std::string why;
};

std::vector<TargetPlan> planTargets(const FrameSnapshot& fa, const FrameSnapshot& fb, const std::vector<std::string>& exclude) {
  std::vector<TargetPlan> plans;
  for (const std::string& tn : targetNames(fa.layout, fb.layout)) {
    TargetPlan p{tn, fa.indexOf(tn), fb.indexOf(tn)};
    const bool pa = p.ia >= 0 && fa.images[size_t(p.ia)].present(), pb = p.ib >= 0 && fb.images[size_t(p.ib)].present();
    if (std::find(exclude.begin(), exclude.end(), tn) != exclude.end())
      p.what = TargetPlan::Do::Skip, p.why = "excluded (--exclude)";
    else if (!pa && !pb)
      p.what = TargetPlan::Do::Skip, p.why = "absent in both (A: " + whyAbsent(fa, p.ia) + "; B: " + whyAbsent(fb, p.ib) + ")";
    else if (pa != pb) {
      // A frame made with the feature off (coverage, primitive ids, ...) has nothing to compare: the
      // options differ (listed in the report), the targets both hold are still compared.
      // Nor does one whose source had no such image (a streamed frame that did not draw it): reported
      // apart, the verdict decided on what both hold.
      const std::string why = pa ? whyAbsent(fb, p.ib) : whyAbsent(fa, p.ia);
      const FrameSnapshot& lacking = pa ? fb : fa;
      const int index = pa ? p.ib : p.ia;  // -1: not in its layout at all (a mismatch)
      const bool notInSource = index >= 0 && lacking.absences[size_t(index)] == Absent::NotInSource;
      p.what = why.rfind("not computed", 0) == 0 || notInSource ? TargetPlan::Do::Skip : TargetPlan::Do::Mismatch;
      p.why = std::string("only in ") + (pa ? "A" : "B") + " (" + why + ")";
    }
    else if (std::string why = targetMismatch(fa, p.ia, fb, p.ib); !why.empty())
      p.what = TargetPlan::Do::Mismatch, p.why = why;
    plans.push_back(p);
  }
  return plans;
}

// Threshold keys and --exclude names must name a target of either layout (or of gblens's own, so
// one threshold file serves several configurations); a key for a compared target must name it or
// one of its quantities. Checked before any work.
bool checkNames(const CompareSettings& settings, const std::vector<TargetPlan>& plans, const FrameSnapshot& fa,
                std::string& error) {
  std::vector<std::string> knownTargets, knownKeys, groups;
  for (const TargetPlan& p : plans) {
    knownTargets.push_back(p.name);
    if (p.what != TargetPlan::Do::Compare) continue;
    knownKeys.push_back(p.name);
    for (const ChannelGroup& g : channelGroups(fa.layout, uint32_t(p.ia))) knownKeys.push_back(g.key), groups.push_back(g.key);
  }
  auto known = [](const std::vector<std::string>& list, const std::string& s) {
    return std::find(list.begin(), list.end(), s) != list.end();
  };
  for (const std::string& tn : settings.exclude)
    if (!known(knownTargets, tn)) {
      error = "--exclude " + tn + ": no target \"" + tn + "\" in either capture (targets:";
      for (const std::string& t : knownTargets) error += " " + t;
      error += ")";
      return false;
    }
  for (auto& [key, params] : settings.thresholds.byKey) {
    if (key.empty()) continue;
    const std::string target = key.substr(0, key.find('.'));
    Target native;
    if (!known(knownTargets, target) && !parseTarget(target, native)) {
      error = "threshold for \"" + key + "\": no target \"" + target + "\" in either capture";
      return false;
    }
    if (known(knownKeys, target) && !known(knownKeys, key)) {
      error = "threshold for \"" + key + "\": no such group (groups:";
      for (const std::string& g : groups) error += " " + g;
      error += ")";
      return false;
    }
  }
  return true;
}

}  // namespace

bool compare(const Capture& ca, const Capture& cb, const CompareSettings& settings, CompareReport& report,
             std::string& error) {
  const auto started = std::chrono::steady_clock::now();
  report = CompareReport{};
  report.a = ca.dir;
  report.b = cb.dir;
  manifestDifferences(ca.manifest, cb.manifest, report.differences, report.onlyInA, report.onlyInB);
  const FrameSnapshot &fa = ca.frame, &fb = cb.frame;
  const std::vector<TargetPlan> plans = planTargets(fa, fb, settings.exclude);
  if (!checkNames(settings, plans, fa, error)) return false;
  if (!settings.mask.empty() && !buildCompareMask(ca, cb, settings.mask, report.mask, error)) return false;

  // Progress by pixels (FLIP's filters cost about eight group comparisons a pixel).
  constexpr double kFlipWeight = 8.0;
  double total = 0.0, done = 0.0;
  for (const TargetPlan& p : plans)
    if (p.what == TargetPlan::Do::Compare)
      total += double(fa.images[size_t(p.ia)].image.width) * fa.images[size_t(p.ia)].image.height *
               double(fa.layout.quantitiesOf(uint32_t(p.ia)).size());
  if (settings.flipOn) total += kFlipWeight * 2.0 * fa.camera.width * fa.camera.height;
  auto progress = [&](const std::string& what, double work) {
    if (settings.progress) settings.progress(total > 0.0 ? done / total : 1.0, what);
    done += work;
  };

  Verdict worst = Verdict::Pass;
  for (const TargetPlan& p : plans) {
    if (p.what == TargetPlan::Do::Skip) report.skipped.push_back({p.name, p.why});
    if (p.what == TargetPlan::Do::Mismatch) report.mismatches.push_back({p.name, p.why});
    if (p.what != TargetPlan::Do::Compare) continue;
    for (const ChannelGroup& g : channelGroups(fa.layout, uint32_t(p.ia))) {
      GroupResult r;
      r.group = g;
      r.target = p.name;
      r.thresholds = settings.thresholds.resolve(p.name, g.key);
      const CpuImage& image = fa.images[size_t(p.ia)].image;
      progress(g.key, double(image.width) * image.height);
      const auto t0 = std::chrono::steady_clock::now();
      compareGroup({fa, *fa.layout.findByName(g.group)}, {fb, *fb.layout.findByName(g.group)}, &report.mask, r);
      r.seconds = secondsSince(t0);
      worst = std::max(worst, r.verdict);
      report.groups.push_back(std::move(r));
    }
  }
  report.exitCode = report.mismatches.empty() ? int(worst) : kCompareMismatch;
  if (settings.flipOn) {
    progress("FLIP", 0.0);
    compareFlip(ca, cb, settings.flip, report);
  }
  if (settings.progress) settings.progress(1.0, "done");
  report.seconds = secondsSince(started);
  return true;
}

bool compareCaptures(const Capture& a, const Capture& b, const ThresholdSettings& thresholds, CompareReport& report,
                     std::string& error) {
  CompareSettings settings;
  settings.thresholds = thresholds;
  settings.flipOn = false;
  return compare(a, b, settings, report, error);
}

}  // namespace gb
