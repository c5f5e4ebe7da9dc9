// LiveReceiver (live_receiver.h): the thread is the only user of the LiveSession's receiving side;
// the viewer reads what it published under the lock.
#include "views/live/live_receiver.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>

#include "views/live/live_wire.h"

namespace gb {

LiveReceiver::LiveReceiver(LiveSession& session) : session_(session) {
  state_.counts = session_.counts();
  wake_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  thread_ = std::thread([this] { run(); });
}

LiveReceiver::~LiveReceiver() {
  stop_ = true;
  thread_.join();
  if (wake_ >= 0) close(wake_);
}

namespace {
double runningMean(double mean, double sample) { return mean > 0.0 ? 0.8 * mean + 0.2 * sample : sample; }
}  // namespace

bool LiveReceiver::take(FrameSnapshot& out, LiveFrameInfo& info) {
  std::lock_guard lock(lock_);
  const uint64_t now = wire::monotonicNs();
  if (takenNs_) {  // the viewer's first look since it took a frame: was the next one there in time?
    drawMs_ = runningMean(drawMs_, std::min(250.0, double(now - takenNs_) * 1e-6));  // a stall is not its pace
    if (!hasLatest_) spareMs_ = std::min(spareMs_ + 2.0, std::max(drawMs_, 3.0));  // late: ask sooner
    else if (double(now - publishedNs_) * 1e-6 > spareMs_ + 2.0) spareMs_ = std::max(1.0, spareMs_ - 0.5);  // it waited
    takenNs_ = 0;
  }
  if (!hasLatest_) return false;
  out = std::move(latest_);
  info = std::move(latestInfo_);
  latest_ = FrameSnapshot{};
  hasLatest_ = false;
  takenNs_ = now;
  wantNext_ = true;  // to come just before the viewer looks again
  if (wake_ >= 0) {
    const uint64_t one = 1;
    (void)!write(wake_, &one, sizeof one);
  }
  // A frame's time to come varies (the application's frame, the copy, the decoding): the time to
  // spare grows when the viewer looked before the frame was there, and shrinks while frames wait.
  askAtNs_ = now + uint64_t(std::max(0.0, drawMs_ - comeMs_ - spareMs_) * 1e6);
  return true;
}

void LiveReceiver::recycle(FrameSnapshot&& frame) {
  std::lock_guard lock(lock_);
  returned_.push_back(std::move(frame));
}

void LiveReceiver::setPaused(bool paused) {
  if (paused_ && !paused) resumedNs_ = wire::monotonicNs();
  paused_ = paused;
  std::lock_guard lock(lock_);
  takenNs_ = 0;  // the time paused is not the viewer's time to draw
}
void LiveReceiver::detach() { detach_ = true; }

LiveReceiver::State LiveReceiver::state() {
  std::lock_guard lock(lock_);
  return state_;
}

std::vector<std::string> LiveReceiver::takeReports() {
  std::lock_guard lock(lock_);
  std::vector<std::string> out;
  out.swap(reports_);
  return out;
}

std::vector<HistoryFrame> LiveReceiver::history() {
  std::lock_guard lock(lock_);
  return history_;
}

bool LiveReceiver::takeSuggestion(nlohmann::json& out) {
  std::lock_guard lock(lock_);
  if (suggestion_.is_null()) return false;
  out = std::move(suggestion_);
  suggestion_ = nullptr;
  suggestionTaken_ = true;
  return true;
}

void LiveReceiver::run() {
  while (!stop_) {
    if (detach_ && session_.attached()) session_.detach();
    std::vector<FrameSnapshot> returned;
    {
      std::lock_guard lock(lock_);
      returned.swap(returned_);
    }
    for (FrameSnapshot& f : returned) session_.recycle(std::move(f));  // the session is this thread's alone
    FrameSnapshot frame;
    LiveFrameInfo info;
    const bool receiving = !paused_ && !detach_ && (session_.attached() || session_.running());
    double waitS = 0.02;
    if (receiving && session_.paced()) {  // the next frame may be copied now, or wait until it may
      bool ask = false;
      unsigned frames = 1;
      {
        std::lock_guard lock(lock_);
        const uint64_t now = wire::monotonicNs();
        ask = wantNext_ && now >= askAtNs_;
        if (ask) wantNext_ = false;
        if (wantNext_) waitS = std::clamp(double(askAtNs_ - now) * 1e-9, 0.001, 0.02);
        frames = comeMs_ > drawMs_ ? 2 : 1;  // slower than the viewer: two on their way, as the application makes them
      }
      if (ask) session_.ready(frames);
      if (ask && !askedNs_) askedNs_ = wire::monotonicNs();
    }
    bool got = receiving && session_.wait(frame, waitS, &info, wake_);
    if (uint64_t n; wake_ >= 0) (void)!read(wake_, &n, sizeof n);
    if (got && info.endNs < resumedNs_) {  // copied before the viewer paused, read after it resumed: not shown
      session_.recycle(std::move(frame));
      frame = FrameSnapshot{};
      got = false;
      std::lock_guard lock(lock_);
      wantNext_ = true, askAtNs_ = 0;
    }
    if (!receiving) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::vector<std::string> reports = session_.takeReports();
    const bool running = session_.running();
    std::lock_guard lock(lock_);
    if (got) {
      if (hasLatest_) ++state_.replaced, returned_.push_back(std::move(latest_));  // recycled next loop
      latest_ = std::move(frame);
      latestInfo_ = std::move(info);
      hasLatest_ = true;
      publishedNs_ = wire::monotonicNs();
      if (askedNs_) comeMs_ = runningMean(comeMs_, double(wire::monotonicNs() - askedNs_) * 1e-6), askedNs_ = 0;
      // A frame takes longer to come than the viewer to draw one: the next ones are asked for now, to
      // be on their way while the viewer shows this one.
      if (comeMs_ > drawMs_) wantNext_ = true, askAtNs_ = 0;
      const FrameHistory& h = session_.history();
      history_.assign(h.frames().begin(), h.frames().end());
    }
    state_.receiving = receiving;
    state_.historyFrames = history_.size();
    state_.historyLimit = session_.history().limit();
    state_.historyBytes = session_.history().bytes();
    for (std::string& r : reports) reports_.push_back(std::move(r));
    state_.counts = session_.counts();
    state_.running = running;
    state_.attached = session_.attached();
    state_.exitStatus = session_.exitStatus();
    if (suggestion_.is_null() && !suggestionTaken_ && session_.suggestion()) suggestion_ = *session_.suggestion();
  }
}

}  // namespace gb
