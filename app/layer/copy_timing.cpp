// GBLENS_LAYER_TIMESTAMPS=1 (docs/attach.md "Cost"): the GPU time of the layer's copies in the
// application's command buffers, from timestamps around them: the transitions into TRANSFER_SRC
// (after every earlier write), each copy command, the buffer copies, and the barrier back. For
// taking a copied frame's cost apart on a real GPU; off by default (a query pool and its reads).
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>

#include "app/layer/layer.h"

namespace gbl {

namespace {
constexpr uint32_t kBlocks = 64;   // copy blocks in flight at most: a block's queries are read when it is reused
constexpr uint32_t kQueries = 40;  // a block's: before, after the transitions, after each copy, after the buffers, after the way back
}  // namespace

struct CopyTiming {
  std::mutex lock;
  VkQueryPool pool = VK_NULL_HANDLE;
  double periodNs = 1.0;
  uint32_t next = 0;
  struct Block {
    std::vector<std::string> copies;  // what each copy command copies
    bool pending = false;
  } blocks[kBlocks];
  uint64_t measured = 0;
  double transitionsNs = 0.0, copiesNs = 0.0, buffersNs = 0.0, backNs = 0.0;
  std::map<std::string, std::pair<double, uint64_t>> byCopy;
};

bool copyTimingOn() {
  static const bool on = [] {
    const char* e = std::getenv("GBLENS_LAYER_TIMESTAMPS");
    return e && !std::strcmp(e, "1");
  }();
  return on;
}

namespace {

// A block's timestamps, once its last submission is done (not ready: left out).
void collect(DeviceData& d, CopyTiming& t, uint32_t block) {
  CopyTiming::Block& b = t.blocks[block];
  if (!b.pending) return;
  b.pending = false;
  const uint32_t n = uint32_t(b.copies.size()) + 4;
  uint64_t q[kQueries];
  if (d.vk.GetQueryPoolResults(d.device, t.pool, block * kQueries, n, sizeof q, q, 8, VK_QUERY_RESULT_64_BIT) != VK_SUCCESS) return;
  auto ns = [&](uint32_t from, uint32_t to) { return double(q[to] - q[from]) * t.periodNs; };
  ++t.measured;
  t.transitionsNs += ns(0, 1);
  for (uint32_t i = 0; i < b.copies.size(); ++i) {
    auto& [sum, count] = t.byCopy[b.copies[i]];
    sum += ns(1 + i, 2 + i);
    ++count;
  }
  t.copiesNs += ns(1, n - 3);
  t.buffersNs += ns(n - 3, n - 2);
  t.backNs += ns(n - 2, n - 1);
}

}  // namespace

int beginCopyTiming(DeviceData& d, VkCommandBuffer cmd, std::vector<std::string> copies) {
  if (!copyTimingOn() || copies.size() + 4 > kQueries) return -1;
  static std::mutex made;  // command buffers may be recorded on several threads at once
  std::unique_lock once(made);
  if (!d.timing) {
    auto t = std::make_unique<CopyTiming>();
    VkPhysicalDeviceProperties props{};
    d.instance->properties(d.physical, &props);
    if (!props.limits.timestampComputeAndGraphics) return -1;
    t->periodNs = props.limits.timestampPeriod;
    VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = kBlocks * kQueries;
    if (d.vk.CreateQueryPool(d.device, &qi, nullptr, &t->pool) != VK_SUCCESS) return -1;
    d.timing = std::move(t);
  }
  once.unlock();
  CopyTiming& t = *d.timing;
  std::lock_guard lock(t.lock);
  const uint32_t block = t.next++ % kBlocks;
  collect(d, t, block);  // the block's last use, 64 copy blocks ago
  t.blocks[block].copies = std::move(copies);
  t.blocks[block].pending = true;
  d.vk.CmdResetQueryPool(cmd, t.pool, block * kQueries, kQueries);
  return int(block);
}

void stampCopyTiming(DeviceData& d, VkCommandBuffer cmd, int block, uint32_t index) {
  if (block < 0) return;
  d.vk.CmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, d.timing->pool, uint32_t(block) * kQueries + index);
}

nlohmann::json copyTimingJson(DeviceData& d) {
  if (!d.timing) return nullptr;
  CopyTiming& t = *d.timing;
  std::lock_guard lock(t.lock);
  for (uint32_t k = 8; k < kBlocks; ++k) collect(d, t, (t.next + kBlocks - k) % kBlocks);  // not the last 8: still in flight
  const double n = t.measured ? double(t.measured) : 1.0;
  nlohmann::json by = nlohmann::json::object();
  for (const auto& [name, sum] : t.byCopy) by[name] = sum.first / double(sum.second) * 1e-6;
  return {{"blocks", t.measured},
          {"transitions_ms", t.transitionsNs / n * 1e-6},
          {"copies_ms", t.copiesNs / n * 1e-6},
          {"buffers_ms", t.buffersNs / n * 1e-6},
          {"back_ms", t.backNs / n * 1e-6},
          {"by_copy_ms", by}};
}

void destroyCopyTiming(DeviceData& d) {
  if (!d.timing) return;
  d.vk.DestroyQueryPool(d.device, d.timing->pool, nullptr);
  d.timing.reset();
}

}  // namespace gbl
