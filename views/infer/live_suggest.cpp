// `gblens attach --suggest` with no layout (live.h suggestLive): the application is started asking the
// layer only for its render passes; a layout is drafted from them; the application is started again
// streaming under that draft (a command buffer recorded before a layout was known copies nothing, and
// many applications record theirs once), and its first frame's texels refine the draft as
// `import --suggest-layout` reads a capture's. The second run goes on streaming under the refined draft.
#include <chrono>

#include "views/live/live.h"
#include "views/infer/suggest_live.h"

namespace gb {

namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Why waiting on `s` is over without what was waited for ("" : not over).
std::string gaveUp(LiveSession& s, std::chrono::steady_clock::time_point start, double timeout, const char* what) {
  if (s.noMatch()) return "nothing matched the draft layout in the application's first frames (the layer's reports say why)";
  if (!s.running() && !s.attached())
    return s.hello().is_null() ? "the application ended without creating a Vulkan device under the layer"
                               : std::string("the application ended before ") + what;
  if (secondsSince(start) > timeout) return "--timeout " + std::to_string(int(timeout)) + " s: " + what + " did not come";
  return "";
}

}  // namespace

bool suggestLive(const LiveOptions& o, double timeout, LiveSession& session, LiveSuggestion& out,
                 const std::function<void(const std::string&)>& progress, std::string& error) {
  // 1. The passes of one frame.
  LiveOptions first = o;
  first.layout.clear();
  first.layoutJson = nullptr;
  first.suggest = true;
  first.captureFrame = -1;
  std::vector<LiveTargetFacts> later;
  {
    LiveSession s;
    if (!s.start(first, error)) return false;
    progress("gblens attach: waiting for the render passes of " + o.argv[0]);
    const auto start = std::chrono::steady_clock::now();
    while (!s.suggestion()) {
      FrameSnapshot unused;
      s.wait(unused, 0.2);
      for (std::string& r : s.takeReports()) out.reports.push_back(std::move(r));
      if (!s.suggestion() && !(error = gaveUp(s, start, timeout, "a render pass was submitted")).empty()) return false;
    }
    out.passes = describeLivePasses(s.hello(), *s.suggestion());
    out.draft = draftLiveLayout(*s.suggestion(), out.summary, &later);
    s.stop();  // its command buffers copy nothing: the streaming run is a new one
  }
  if (out.draft["targets"].empty()) {
    error = "no render pass of the application writes an attachment a layout can hold";
    return false;
  }
  // 2. The application again, streaming the drafted attachments; its first frame refines the draft.
  LiveOptions second = o;
  second.layout.clear();
  second.layoutJson = out.draft;
  withoutCamera(second.layoutJson, nullptr);  // the texels as stored; the refined draft says what they need
  second.suggest = false;
  // The buffers the G-buffer pass binds, copied with each frame: the camera search reads the first
  // frame's, and the refined draft's camera.live reads its camera from them in every later frame.
  for (const LiveTargetFacts& f : later)
    if (f.writer != Writer::Later) second.boundBuffersPass = f.pass;
  progress("gblens attach: starting " + o.argv[0] + " again, streaming the " + std::to_string(out.draft["targets"].size()) +
           " attachments the draft names");
  if (!session.start(second, error)) return false;
  FrameSnapshot raw;
  const auto start = std::chrono::steady_clock::now();
  bool got = false;
  while (!got && error.empty()) {
    got = session.wait(raw, 0.2, &out.info);
    for (std::string& r : session.takeReports()) out.reports.push_back(std::move(r));
    if (!got) error = gaveUp(session, start, timeout, "a frame");
  }
  if (!got) return false;
  if (!refineLiveDraft(out.draft, later, raw, out.info.appFrame, session.boundBuffers(), out.frame, out.summary, error) ||
      !session.setLayout(out.draft, error)) {
    error = "the refined draft: " + error;  // a bug here: the refinement keeps targets and sources
    return false;
  }
  out.frame.options = raw.options;
  return true;
}

}  // namespace gb
