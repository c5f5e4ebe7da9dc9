// gblens stress: the numerical stability torture suite. Each case builds its scenes in code,
// states its bounds before it runs, renders on the GPU, measures against the double-precision
// reference (or an exact value) and scans every target it read back for NaN/Inf.
#pragma once
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

#include "renderer/frame/session.h"
#include "renderer/scene/scene.h"
#include "views/analysis/accuracy.h"

namespace gb::stress {

// One line of the table: a measured value against its stated bound.
struct Row {
  std::string caseName, metric;
  std::string bound;      // as stated, e.g. "<= 1e-05"
  double limit = 0.0;     // measured must be <= limit (or == when exact)
  double measured = 0.0;
  bool pass = false;
  bool informational = false;  // reported, no bound (e.g. peak memory, the best bias found)
  std::string note;
};

struct Context {
  HeadlessSession* session = nullptr;  // the suite's one context; each scene in turn (SessionScene)
  bool quick = false;  // reduced sizes (CTest)
  std::vector<Row> rows;
  std::string caseName;
  std::vector<std::string> stated;  // bounds stated by the running case (printed before it runs)

  // States a bound; prints it at once (before the measurement that follows).
  void state(const std::string& text);
  // Records a measurement: pass when measured <= limit (NaN never passes).
  Row& check(const std::string& metric, double measured, double limit, const std::string& note = {});
  Row& info(const std::string& metric, double measured, const std::string& note = {});
  void progress(const std::string& text) const;
};

// NaN and Inf texels in one read-back image (float channels; integer targets cannot hold them).
struct NonFinite {
  uint64_t nan = 0, inf = 0;
};
NonFinite scanNonFinite(const CpuImage& image);

// Renders `o` once with every readable target read back; returns NaN+Inf over all of them
// (hdr Inf counted apart in `hdrInf` when the caller expects fp16 saturation).
struct Scan {
  uint64_t nonFinite = 0;  // NaN + Inf in every target (hdr Inf included unless split out)
  uint64_t hdrInf = 0;     // Inf in hdr (split out when splitHdrInf)
  std::string where;       // targets that held any
  FrameSnapshot frame;     // the frame scanned
};
Scan scanAfterFrame(HeadlessSession& s, const RenderOptions& o, bool splitHdrInf = false);
// Adds a frame's scan to the case's running NaN/Inf total (the case's last row reports it).
void addScan(Context& c, const Scan& s, const std::string& label);

// A case: name, one-line description, and the function that runs it.
struct Case {
  std::string name, description;
  std::function<void(Context&)> run;
};
const std::vector<Case>& cases();

// The cases (stress_*.cpp).
void depthRangeCase(Context& c);
void farFromOriginCase(Context& c);
void lightsAtCameraCase(Context& c);
void tinyHugeLightsCase(Context& c);
void manyLightsCase(Context& c);
void grazingSunCase(Context& c);
void degenerateGeometryCase(Context& c);
void sizesCase(Context& c);
void extremeFovCase(Context& c);

// Scene helpers for the cases (stress_scenes.cpp).
Scene groundScene(double halfSize, bool sun);  // a floor quad at y = 0 and three boxes
void placeCamera(Scene& s, glm::dvec3 eye, glm::dvec3 target, double yfov = 0.9, double znear = 0.1,
                 double zfar = 100.0);
// The whole scene moved by `offset` (instances, cameras, lights): the camera follows.
void translateScene(Scene& s, const glm::dvec3& offset);
// The session renders one scene while this lives (the scene must outlive it).
struct SessionScene {
  HeadlessSession& session;
  SessionScene(HeadlessSession& s, const Scene& scene) : session(s) { s.useScene(scene); }
  ~SessionScene() { session.releaseScene(); }
  SessionScene(const SessionScene&) = delete;
  SessionScene& operator=(const SessionScene&) = delete;
};
// Measures `o` against the reference (coverage on), scans every target of that frame for
// NaN/Inf (added to the case's total) and returns the error. `referenceCamera`: see MeasureExtras;
// `frame`, when given, receives the frame measured.
FrameError measure(Context& c, const RenderOptions& o, ReferenceCache& cache, const std::string& label,
                   const Camera* referenceCamera = nullptr, FrameSnapshot* frame = nullptr);

nlohmann::json tableJson(const std::vector<Row>& rows);
void printTable(const std::vector<Row>& rows);

}  // namespace gb::stress
