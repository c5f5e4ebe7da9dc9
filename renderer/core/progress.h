// Progress and cancellation of long CPU work done row by row (the viewer's reference error, gblens
// decompose): the work counts finished rows into a WorkProgress and stops taking rows once it is
// cancelled. Loops deep inside (reference::parallelRows) find it through the calling thread's
// ProgressScope, so the functions between need no extra parameter.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>

namespace gb {

struct WorkProgress {
  std::atomic<uint64_t> done{0};   // rows finished, each counted `weight` times
  std::atomic<uint64_t> total{0};  // what the caller expects in all (its stages' rows, weighted)
  // What a row of the stage now running counts for: a caller whose stages cost differently per row
  // sets it before each (1: every row alike).
  std::atomic<uint32_t> weight{1};
  std::atomic<bool> cancel{false};
  // Fraction done in [0, 1] (0 while nothing is expected).
  double fraction() const {
    const uint64_t t = total.load();
    return t ? std::min(1.0, double(done.load()) / double(t)) : 0.0;
  }
  bool cancelled() const { return cancel.load(std::memory_order_relaxed); }
};

namespace detail {
inline thread_local WorkProgress* currentProgress = nullptr;
}

// The progress the current thread's row loops report into (nullptr: none).
inline WorkProgress* currentProgress() { return detail::currentProgress; }

// Installs `p` for the current thread while it lives.
class ProgressScope {
 public:
  explicit ProgressScope(WorkProgress* p) : previous_(detail::currentProgress) { detail::currentProgress = p; }
  ~ProgressScope() { detail::currentProgress = previous_; }
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  WorkProgress* previous_;
};

}  // namespace gb
