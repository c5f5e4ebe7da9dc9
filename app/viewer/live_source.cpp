// The viewer on an attached application's stream (gblens attach, docs/attach.md): the latest frame
// polled from the LiveSession is shown exactly as an opened capture is (capture A: every view of the
// layout decoded and uploaded, hover, probe and region statistics on its snapshot). Paused, nothing is
// polled (the layer drops the frames nobody takes; the application runs on); "Capture" writes the
// frame shown with writeCapture, the format `import` and `attach --capture-frame` write.
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "app/viewer/viewer.h"
#include "views/infer/suggest_live.h"
#include "renderer/core/decode.h"
#include "views/analysis/probe.h"
#include "views/analysis/sample_views.h"
#include "views/analysis/visualize.h"
#include "views/capture/image_io.h"
#include "views/live/live_wire.h"

namespace gb {

namespace {

// Frames the viewer did not show: those the layer dropped (this side busy), those read in place while
// the application's GPU wrote them again, and those a newer one replaced before the viewer drew.
uint64_t droppedFrames(const LiveReceiver::State& st) {
  return st.counts.dropped + st.counts.overwritten + st.replaced;
}

// The application's state as the status bar says it.
std::string stateText(Viewer& v, const LiveReceiver::State& st) {
  const ViewerModel& m = v.model;
  if (!st.running) return "application exited (code " + std::to_string(st.exitStatus) + ")";
  return m.attach.detachRequested ? "detached (the application runs on)"
         : m.playing              ? "running"
                                  : "paused (the application runs on)";
}

// What the status bar says: the frame shown, frames received and dropped, the history kept
// (--history K: frames and their memory, at most K frames' bytes), the application's state.
std::string statusText(Viewer& v, const LiveReceiver::State& st) {
  char text[256];
  std::snprintf(text, sizeof text, "application frame %llu | received %llu, dropped %llu | latency %.0f ms | ",
                (unsigned long long)v.attachInfo.appFrame, (unsigned long long)st.counts.received,
                (unsigned long long)droppedFrames(st), v.attachShownMs);
  std::string line = text;
  if (st.counts.notAsked > 0) line += std::to_string(st.counts.notAsked) + " not asked for (paced) | ";
  if (st.historyLimit > 0) {
    std::snprintf(text, sizeof text, "history %zu/%zu frames, %.1f MB | ", st.historyFrames, st.historyLimit,
                  double(st.historyBytes) / 1e6);
    line += text;
  }
  return line + stateText(v, st);
}

// The dossier of the probed pixel again on a new frame, quietly (only a user's probe is logged).
void refreshDossier(Viewer& v) {
  ViewerModel& m = v.model;
  if (!m.probePixel || !m.dossier) return;
  const FrameSnapshot& f = v.captureA.frame;
  const glm::ivec2 p = glm::clamp(*m.probePixel, glm::ivec2(0), glm::ivec2(int(f.options.width) - 1, int(f.options.height) - 1));
  m.dossier = probePixel(f, uint32_t(p.x), uint32_t(p.y));
  m.dossierJson = dossierJson(*m.dossier);
  m.probeError = m.dossier->error;
}

// The views on screen decoded from the frame shown and uploaded; the others are decoded when they
// come on screen (a stream's frame is shown once: decoding every view of it would halve the frames
// the viewer keeps up with). On the GPU where it can (view_decode.h: the decoded image and its
// ranges), else on the CPU; the probe, hover and regions decode the snapshot on the CPU.
void decodeShown(Viewer& v) {
  ViewerModel& m = v.model;
  const FrameSnapshot& f = v.captureA.frame;
  v.attachShown = visibleViews(m);
  v.decodedA.assign(m.views.size(), CpuImage{});
  v.gpuRanges.assign(m.views.size(), {});
  std::vector<int> cpu, gpu;
  std::vector<bool> onGpu(m.views.size(), false);
  for (int k : v.attachShown) {
    const ViewDef& d = m.views[size_t(k)];
    if (!m.unavailable[size_t(k)].empty() || d.quantity < 0) continue;
    const bool there = v.gpuDecode && gpuDecodeRefusal(v.ctx, f, d).empty();
    (there ? gpu : cpu).push_back(k);
    onGpu[size_t(k)] = there;
  }
  for (int k : cpu) v.decodedA[size_t(k)] = viewImage(f, m.views[size_t(k)]);  // each on every core
  uploadViewImages(v.imagesA, v.ctx, v.decodedA, onGpu);
  std::vector<bool> ranges(m.views.size(), false);  // statistics only where a range comes from the data
  for (int k : gpu) ranges[size_t(k)] = m.settings[size_t(k)].autoRange;
  if (!gpu.empty()) v.gpuRanges = decodeViewsOnGpu(v.decoder, v.ctx, f, m.views, gpu, ranges, v.imagesA);
  v.gpuDecoded = onGpu;
  v.rangeKeys.assign(m.views.size(), "");
}

bool sameViews(const std::vector<ViewDef>& a, const std::vector<ViewDef>& b) {
  bool same = a.size() == b.size();
  for (size_t k = 0; same && k < a.size(); ++k) same = a[k].name == b[k].name && a[k].visual == b[k].visual;
  return same;
}

// Each drafted quantity's verdict for the Suggested layout window's table (views/infer/guess.h).
std::vector<ViewerModel::AttachUi::Verdict> verdictsOf(const nlohmann::json& draft) {
  std::vector<ViewerModel::AttachUi::Verdict> out;
  for (const nlohmann::json& t : draft.value("targets", nlohmann::json::array()))
    for (const nlohmann::json& q : t.value("quantities", nlohmann::json::array())) {
      const nlohmann::json g = q.value("guess", nlohmann::json::object());
      if (!g.is_object()) continue;
      const std::string kind = q.value("quantity", "");
      const bool unknown = g.value("quantity", "") == "unknown" || kind == "scalar" || kind == "vector";
      char confidence[16];
      std::snprintf(confidence, sizeof confidence, "%.2f", g.value("confidence", 0.0));
      out.push_back({t.value("name", ""), q.value("channels", nlohmann::json::array()).dump(), unknown ? "unknown" : kind,
                     confidence, g.value("evidence", "")});
    }
  return out;
}

}  // namespace

void showStreamFrame(Viewer& v, FrameSnapshot&& frame, const LiveFrameInfo& info, bool kept) {
  ViewerModel& m = v.model;
  const auto start = std::chrono::steady_clock::now();
  v.captureA.frame = std::move(frame);
  showSample(v.captureA.frame, m.sampleShown);  // X's choice holds from frame to frame
  m.samplesNote = samplesNote(v.captureA.frame);
  ++v.framesShown;
  v.attachInfo = info;
  const FrameSnapshot& f = v.captureA.frame;
  v.renderer.camera = v.renderer.unjitteredCamera = f.camera;
  m.rendered = f.options;
  if (!sameViews(frameViews(f), m.views) || v.decodedA.empty()) {
    setCaptureViews(v, false);  // the views and the unavailable ones named
    decodeShown(v);
  } else {
    m.frameLayout = f.layout;
    for (size_t k = 0; k < m.views.size(); ++k) {
      const uint32_t t = m.views[k].target;
      const Absent why = f.absences[t];
      m.unavailable[k] = f.images[t].present() ? "" : f.layout.targets[t].name + ": " + absentText(why == Absent::No ? Absent::NotCaptured : why);
    }
    decodeShown(v);
  }
  refreshDossier(v);
  m.regionDirty = m.region.has_value();
  char text[160];
  std::snprintf(text, sizeof text, "application frame %llu (streamed frame %llu), %.0f ms after its end",
                (unsigned long long)info.appFrame, (unsigned long long)info.stream, info.latencyMs);
  m.attach.frame = text;
  for (const std::string& a : info.absent) m.attach.frame += "\nabsent: " + a;
  if (kept) {
    m.attach.frame = "kept " + m.attach.frame.substr(0, m.attach.frame.find(','));  // its latency meant nothing now
    return;
  }
  const LiveReceiver::State st = v.receiver->state();
  const LiveCounts& c = st.counts;
  v.attachPresentPending = true;
  logLine(v.eventLog, {{"event", "attach_frame"},
                       {"stream", info.stream},
                       {"app_frame", info.appFrame},
                       {"latency_ms", double(wire::monotonicNs() - info.endNs) * 1e-6},
                       {"received", c.received},
                       {"dropped", droppedFrames(st)},
                       {"copied", c.layer.value("copied_frames", uint64_t(0))},
                       {"paced", c.layer.value("paced", false)},
                       {"time_s", std::chrono::duration<double>(start - v.attachOpened).count()},
                       {"decode_ms", c.meanDecodeMs},
                       {"show_ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()}});
}

void openAttached(Viewer& v) {
  ViewerModel& m = v.model;
  LiveSession& s = *v.args.attach;
  v.captureA = Capture{};
  v.captureA.dir = v.args.scene;
  v.captureA.frame = *v.args.attachFirst;
  v.receiver = std::make_unique<LiveReceiver>(s);
  const char* decode = std::getenv("GBLENS_VIEW_DECODE");  // "cpu": the views decoded on the CPU (measuring)
  v.gpuDecode = !(decode && std::string(decode) == "cpu");
  if (v.gpuDecode) initViewDecoder(v.decoder, v.ctx);
  v.attachOpened = std::chrono::steady_clock::now();
  v.attachInfo = v.args.attachFirstInfo;
  m.source = FrameSource::Capture;
  m.attach.on = true;
  m.attach.application = s.hello().value("application", "?") + " (" + s.hello().value("device", "?") + "), pid " +
                         std::to_string(s.pid()) + ", layout " + v.captureA.frame.layout.name;
  m.captureInfo = m.attach.application;
  v.scene = emptyScene(v.captureA.frame.camera);
  initRenderer(v.renderer, v.ctx, v.scene);
  FrameSnapshot first = v.captureA.frame;
  showStreamFrame(v, std::move(first), v.args.attachFirstInfo);
  m.captureAvailable = true;
  m.captureHint = "Writes the frame shown (paused: the frozen one) as a gblens capture to ./gblens-attach-<date>-<time>/\n"
                  "(the format gblens import and attach --capture-frame write; key C)";
  m.attach.status = statusText(v, v.receiver->state());
  if (!v.args.attachDraft.is_null()) {  // attach --suggest without a layout: the stream's layout is this draft
    m.attach.passes = v.args.attachPasses;
    m.attach.summary = v.args.attachSummary;
    m.attach.draft = v.args.attachDraft.dump(2);
    m.attach.verdicts = verdictsOf(v.args.attachDraft);
    m.attach.draftStreamed = true;
    logLine(v.eventLog, {{"event", "attach_suggestion"}, {"draft", v.args.attachDraft}, {"streamed", true}});
  }
  v.frameValid = true;
  v.attachPlaying = m.playing;
  logLine(v.eventLog, {{"event", "attach_open"}, {"pid", s.pid()}, {"hello", s.hello()}});
}

bool pollAttached(Viewer& v) {
  ViewerModel& m = v.model;
  LiveReceiver& receiver = *v.receiver;
  bool changed = updateLiveTimeline(v);  // --history K: a step freezes the stream, frozen a kept frame
  if (m.attach.detachRequested && !v.attachDetachLogged) {
    receiver.detach();
    v.attachDetachLogged = true;
    logLine(v.eventLog, {{"event", "attach_state"}, {"state", "detached"}});
  }
  if (m.playing != v.attachPlaying) {  // Space, the menu or the button
    v.attachPlaying = m.playing;
    receiver.setPaused(!m.playing);
    logLine(v.eventLog, {{"event", "attach_state"}, {"state", m.playing ? "resumed" : "paused"}, {"app_frame", v.attachInfo.appFrame}});
  }
  FrameSnapshot frame;
  LiveFrameInfo info;
  if (m.playing && !m.attach.detachRequested && receiver.take(frame, info)) {
    receiver.recycle(std::move(v.captureA.frame));  // its buffers hold the frames to come
    v.captureA.frame = FrameSnapshot{};
    showStreamFrame(v, std::move(frame), info);
    updateLiveTimeline(v);  // the strip on the frame taken among the kept ones
    changed = true;
  } else if (visibleViews(m) != v.attachShown) {  // other views came on screen
    decodeShown(v);
    changed = true;
  }
  for (std::string& r : receiver.takeReports()) {
    logLine(v.eventLog, {{"event", "attach_report"}, {"text", r}});
    m.attach.reports.push_back(std::move(r));
    changed = true;
  }
  if (m.attach.saveDraftRequested) {
    m.attach.saveDraftRequested = false;
    std::string path, error;
    m.attach.draftStatus = saveAttachedDraft(m.attach.draft, path, error) ? "saved " + path : "not saved: " + error;
    logLine(v.eventLog, {{"event", "draft_saved"}, {"status", m.attach.draftStatus}, {"path", path}});
    changed = true;
  }
  if (nlohmann::json suggestion; m.attach.passes.empty() && receiver.takeSuggestion(suggestion)) {
    m.attach.passes = describeLivePasses(v.args.attach->hello(), suggestion);
    std::vector<std::string> summary;
    const nlohmann::json draft = draftLiveLayout(suggestion, summary);
    m.attach.draft = draft.dump(2);
    m.attach.summary = summary;
    logLine(v.eventLog, {{"event", "attach_suggestion"}, {"draft", draft}});
    changed = true;
  }
  // The status at most ten times a second (it asks whether the application still runs).
  const auto now = std::chrono::steady_clock::now();
  if (changed || now - v.attachLastStatus > std::chrono::milliseconds(100)) {
    v.attachLastStatus = now;
    const LiveReceiver::State st = receiver.state();
    std::string status = statusText(v, st);
    if (!st.running && !v.attachExitLogged) {
      v.attachExitLogged = true;
      logLine(v.eventLog, {{"event", "attach_state"}, {"state", "exited"}, {"code", st.exitStatus}, {"status", status}});
    }
    if (status != m.attach.status) m.attach.status = std::move(status), changed = true;
  }
  return changed;
}

void attachedFramePresented(Viewer& v) {
  if (!v.attachPresentPending) return;
  v.attachPresentPending = false;
  v.attachShownMs = double(wire::monotonicNs() - v.attachInfo.endNs) * 1e-6;
  logLine(v.eventLog, {{"event", "attach_shown"}, {"stream", v.attachInfo.stream}, {"app_frame", v.attachInfo.appFrame},
                       {"latency_ms", v.attachShownMs}});
}

// A name in the working directory no file has yet: PREFIX<date>-<time>[-n]SUFFIX.
static std::string freshName(const std::string& prefix, const std::string& suffix) {
  char stamp[32];
  std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  std::string name = prefix + stamp + suffix;
  for (int n = 2; std::filesystem::exists(name); ++n)  // two in one second
    name = prefix + stamp + "-" + std::to_string(n) + suffix;
  return name;
}

bool saveAttachedDraft(const std::string& draft, std::string& written, std::string& error) {
  written = freshName("gblens-layout-", ".json");
  return writeTextAtomically(written, draft + "\n", error);
}

bool captureAttachedFrame(Viewer& v, std::string& written, std::string& error) {
  written = freshName("gblens-attach-", "");
  const LiveSession& s = *v.args.attach;
  CaptureMeta meta;
  meta.device = s.hello().value("device", "");
  meta.scene = v.args.scene + " (application frame " + std::to_string(v.attachInfo.appFrame) + ")";
  meta.commandLine = v.args.commandLine + " (capture button)";
  return writeCapture(written, v.captureA.frame, meta, error);
}

}  // namespace gb
