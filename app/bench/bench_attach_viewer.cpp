// make bench's attach variants with a viewer (see bench_attach.h runViewed): the viewer's own
// receiver (views/live/live_receiver.h) and, in place of a window, a loop that takes the newest frame
// at a display's rate and gives the one before back, as the viewer does, so that what pacing saves the
// application (docs/attach.md "The viewer asks for each frame") is measured where no display is.
#include "app/bench/bench_attach.h"

#include <chrono>
#include <thread>

#include "views/live/live_receiver.h"

namespace gb {

Attached runViewed(const std::string& layout, const std::vector<std::string>& argv, const std::string& log, double hz,
                   bool paced, uint64_t& taken) {
  Attached a;
  taken = 0;
  LiveSession s;
  if (!startAttached(s, layout, argv, log, 1, paced)) return a;
  {
    LiveReceiver receiver(s);
    const auto period = std::chrono::duration<double>(1.0 / hz);
    FrameSnapshot shown;
    for (auto next = std::chrono::steady_clock::now();;) {
      next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
      std::this_thread::sleep_until(next);
      const LiveReceiver::State st = receiver.state();
      if (!st.running && !st.attached) break;
      FrameSnapshot frame;
      LiveFrameInfo info;
      if (receiver.take(frame, info)) {  // what the viewer's loop does with each frame it shows
        receiver.recycle(std::move(shown));
        shown = std::move(frame);
        ++taken;
      }
    }
  }  // the receiver's thread ends before the session is read here
  a.counts = s.counts();
  a.app = renderStats(log);
  a.peakKb = s.applicationPeakKb();
  a.exitStatus = s.exitStatus();
  return a;
}

}  // namespace gb
