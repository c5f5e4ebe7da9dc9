// LiveReceiver (live_receiver.h): the thread is the only user of the LiveSession's receiving side;
// the viewer reads what it published under the lock.
#include "views/live/live_receiver.h"

#include <chrono>

namespace gb {

LiveReceiver::LiveReceiver(LiveSession& session) : session_(session) {
  state_.counts = session_.counts();
  thread_ = std::thread([this] { run(); });
}

LiveReceiver::~LiveReceiver() {
  stop_ = true;
  thread_.join();
}

bool LiveReceiver::take(FrameSnapshot& out, LiveFrameInfo& info) {
  std::lock_guard lock(lock_);
  if (!hasLatest_) return false;
  out = std::move(latest_);
  info = std::move(latestInfo_);
  latest_ = FrameSnapshot{};
  hasLatest_ = false;
  return true;
}

void LiveReceiver::recycle(FrameSnapshot&& frame) {
  std::lock_guard lock(lock_);
  returned_.push_back(std::move(frame));
}

void LiveReceiver::setPaused(bool paused) { paused_ = paused; }
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
    const bool got = receiving && session_.wait(frame, 0.02, &info);
    if (!receiving) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::vector<std::string> reports = session_.takeReports();
    const bool running = session_.running();
    std::lock_guard lock(lock_);
    if (got) {
      if (hasLatest_) ++state_.replaced, returned_.push_back(std::move(latest_));  // recycled next loop
      latest_ = std::move(frame);
      latestInfo_ = std::move(info);
      hasLatest_ = true;
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
