// The stress suite's frame: bounds stated and checked, NaN/Inf scans of every target, the case
// list, and the table (text and JSON).
#include "app/stress/stress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderer/gpu/render_targets.h"

namespace gb::stress {

static std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void Context::state(const std::string& text) {
  stated.push_back(text);
  std::fprintf(stderr, "  bound: %s\n", text.c_str());
}

Row& Context::check(const std::string& metric, double measured, double limit, const std::string& note) {
  Row row;
  row.caseName = caseName;
  row.metric = metric;
  row.bound = "<= " + fmt(limit);
  row.limit = limit;
  row.measured = measured;
  row.pass = measured <= limit;  // NaN compares false: never passes
  row.note = note;
  rows.push_back(row);
  std::fprintf(stderr, "  %-4s %-52s %-12s (bound %s)\n", row.pass ? "ok" : "FAIL", metric.c_str(), fmt(measured).c_str(),
               row.bound.c_str());
  return rows.back();
}

Row& Context::info(const std::string& metric, double measured, const std::string& note) {
  Row row;
  row.caseName = caseName;
  row.metric = metric;
  row.bound = "(reported)";
  row.measured = measured;
  row.pass = true;
  row.informational = true;
  row.note = note;
  rows.push_back(row);
  std::fprintf(stderr, "  info %-52s %-12s %s\n", metric.c_str(), fmt(measured).c_str(), note.c_str());
  return rows.back();
}

void Context::progress(const std::string& text) const { std::fprintf(stderr, "  .. %s\n", text.c_str()); }

NonFinite scanNonFinite(const CpuImage& img) {
  NonFinite n;
  if (img.type != PixelType::F16 && img.type != PixelType::F32) return n;
  const uint32_t channels = img.channelCount();
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = 0; x < img.width; ++x)
      for (uint32_t c = 0; c < channels; ++c) {
        double v = img.value(x, y, c);
        if (std::isnan(v)) n.nan++;
        else if (std::isinf(v)) n.inf++;
      }
  return n;
}

static Scan scanFrame(FrameSnapshot frame, const std::vector<Target>& targets, bool splitHdrInf) {
  Scan s;
  for (Target t : targets) {
    NonFinite n = scanNonFinite(frame.target(t).image);
    uint64_t counted = n.nan + n.inf;
    if (splitHdrInf && t == Target::Hdr) {
      s.hdrInf += n.inf;
      counted = n.nan;
    }
    if (counted) s.where += std::string(s.where.empty() ? "" : ", ") + targetName(t) + " " + std::to_string(counted);
    s.nonFinite += counted;
  }
  s.frame = std::move(frame);
  return s;
}

Scan scanAfterFrame(HeadlessSession& session, const RenderOptions& o, bool splitHdrInf) {
  std::vector<Target> targets = session.readableTargets(o);
  return scanFrame(session.renderSnapshot(o, targets), targets, splitHdrInf);
}

void addScan(Context& c, const Scan& s, const std::string& label) {
  if (s.nonFinite) std::fprintf(stderr, "  !! %s: NaN/Inf texels: %s\n", label.c_str(), s.where.c_str());
  // One running total per case; the case's final row is added by the runner.
  Row* total = nullptr;
  for (Row& row : c.rows)
    if (row.caseName == c.caseName && row.metric == "NaN/Inf texels, all targets") total = &row;
  if (!total) {
    Row row;
    row.caseName = c.caseName;
    row.metric = "NaN/Inf texels, all targets";
    row.bound = "== 0";
    row.limit = 0.0;
    row.pass = true;
    c.rows.push_back(row);
    total = &c.rows.back();
  }
  total->measured += double(s.nonFinite);
  total->pass = total->measured == 0.0;
  if (s.nonFinite) total->note += (total->note.empty() ? "" : "; ") + label + ": " + s.where;
}

FrameError measure(Context& c, const RenderOptions& options, ReferenceCache& cache, const std::string& label,
                   const Camera* referenceCamera, FrameSnapshot* frame) {
  RenderOptions o = options;
  o.coverage = true;  // the coverage targets are scanned as well
  MeasureExtras extras;
  extras.referenceCamera = referenceCamera;
  RenderOptions measured = o;
  measured.primitiveId = true;
  measured.fairies = false;
  extras.readback = c.session->readableTargets(measured);
  auto render = [&](const RenderOptions& ro, const std::vector<Target>& t) { return c.session->renderSnapshot(ro, t); };
  MeasuredFrame m = measureFrame(render, o, cache, kShadowBandTexels, extras);
  Scan s = scanFrame(std::move(m.frame), extras.readback, false);
  addScan(c, s, label);
  if (frame) *frame = std::move(s.frame);
  return m.error;
}

// ---- the case list and the table --------------------------------------------------------------

const std::vector<Case>& cases() {
  static const std::vector<Case> list = {
      {"depth-range", "near/far 1e-3/1e3, 1e-2/1e5, 1/1e7: reconstructed positions per depth option", depthRangeCase},
      {"far-from-origin", "scene and camera moved by 1e3, 1e5, 1e7: camera-relative positions stay exact",
       farFromOriginCase},
      {"lights-at-camera", "lights containing the camera, at the camera, across the near and far planes: none lost",
       lightsAtCameraCase},
      {"tiny-huge-lights", "radius 1e-4 and 1e4; zero radius and zero intensity skipped", tinyHugeLightsCase},
      {"many-lights", "1 .. 16384 lights on one pixel per accumulation format; fp16 saturation reported",
       manyLightsCase},
      {"grazing-sun", "sun at 90, 10, 1, 0.1 degrees: shadow acne, default bias and the best of a search",
       grazingSunCase},
      {"degenerate-geometry", "zero-area and sliver triangles, duplicate vertices, zero-length normals",
       degenerateGeometryCase},
      {"sizes", "1x1, 3x2 and 8192x8192 (or the device maximum); peak memory", sizesCase},
      {"extreme-fov", "1 and 179 degree vertical FOV, aspect 100:1", extremeFovCase},
  };
  return list;
}

nlohmann::json tableJson(const std::vector<Row>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const Row& r : rows) {
    nlohmann::json j = {{"case", r.caseName}, {"metric", r.metric}, {"bound", r.bound},
                        {"result", r.informational ? "INFO" : (r.pass ? "PASS" : "FAIL")}};
    j["measured"] = std::isfinite(r.measured) ? nlohmann::json(r.measured) : nlohmann::json(fmt(r.measured));
    if (!r.informational) j["limit"] = r.limit;
    if (!r.note.empty()) j["note"] = r.note;
    out.push_back(j);
  }
  return out;
}

void printTable(const std::vector<Row>& rows) {
  size_t cw = 4, mw = 6;
  for (const Row& r : rows) {
    cw = std::max(cw, r.caseName.size());
    mw = std::max(mw, r.metric.size());
  }
  std::printf("%-*s  %-*s  %-12s  %-12s  %s\n", int(cw), "case", int(mw), "metric", "bound", "measured", "result");
  for (const Row& r : rows)
    std::printf("%-*s  %-*s  %-12s  %-12s  %s%s%s\n", int(cw), r.caseName.c_str(), int(mw), r.metric.c_str(),
                r.bound.c_str(), fmt(r.measured).c_str(), r.informational ? "INFO" : (r.pass ? "PASS" : "FAIL"),
                r.note.empty() ? "" : "  ", r.note.c_str());
}

}  // namespace gb::stress
