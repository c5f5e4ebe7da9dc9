// The viewer's side of an attached stream (gblens attach): a LiveSession driven by a thread of its
// own, which receives and decodes each frame as it comes, so that the layer can send the next one at
// once and the viewer, whenever it draws, takes the newest (a frame no longer waits in the socket for
// the viewer's next loop). Paused, the thread takes nothing: the layer drops the application's frames.
// A paced session (LiveOptions::paced) asks the layer for each frame, so that none is copied, sent or
// decoded that the viewer would not show: after the viewer takes a frame, timed to come just before
// the viewer next looks for one (its time from a take to its next look, less a frame's time from
// the ask to its decoding); where a frame takes longer to come than the viewer to draw one, as soon
// as the frame before is decoded, two at a time (on their way while the viewer shows this one, as
// the application makes them in flight).
#pragma once
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "views/live/live.h"

namespace gb {

class LiveReceiver {
 public:
  explicit LiveReceiver(LiveSession& session);  // the session must have started; the thread starts here
  ~LiveReceiver();                               // stops the thread; the session stays as it is
  LiveReceiver(const LiveReceiver&) = delete;
  LiveReceiver& operator=(const LiveReceiver&) = delete;

  // The newest frame decoded since the last call, if any (never waits). Paced: taking it asks for the
  // next one.
  bool take(FrameSnapshot& out, LiveFrameInfo& info);
  // A frame take() gave that is no longer shown: the thread gives its buffers to the session's
  // next frames (LiveSession::recycle).
  void recycle(FrameSnapshot&& frame);
  void setPaused(bool paused);
  void detach();  // the session detaches (the layer goes idle for good; the application runs on)

  // What the session said, as of the thread's last look (it asks at least every 20 ms).
  struct State {
    LiveCounts counts;
    bool running = true, attached = true;
    int exitStatus = -1;
    uint64_t replaced = 0;          // decoded frames a newer one replaced before the viewer took them
    bool receiving = true;          // the thread's last look took frames (false: paused or detached, no frame comes)
    // The session's history (LiveOptions::history): frames kept, at most, and their texels' bytes.
    size_t historyFrames = 0, historyLimit = 0, historyBytes = 0;
  };
  State state();
  std::vector<std::string> takeReports();
  // The last frames decoded (the session's history, oldest first, as of the thread's last frame):
  // shared, never copied again; empty unless LiveOptions::history was given.
  std::vector<HistoryFrame> history();
  // The layer's report of one frame's passes (--suggest): true once, when it has come.
  bool takeSuggestion(nlohmann::json& out);

 private:
  void run();

  LiveSession& session_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, paused_{false}, detach_{false};
  std::atomic<uint64_t> resumedNs_{0};  // when the viewer last resumed: a frame that ended before is stale
  // Paced, under lock_: ask for the next frame at askAtNs_ (the session's first frame was taken before
  // the thread began: at once). The running means: the viewer's time from a take to its next look
  // (drawMs_), a frame's from the ask to its decoding (comeMs_).
  bool wantNext_ = true;
  int wake_ = -1;  // an eventfd: take() wakes the thread to ask for the next frame
  uint64_t askAtNs_ = 0, takenNs_ = 0, publishedNs_ = 0;
  double drawMs_ = 0.0, comeMs_ = 0.0;
  double spareMs_ = 3.0;  // asked that much sooner (more after a frame came late, less while frames wait)
  uint64_t askedNs_ = 0;  // the thread's: its first ask since the last frame decoded (0: none)
  std::mutex lock_;
  FrameSnapshot latest_;
  std::vector<FrameSnapshot> returned_;  // recycle()'s, for the thread
  LiveFrameInfo latestInfo_;
  bool hasLatest_ = false;
  State state_;
  std::vector<std::string> reports_;
  nlohmann::json suggestion_;
  std::vector<HistoryFrame> history_;
  bool suggestionTaken_ = false;
};

}  // namespace gb
