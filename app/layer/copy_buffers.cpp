// The buffers a pass's end copies besides its attachments: the camera's bytes (the buffer of its
// debug name, or camera.live: the range bound at a set / binding / index of that pass, or its push
// constants) and bound_buffers (every distinct buffer range the pass's sets bind at the graphics bind
// point, in bind order, up to max_bytes, and its push constants). copy.cpp records them.
#include <algorithm>

#include "app/layer/layer.h"

namespace gbl {

namespace {

// Whether the layer can copy this buffer, with why not (reported once) otherwise.
bool copyable(DeviceData& d, const BufferInfo* info, const std::string& what) {
  if (info && (info->usage & VK_BUFFER_USAGE_TRANSFER_SRC_BIT)) return true;
  report(d, "nocopy:" + what, what + (info ? ": cannot be copied (the buffer has no TRANSFER_SRC usage)"
                                           : ": cannot be copied (a buffer the layer did not see made)"));
  return false;
}

std::string bindingText(uint32_t set, uint32_t binding, uint32_t index) {
  return "set " + std::to_string(set) + " binding " + std::to_string(binding) + (index ? " index " + std::to_string(index) : "");
}

VkBuffer findCamera(DeviceData& d, const CmdState& s, const Request& req, VkDeviceSize& size) {
  std::shared_lock lock(d.objects);
  VkBuffer found = s.cameraBuffer;
  if (!found || !d.buffers.count(found)) {  // not seen bound: the only buffer of that name, if one
    found = VK_NULL_HANDLE;
    int named = 0;
    for (const auto& [b, info] : d.buffers)
      if (info.name == req.cameraBuffer) found = b, ++named;
    if (named != 1) return VK_NULL_HANDLE;
  }
  const BufferInfo& info = d.buffers.at(found);
  if (!(info.usage & VK_BUFFER_USAGE_TRANSFER_SRC_BIT)) return VK_NULL_HANDLE;
  size = std::min(info.size, req.cameraBytes);
  return found;
}

BufferCopy pushCopy(const PushState& p, uint32_t lo, uint32_t hi) {
  BufferCopy c;
  c.inlineBytes.assign(p.bytes.begin() + lo, p.bytes.begin() + hi);
  c.size = hi - lo;
  c.copy.bound = {"push_constants", 0, 0, 0, "", c.size, lo, c.size};
  return c;
}

// camera.live: the matrices' bytes as the pass's last draw saw them.
bool liveCamera(DeviceData& d, const CmdState& s, const Request& req, BufferCopy& out) {
  const std::string where = "camera.live: render pass " + std::to_string(s.open.ordinal);
  if (req.cameraPushConstants) {
    if (s.push.hi < req.cameraBytes || s.push.lo > 0) {
      report(d, "camera.live", where + ": its push constants hold bytes " + std::to_string(s.push.lo == UINT32_MAX ? 0 : s.push.lo) +
                                   ".." + std::to_string(s.push.hi) + ", the matrices need 0.." + std::to_string(req.cameraBytes));
      return false;
    }
    out = pushCopy(s.push, 0, uint32_t(req.cameraBytes));
    return true;
  }
  std::shared_lock lock(d.objects);
  std::vector<BoundDescriptor> all;
  if (req.cameraSet < s.graphicsSets.size()) boundDescriptors(d, req.cameraSet, s.graphicsSets[req.cameraSet], all);
  auto hit = std::find_if(all.begin(), all.end(), [&](const BoundDescriptor& b) {
    return b.binding == req.cameraBinding && b.index == req.cameraIndex && bufferDescriptor(b.type) && b.buffer;
  });
  if (hit == all.end()) {
    report(d, "camera.live", where + " binds no uniform or storage buffer at " +
                                 bindingText(req.cameraSet, req.cameraBinding, req.cameraIndex));
    return false;
  }
  auto info = d.buffers.find(hit->buffer);
  if (!copyable(d, info == d.buffers.end() ? nullptr : &info->second, "camera.live")) return false;
  out.source = hit->buffer;
  out.offset = hit->offset;
  out.size = std::min(hit->range, req.cameraBytes);
  if (out.size < req.cameraBytes)
    report(d, "camera.live:short", where + ": the range bound at " + bindingText(req.cameraSet, req.cameraBinding, req.cameraIndex) +
                                       " holds " + std::to_string(hit->range) + " bytes, the matrices need " +
                                       std::to_string(req.cameraBytes));
  return out.size > 0;
}

// bound_buffers: each distinct range once, in bind order, up to max_bytes in all.
void boundBuffers(DeviceData& d, const CmdState& s, const Request& req, std::vector<BufferCopy>& out) {
  std::shared_lock lock(d.objects);
  std::vector<BoundDescriptor> all;
  for (const BindEvent& b : s.passBinds) boundDescriptors(d, b.number, b.set, all);
  VkDeviceSize total = 0, bound = 0;
  std::vector<BoundDescriptor> seen;
  for (const BoundDescriptor& b : all) {
    if (!bufferDescriptor(b.type) || !b.buffer || !b.range) continue;
    if (std::any_of(seen.begin(), seen.end(), [&](const BoundDescriptor& e) {
          return e.buffer == b.buffer && e.offset == b.offset && e.range == b.range;
        }))
      continue;
    seen.push_back(b);
    bound += b.range;
    auto info = d.buffers.find(b.buffer);
    const BufferInfo* bi = info == d.buffers.end() ? nullptr : &info->second;
    const std::string what = "bound_buffers: " + bindingText(b.set, b.binding, b.index) + (bi && !bi->name.empty() ? " (\"" + bi->name + "\")" : "");
    if (total >= req.boundMaxBytes || !copyable(d, bi, what)) continue;
    BufferCopy c;
    c.source = b.buffer;
    c.offset = b.offset;
    c.size = std::min(b.range, req.boundMaxBytes - total);
    total += c.size;
    const bool uniform = b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
    c.copy.bound = {uniform ? "uniform" : "storage", b.set, b.binding, b.index, bi->name, bi->size, b.offset, b.range};
    out.push_back(std::move(c));
  }
  if (bound > total)
    report(d, "bound_buffers:truncated", "bound_buffers: render pass " + std::to_string(s.open.ordinal) + " binds " +
                                             std::to_string(bound) + " bytes of buffers; the first " + std::to_string(total) +
                                             " are copied (max_bytes)");
}

}  // namespace

std::vector<BufferCopy> bufferCopies(DeviceData& d, const CmdState& s, const Request& req, bool targets) {
  std::vector<BufferCopy> out;
  // The camera by name, as the pass that copies targets saw it (a later pass's copy replaces it).
  if (targets && !req.cameraBuffer.empty()) {
    BufferCopy c;
    if ((c.source = findCamera(d, s, req, c.size)) != VK_NULL_HANDLE)
      out.push_back(std::move(c));
    else
      report(d, "camera", "camera: no buffer named \"" + req.cameraBuffer +
                              "\" is bound where the pass runs (or several have that name and none is bound)");
  }
  if (req.liveCamera.on && passMatches(req.liveCamera, s.open)) {
    BufferCopy c;
    if (liveCamera(d, s, req, c)) out.push_back(std::move(c));
  }
  for (BufferCopy& c : out) c.copy.target = kCameraCopy, c.copy.bytes = c.size;
  if (req.boundBuffers.on && passMatches(req.boundBuffers, s.open)) {
    const size_t first = out.size();
    boundBuffers(d, s, req, out);
    if (s.push.hi > s.push.lo) out.push_back(pushCopy(s.push, s.push.lo, s.push.hi));
    for (size_t i = first; i < out.size(); ++i) out[i].copy.target = kBoundCopy, out[i].copy.bytes = out[i].size;
  }
  return out;
}

}  // namespace gbl
