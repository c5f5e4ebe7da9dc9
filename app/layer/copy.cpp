// At the end of a render pass: which requested targets it holds, and the commands that copy them
// (and the camera's and the bound buffers' bytes, copy_buffers.cpp) into the ring, recorded into the application's command buffer right
// after the pass. Each attachment goes from the layout the pass left it in to TRANSFER_SRC and back,
// with barriers that order the copy after the pass's writes and everything after it after the
// copy, so the application's own synchronisation sees its images as it left them.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>

#include "app/layer/layer.h"

namespace gbl {

namespace {

struct Looked {  // an attachment with what the layer knows of its image
  const PassAttachment* a = nullptr;
  ImageInfo image;
  std::string viewName;
  uint32_t viewMip = 0, viewLayer = 0;
};

struct Region {  // one copy command: to the ring, or (a multisampled attachment) to the layer's image
  VkImage image;
  VkImageLayout layout;
  VkBuffer buffer;
  VkBufferImageCopy copy;
  VkImage stage = VK_NULL_HANDLE;
  VkImageCopy samples{};
};

bool passMatches(const Pick& p, const OpenPass& pass) {
  if (p.passIndex >= 0 && p.passIndex != pass.ordinal) return false;
  if (!p.pass.empty() && p.pass != pass.renderPass &&
      std::find(pass.labels.begin(), pass.labels.end(), p.pass) == pass.labels.end())
    return false;
  return true;
}

}  // namespace

std::string pickText(const Pick& p) {
  std::string t = p.storageSet >= 0   ? "the storage image at set " + std::to_string(p.storageSet) + " binding " +
                                           std::to_string(p.storageBinding)
                  : !p.name.empty()    ? "the image named \"" + p.name + "\""
                  : p.attachment >= 0 ? "attachment " + std::to_string(p.attachment)
                  : p.color >= 0      ? "colour attachment " + std::to_string(p.color)
                  : p.depth           ? std::string("the depth attachment")
                                      : "the " + p.byFormat + " attachment";
  if (p.subpass >= 0) t += " of subpass " + std::to_string(p.subpass);
  if (!p.pass.empty()) t += " of pass \"" + p.pass + "\"";
  if (p.passIndex >= 0) t += " of render pass " + std::to_string(p.passIndex);
  return t;
}

namespace {

// The attachment a pick selects in this pass, or null.
const Looked* select(DeviceData& d, const Pick& p, const OpenPass& pass, const std::vector<Looked>& all) {
  // A dispatch's storage images are picked by name or by the set and binding it binds them at
  // (attachment indices, colour slots and formats are a render pass's); a storage pick is no
  // render pass's attachment.
  if (pass.ordinal < 0 && p.storageSet < 0 && (p.name.empty() || p.attachment >= 0 || p.subpass >= 0)) return nullptr;
  if (pass.ordinal >= 0 && p.storageSet >= 0) return nullptr;
  int index = p.attachment;  // a pick by the render pass's attachment index, or by a subpass's
  if (p.subpass >= 0) {
    if (size_t(p.subpass) >= pass.subpassColors.size()) {
      report(d, "subpass:" + p.targetName, "target \"" + p.targetName + "\": render pass " + std::to_string(pass.ordinal) + " has " +
                                              std::to_string(pass.subpassColors.size()) + " subpasses, the layout names subpass " +
                                              std::to_string(p.subpass));
      return nullptr;
    }
    const std::vector<int>& colors = pass.subpassColors[size_t(p.subpass)];
    index = p.depth ? pass.subpassDepth[size_t(p.subpass)] : size_t(p.color) < colors.size() ? colors[size_t(p.color)] : -1;
    if (index < 0) return nullptr;
  }
  std::vector<const Looked*> found;
  for (const Looked& l : all) {
    const bool hit = p.storageSet >= 0 ? l.a->storageSet == p.storageSet && l.a->storageBinding == p.storageBinding
                     : index >= 0       ? l.a->attachment == index
                     : !p.name.empty() ? (l.image.name == p.name || l.viewName == p.name)
                     : p.color >= 0  ? l.a->color == p.color
                     : p.depth       ? l.a->depth
                                     : formatInfo(l.image.format).storage == p.byFormat;
    if (hit) found.push_back(&l);
  }
  if (found.empty()) return nullptr;
  if (found.size() > 1 && !p.byFormat.empty()) {
    report(d, "ambiguous:" + p.targetName,
           "target \"" + p.targetName + "\": render pass " + std::to_string(pass.ordinal) + " has " +
               std::to_string(found.size()) + " attachments of format " + p.byFormat + "; pick one by name or index");
    return nullptr;
  }
  // A pick by name alone follows the image through every pass that writes it (the last one wins).
  if (!p.name.empty() && p.pass.empty() && p.passIndex < 0 && !found[0]->a->written) return nullptr;
  return found[0];
}

}  // namespace

std::string refusal(DeviceData& d, const ImageInfo& image, const std::string& want) {
  const FormatInfo& f = formatInfo(image.format);
  if (!*f.storage) return "is " + formatName(image.format) + ", which no layout storage format holds";
  if (!want.empty() && want != f.storage)
    return "is " + std::string(f.storage) + " (" + formatName(image.format) + "), the layout says " + want;
  if (image.samples != VK_SAMPLE_COUNT_1_BIT)
    if (std::string why = sampleRefusal(d, image); !why.empty()) return why;
  if (image.transient && !(image.usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
    return "is a transient attachment on a device with lazily allocated memory: create it without "
           "VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT (and in ordinary device memory) for gblens to copy it";
  if (!(image.usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
    return "cannot be copied (a format the device cannot copy from)";
  return "";
}

namespace {

VkImageAspectFlags aspects(const FormatInfo& f) {
  if (!f.depth && !f.stencil) return VK_IMAGE_ASPECT_COLOR_BIT;
  return (f.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : 0) | (f.stencil ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}

// An attachment the pass left in GENERAL is copied there; a storage image (in GENERAL to be written,
// and about to be copied once) goes to TRANSFER_SRC like the others.
bool inPlace(const PassAttachment& a, VkImageLayout layout) { return layout == VK_IMAGE_LAYOUT_GENERAL && !a.storage; }

// The barriers that take an attachment to TRANSFER_SRC (there) and back (after its copy).
void transitions(const Looked& l, const FormatInfo& f, std::vector<VkImageMemoryBarrier>& there,
                 std::vector<VkImageMemoryBarrier>& back) {
  const PassAttachment& a = *l.a;
  auto barrier = [&](VkImageAspectFlags aspect, VkImageLayout layout) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = a.storage                ? VK_ACCESS_SHADER_WRITE_BIT
                      : f.depth || f.stencil ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT
                                             : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.oldLayout = layout;
    b.newLayout = inPlace(a, layout) ? layout : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = a.image;
    b.subresourceRange = {aspect, l.viewMip, 1, l.viewLayer, 1};
    there.push_back(b);
    std::swap(b.oldLayout, b.newLayout);
    b.srcAccessMask = 0;  // the copy only read it
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    back.push_back(b);
  };
  if (f.depth && f.stencil && a.layout != a.stencilLayout) {  // separate depth and stencil layouts
    barrier(VK_IMAGE_ASPECT_DEPTH_BIT, a.layout);
    barrier(VK_IMAGE_ASPECT_STENCIL_BIT, a.stencilLayout);
  } else {
    barrier(aspects(f), a.layout);
  }
}

// One aspect of the attachment copied into subresource 0 of an image of the layer's (vkCmdCopyImage,
// sample for sample), from the layout the pass left that aspect in.
Region layerImageCopy(const Looked& l, VkImage dst, VkImageAspectFlags aspect, uint32_t width, uint32_t height) {
  const VkImageLayout was = aspect == VK_IMAGE_ASPECT_STENCIL_BIT ? l.a->stencilLayout : l.a->layout;
  Region r{l.a->image, inPlace(*l.a, was) ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
           VK_NULL_HANDLE, {}, dst, {}};
  r.samples.srcSubresource = {aspect, l.viewMip, l.viewLayer, 1};
  r.samples.dstSubresource = {aspect, 0, 0, 1};
  r.samples.extent = {width, height, 1};
  return r;
}

// The layer's image made ready for those copies: its last contents (an earlier frame's) are not needed.
VkImageMemoryBarrier toTransferDst(VkImage image, VkImageAspectFlags aspects) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspects, 0, 1, 0, 1};
  return b;
}

// The staged ring's copy of a single-sampled attachment into its tile image (ring.h TileImage): image
// to image on the application's queue, each aspect from its own layout; the tile left in
// TRANSFER_SRC for the download on the layer's queue (staging.cpp recordDownload).
void tileCopies(DeviceData& d, const Looked& l, const FormatInfo& f, Copy& c, VkImage tile, std::vector<Region>& regions,
                std::vector<VkImageMemoryBarrier>& there, std::vector<VkImageMemoryBarrier>& back) {
  c.tile = tile;
  ++d.tileCopies;
  if (f.depth || !f.stencil)
    regions.push_back(layerImageCopy(l, tile, f.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, c.width, c.height));
  if (f.stencil) regions.push_back(layerImageCopy(l, tile, VK_IMAGE_ASPECT_STENCIL_BIT, c.width, c.height));
  VkImageMemoryBarrier b = toTransferDst(tile, aspects(f));
  there.push_back(b);
  b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;  // then the download's read, after the fence
  b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  back.push_back(b);
}

}  // namespace

namespace {

// The commands: every earlier write before the copies, the attachments to TRANSFER_SRC, the
// copies, then the ring's bytes to the host and the attachments back to the application's layouts.
// GBLENS_LAYER_MEASURE (docs/attach.md "Cost"): "barriers" records the transitions and no copies,
// "none" records nothing (the ring, fences and frames as usual): what a copied frame costs the
// application, taken apart. The frames streamed then hold garbage; for the bench only.
int measureMode() {
  static const int mode = [] {
    const char* e = std::getenv("GBLENS_LAYER_MEASURE");
    return !e ? 0 : !std::strcmp(e, "barriers") ? 1 : !std::strcmp(e, "none") ? 2 : 0;
  }();
  return mode;
}

void recordTransfers(DeviceData& d, VkCommandBuffer cmd, const std::vector<VkImageMemoryBarrier>& there,
                     const std::vector<VkImageMemoryBarrier>& back, const std::vector<Region>& regions,
                     const std::vector<Copy>& made, const std::vector<BufferCopy>& buffers) {
  const DeviceTable& vk = d.vk;
  if (measureMode() == 2) return;
  std::vector<std::string> names;  // GBLENS_LAYER_TIMESTAMPS=1: each copy command's time (copy_timing.cpp)
  if (copyTimingOn()) {
    std::shared_lock lock(d.objects);
    for (const Region& r : regions) {
      auto img = d.images.find(r.image);
      const VkImageAspectFlags aspect = r.stage ? r.samples.srcSubresource.aspectMask : r.copy.imageSubresource.aspectMask;
      names.push_back((img != d.images.end() && !img->second.name.empty() ? img->second.name : "image") +
                      (aspect == VK_IMAGE_ASPECT_STENCIL_BIT ? " stencil" : aspect == VK_IMAGE_ASPECT_DEPTH_BIT ? " depth" : "") +
                      (r.stage ? " (samples)" : ""));
    }
  }
  const int timing = beginCopyTiming(d, cmd, std::move(names));  // -1: not timed
  stampCopyTiming(d, cmd, timing, 0);
  // Every earlier write before these copies: the buffers' (whoever made them), and the ring's own
  // from an earlier pass or an earlier submission of this command buffer (the copies write the same
  // bytes again).
  VkMemoryBarrier memory{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  memory.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  memory.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &memory, 0, nullptr,
                        uint32_t(there.size()), there.data());
  stampCopyTiming(d, cmd, timing, 1);
  uint32_t stamp = 2;
  for (const Region& r : regions) {
    if (measureMode() != 1 && r.stage)
      vk.CmdCopyImage(cmd, r.image, r.layout, r.stage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r.samples);
    else if (measureMode() != 1)
      vk.CmdCopyImageToBuffer(cmd, r.image, r.layout, r.buffer, 1, &r.copy);
    stampCopyTiming(d, cmd, timing, stamp++);
  }
  for (const BufferCopy& b : buffers) {
    if (b.source) {
      VkBufferCopy bc{b.offset, b.copy.offset, b.size};
      vk.CmdCopyBuffer(cmd, b.source, b.copy.buffer->buffer, 1, &bc);
    } else {  // push constants: bytes the application gave at recording (a multiple of 4, at most 4 KiB)
      vk.CmdUpdateBuffer(cmd, b.copy.buffer->buffer, b.copy.offset, b.size, b.inlineBytes.data());
    }
  }
  std::vector<VkBufferMemoryBarrier> toHost;  // the ring's bytes, for the layer's thread once the fence says so
  auto ring = [&](VkBuffer buffer) {
    if (std::any_of(toHost.begin(), toHost.end(), [&](const VkBufferMemoryBarrier& b) { return b.buffer == buffer; })) return;
    VkBufferMemoryBarrier b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.size = VK_WHOLE_SIZE;
    toHost.push_back(b);
  };
  for (const Copy& c : made) ring(c.buffer->buffer);
  for (const BufferCopy& b : buffers) ring(b.copy.buffer->buffer);
  stampCopyTiming(d, cmd, timing, stamp++);
  vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                        0, 0, nullptr, uint32_t(toHost.size()), toHost.data(), uint32_t(back.size()), back.data());
  stampCopyTiming(d, cmd, timing, stamp);
}

// The recording's copies so far: a target copied again (a later pass writes it too) and a later
// pass's camera replace the earlier ones; a pass's bound buffers replace all earlier ones.
void keep(CmdState& s, std::vector<Copy>& made, std::vector<BufferCopy>& buffers) {
  for (Copy& c : made) {
    std::erase_if(s.copiesMade, [&](const Copy& e) { return e.target == c.target; });
    s.copiesMade.push_back(std::move(c));
  }
  for (int kind : {kCameraCopy, kBoundCopy})
    if (std::any_of(buffers.begin(), buffers.end(), [&](const BufferCopy& b) { return b.copy.target == kind; }))
      std::erase_if(s.copiesMade, [&](const Copy& e) { return e.target == kind; });
  for (BufferCopy& b : buffers) s.copiesMade.push_back(std::move(b.copy));
}

}  // namespace

void recordCopies(DeviceData& d, VkCommandBuffer cmd, CmdState& s) { recordPassCopies(d, cmd, s, s.open); }

void recordPassCopies(DeviceData& d, VkCommandBuffer cmd, CmdState& s, const OpenPass& pass) {
  const auto start = std::chrono::steady_clock::now();
  std::shared_ptr<const Request> req = currentRequest(d);
  if (!req) return;
  std::vector<Looked> all;
  {
    std::shared_lock lock(d.objects);
    for (const PassAttachment& a : pass.attachments) {
      auto img = d.images.find(a.image);
      auto view = d.views.find(a.view);
      if (img == d.images.end() || view == d.views.end()) continue;
      all.push_back({&a, img->second, view->second.name, view->second.mip, view->second.layer});
    }
  }
  std::vector<VkImageMemoryBarrier> there, back;
  std::vector<Region> regions;
  std::vector<Copy> made;
  for (size_t t = 0; t < req->picks.size(); ++t) {
    const Pick& p = req->picks[t];
    if (!passMatches(p, pass)) continue;
    const Looked* l = select(d, p, pass, all);
    if (!l) continue;
    if (std::string why = refusal(d, l->image, p.format); !why.empty()) {
      report(d, "refused:" + p.targetName, "target \"" + p.targetName + "\": " + pickText(p) + " " + why);
      continue;
    }
    const FormatInfo& f = formatInfo(l->image.format);
    Copy c;
    c.target = int(t);
    c.width = std::max(1u, l->image.extent.width >> l->viewMip);
    c.height = std::max(1u, l->image.extent.height >> l->viewMip);
    c.format = l->image.format;
    c.passOrdinal = pass.ordinal;
    c.pass = !pass.labels.empty() ? pass.labels.back() : pass.renderPass;
    const VkDeviceSize plane = VkDeviceSize(c.width) * c.height * f.bytes;
    const VkDeviceSize stencilAt = (plane + 3) / 4 * 4;
    VkDeviceSize bytes = f.stencil && f.depth ? stencilAt + VkDeviceSize(c.width) * c.height : plane;
    if (l->image.samples != VK_SAMPLE_COUNT_1_BIT) {  // one plane per sample, each whole words (samples.cpp)
      c.stage = sampleStage(d, l->a->image, l->viewMip, l->viewLayer, l->image);
      if (!c.stage) {
        report(d, "samples:memory:" + p.targetName, "target \"" + p.targetName + "\": no device memory for a copy of its samples");
        continue;
      }
      c.samples = uint32_t(l->image.samples);
      c.sampleStride = stencilAt;
      bytes = c.sampleStride * c.samples;
    }
    // The same target again in this recording (a later pass writes it too): the same place.
    auto earlier = std::find_if(s.copiesMade.begin(), s.copiesMade.end(), [&](const Copy& e) {
      return e.target == c.target && e.width == c.width && e.height == c.height && e.format == c.format;
    });
    if (earlier != s.copiesMade.end()) {
      c.buffer = earlier->buffer, c.offset = earlier->offset;
    } else if (!reserve(d, s, bytes, c.buffer, c.offset)) {
      if (s.ringPending) continue;  // the thread makes the ring: the rest of the pass still counts its size
      if (s.slot >= 0) {  // a slot, but no memory for it
        report(d, "memory", "out of host-visible memory for the copies: streaming stops");
        d.streaming = false;
      }
      s.copies = false;  // every slot is held: this recording's frame is dropped
      s.skipped = true;
      return;
    }
    c.stencilOffset = c.offset + stencilAt;
    if (std::none_of(there.begin(), there.end(), [&](const VkImageMemoryBarrier& b) { return b.image == l->a->image; }))
      transitions(*l, f, there, back);  // once, when two targets pick one attachment
    auto region = [&](VkImageAspectFlags aspect, VkDeviceSize offset) {
      Region r{l->a->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, c.buffer->buffer, {}};
      const VkImageLayout was = aspect == VK_IMAGE_ASPECT_STENCIL_BIT ? l->a->stencilLayout : l->a->layout;
      if (inPlace(*l->a, was)) r.layout = VK_IMAGE_LAYOUT_GENERAL;  // copied where it is
      r.copy.bufferOffset = offset;
      r.copy.imageSubresource = {aspect, l->viewMip, l->viewLayer, 1};
      r.copy.imageExtent = {c.width, c.height, 1};
      regions.push_back(r);
    };
    if (c.stage) {  // sample for sample into the layer's image, which the unpacking after the submission reads
      const VkImageAspectFlags aspect = f.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
      regions.push_back(layerImageCopy(*l, stageImage(*c.stage), aspect, c.width, c.height));
      there.push_back(toTransferDst(stageImage(*c.stage), aspect));
    } else if (VkImage tile = tilesWanted(d, f.depth || f.stencil) && c.buffer->hostBuffer
                                  ? ringTile(d, *c.buffer, c.offset, c.format, c.width, c.height)
                                  : VK_NULL_HANDLE) {
      tileCopies(d, *l, f, c, tile, regions, there, back);
    } else {
      if (f.depth || !f.stencil) region(f.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, c.offset);
      if (f.stencil && f.depth) region(VK_IMAGE_ASPECT_STENCIL_BIT, c.stencilOffset);
    }
    if (pass.ordinal < 0) ++d.storageCopies;
    made.push_back(c);
  }
  if (s.ringPending) {  // no copies until the layer's thread has made the ring (ring.cpp reserve)
    s.copies = false;
    s.skipped = true;
    return;
  }
  // The camera's bytes and the bound buffers, each where the ring has room.
  // (a dispatch's storage images: no buffers)
  std::vector<BufferCopy> buffers;
  if (pass.ordinal >= 0)
    for (BufferCopy& b : bufferCopies(d, s, *req, !made.empty()))
      if (reserve(d, s, b.size, b.copy.buffer, b.copy.offset)) {
        b.copy.passOrdinal = pass.ordinal;
        b.copy.pass = !pass.labels.empty() ? pass.labels.back() : pass.renderPass;
        buffers.push_back(std::move(b));
      }
  if (made.empty() && buffers.empty()) return;
  const auto transfers = std::chrono::steady_clock::now();
  recordTransfers(d, cmd, there, back, regions, made, buffers);
  keep(s, made, buffers);
  const auto end = std::chrono::steady_clock::now();
  d.hookNs += uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(end - start).count());
  if (end - start > std::chrono::milliseconds(1))  // a driver making what a first copy of a kind needs
    GBL_LOG("%s %d: %zu copies took %.2f ms to record (the driver's commands %.2f ms)", pass.ordinal < 0 ? "dispatch" : "pass",
            pass.ordinal, regions.size(), std::chrono::duration<double, std::milli>(end - start).count(),
            std::chrono::duration<double, std::milli>(end - transfers).count());
}

}  // namespace gbl
