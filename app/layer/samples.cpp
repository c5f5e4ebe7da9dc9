// Every sample of a multisampled attachment (docs/attach.md "MSAA"). A multisampled image cannot be
// copied to a buffer: at the pass's end the application's command buffer copies it (vkCmdCopyImage,
// sample for sample) into an image of the layer's, and right after the application's submission a
// recording of the layer's own runs shaders/layer_samples.comp, which writes each sample's bits into
// the ring, one plane per sample, before the layer's fence. The application's images, layouts and
// bound state are never touched by the shader. The same batch downloads a staged ring where the
// layer has no queue of its own (staging.cpp).
#include <algorithm>
#include <cstring>

#include "app/layer/layer.h"
#include "layer_samples_colour.spv.h"
#include "layer_samples_depth.spv.h"

namespace gbl {

struct SampleStage {
  DeviceData* d = nullptr;
  VkImage app = VK_NULL_HANDLE;  // the application's image, and which of its subresources
  uint32_t mip = 0, layer = 0;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;  // the application's (depth) or a uint format of its size (colour)
  VkFormat appFormat = VK_FORMAT_UNDEFINED;
  bool depth = false;
  uint32_t depthKind = 0;  // layer_samples.comp: 0 float32 bits, 1 unorm16, 2 unorm24
  uint32_t texelBytes = 0, width = 0, height = 0, samples = 1;
  ~SampleStage() {
    if (view) d->vk.DestroyImageView(d->device, view, nullptr);
    if (image) d->vk.DestroyImage(d->device, image, nullptr);
    if (memory) d->vk.FreeMemory(d->device, memory, nullptr);
  }
};

struct SampleState {
  std::mutex lock;
  bool tried = false, ready = false;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkPipeline colour = VK_NULL_HANDLE, depth = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::unordered_map<uint32_t, VkCommandPool> commandPools;  // per queue family
  struct InFlight {
    VkCommandPool pool;
    VkCommandBuffer cmd;
    std::vector<VkDescriptorSet> sets;
  };
  std::unordered_map<VkFence, InFlight> inFlight;
  std::vector<std::shared_ptr<SampleStage>> stages;  // one per application subresource copied
};

namespace {

struct Params {  // layer_samples.comp's push constants
  uint32_t width, height, samples, texelBytes, depthKind, firstWord, planeWords;
};

SampleState& state(DeviceData& d) {
  if (!d.sampling) d.sampling = new SampleState;
  return *d.sampling;
}

VkFormat uintFormat(uint32_t bytes) {
  switch (bytes) {
    case 1: return VK_FORMAT_R8_UINT;
    case 2: return VK_FORMAT_R16_UINT;
    case 4: return VK_FORMAT_R32_UINT;
    case 8: return VK_FORMAT_R32G32_UINT;
    case 16: return VK_FORMAT_R32G32B32A32_UINT;
    default: return VK_FORMAT_UNDEFINED;
  }
}

// The format the layer's image has: a depth format as it is (depth copies need the same format),
// colour bits through an unsigned-integer format of the same size (one compatibility class).
VkFormat stageFormat(const FormatInfo& f) { return f.depth ? f.format : uintFormat(f.bytes); }

uint32_t depthKind(VkFormat f) {
  if (f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D16_UNORM_S8_UINT) return 1;
  if (f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D24_UNORM_S8_UINT) return 2;
  return 0;
}

VkShaderModule module(DeviceData& d, const uint32_t* code, size_t bytes) {
  VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  mi.codeSize = bytes;
  mi.pCode = code;
  VkShaderModule m = VK_NULL_HANDLE;
  return d.vk.CreateShaderModule(d.device, &mi, nullptr, &m) == VK_SUCCESS ? m : VK_NULL_HANDLE;
}

// The sampler, set layout, pipelines and descriptor pool, made once (under the state's lock).
bool makePipelines(DeviceData& d, SampleState& s) {
  if (s.tried) return s.ready;
  s.tried = true;
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};  // texelFetch ignores it; integer views need nearest
  if (d.vk.CreateSampler(d.device, &si, nullptr, &s.sampler) != VK_SUCCESS) return false;
  VkDescriptorSetLayoutBinding b[2] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, &s.sampler},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 2;
  li.pBindings = b;
  if (d.vk.CreateDescriptorSetLayout(d.device, &li, nullptr, &s.setLayout) != VK_SUCCESS) return false;
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(Params)};
  VkPipelineLayoutCreateInfo pi{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pi.setLayoutCount = 1;
  pi.pSetLayouts = &s.setLayout;
  pi.pushConstantRangeCount = 1;
  pi.pPushConstantRanges = &range;
  if (d.vk.CreatePipelineLayout(d.device, &pi, nullptr, &s.pipelineLayout) != VK_SUCCESS) return false;
  auto pipeline = [&](const uint32_t* code, size_t bytes, VkPipeline& out) {
    VkShaderModule m = module(d, code, bytes);
    if (!m) return false;
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, m, "main", nullptr};
    ci.layout = s.pipelineLayout;
    const bool ok = d.vk.CreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &ci, nullptr, &out) == VK_SUCCESS;
    d.vk.DestroyShaderModule(d.device, m, nullptr);
    return ok;
  };
  if (!pipeline(spv_layer_samples_colour, sizeof(spv_layer_samples_colour), s.colour) ||
      !pipeline(spv_layer_samples_depth, sizeof(spv_layer_samples_depth), s.depth))
    return false;
  constexpr uint32_t kSets = 256;  // targets x frames in flight (16 fences at most, ring.cpp)
  VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kSets}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kSets}};
  VkDescriptorPoolCreateInfo dp{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dp.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  dp.maxSets = kSets;
  dp.poolSizeCount = 2;
  dp.pPoolSizes = sizes;
  if (d.vk.CreateDescriptorPool(d.device, &dp, nullptr, &s.pool) != VK_SUCCESS) return false;
  return s.ready = true;
}

uint32_t familyOf(DeviceData& d, VkQueue queue) {
  {
    std::shared_lock lock(d.objects);
    auto it = d.queueFamilies.find(queue);
    if (it != d.queueFamilies.end()) return it->second;
  }
  return d.createdFamilies.size() == 1 ? d.createdFamilies[0] : UINT32_MAX;
}

VkCommandPool commandPool(DeviceData& d, SampleState& s, uint32_t family) {
  auto it = s.commandPools.find(family);
  if (it != s.commandPools.end()) return it->second;
  VkCommandPoolCreateInfo ci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  ci.queueFamilyIndex = family;
  VkCommandPool pool = VK_NULL_HANDLE;
  if (d.vk.CreateCommandPool(d.device, &ci, nullptr, &pool) != VK_SUCCESS) return VK_NULL_HANDLE;
  return s.commandPools[family] = pool;
}

// One target's unpacking: its image readable by the shader, the shader over every word of every plane.
bool recordUnpack(DeviceData& d, SampleState& s, VkCommandBuffer cmd, const Copy& c, std::vector<VkDescriptorSet>& sets) {
  const SampleStage& st = *c.stage;
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = s.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &s.setLayout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (d.vk.AllocateDescriptorSets(d.device, &ai, &set) != VK_SUCCESS) return false;
  sets.push_back(set);
  VkDescriptorImageInfo image{VK_NULL_HANDLE, st.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo ring{c.buffer->buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  w[0].dstSet = w[1].dstSet = set;
  w[0].descriptorCount = w[1].descriptorCount = 1;
  w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w[0].pImageInfo = &image;
  w[1].dstBinding = 1;
  w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w[1].pBufferInfo = &ring;
  d.vk.UpdateDescriptorSets(d.device, 2, w, 0, nullptr);
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;  // the application's recording copied into it
  b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = st.image;
  b.subresourceRange = {VkImageAspectFlags(st.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1};
  d.vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr,
                          1, &b);
  d.vk.CmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, st.depth ? s.depth : s.colour);
  d.vk.CmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelineLayout, 0, 1, &set, 0, nullptr);
  const uint32_t planeWords = uint32_t(c.sampleStride / 4);
  const Params p{st.width, st.height, st.samples, st.texelBytes, st.depthKind, uint32_t(c.offset / 4), planeWords};
  d.vk.CmdPushConstants(cmd, s.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(p), &p);
  const uint32_t groups = (planeWords + 63) / 64, x = std::min(groups, 4096u);
  d.vk.CmdDispatch(cmd, x, st.samples, (groups + x - 1) / x);
  return true;
}

}  // namespace

std::string sampleRefusal(DeviceData& d, const ImageInfo& image) {
  const FormatInfo& f = formatInfo(image.format);
  if (f.depth && f.stencil)
    return "is multisampled " + formatName(image.format) +
           ": gblens streams the samples of a depth-only or colour attachment (not of a stencil aspect)";
  const VkFormat stage = stageFormat(f);
  VkImageFormatProperties props{};
  if (stage == VK_FORMAT_UNDEFINED || !d.instance->imageFormatProperties ||
      d.instance->imageFormatProperties(d.physical, stage, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, 0, &props) != VK_SUCCESS ||
      !(props.sampleCounts & image.samples))
    return "is multisampled (" + std::to_string(int(image.samples)) + " samples) and this device cannot sample " +
           formatName(stage) + " with as many: its samples cannot be read";
  if (d.createdFamilies.empty()) return "is multisampled and the device was made without queues the layer can use";
  return "";
}

std::shared_ptr<SampleStage> sampleStage(DeviceData& d, VkImage app, uint32_t mip, uint32_t layer, const ImageInfo& info) {
  SampleState& s = state(d);
  const FormatInfo& f = formatInfo(info.format);
  const uint32_t w = std::max(1u, info.extent.width >> mip), h = std::max(1u, info.extent.height >> mip);
  std::lock_guard lock(s.lock);
  for (auto& st : s.stages)
    if (st->app == app && st->mip == mip && st->layer == layer) {
      if (st->appFormat == info.format && st->width == w && st->height == h && st->samples == uint32_t(info.samples)) return st;
      st.reset();  // the handle was reused for another image: a new stage (recordings in flight keep the old)
    }
  std::erase(s.stages, nullptr);
  auto st = std::make_shared<SampleStage>();
  st->d = &d, st->app = app, st->mip = mip, st->layer = layer;
  st->appFormat = info.format;
  st->format = stageFormat(f);
  st->depth = f.depth;
  st->depthKind = depthKind(info.format);
  st->texelBytes = f.bytes;
  st->width = w, st->height = h, st->samples = uint32_t(info.samples);
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = st->format;
  ci.extent = {w, h, 1};
  ci.mipLevels = ci.arrayLayers = 1;
  ci.samples = info.samples;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (d.vk.CreateImage(d.device, &ci, nullptr, &st->image) != VK_SUCCESS) return nullptr;
  VkMemoryRequirements req{};
  d.vk.GetImageMemoryRequirements(d.device, st->image, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = deviceLocalMemoryType(d, req.memoryTypeBits);
  if (ai.memoryTypeIndex == UINT32_MAX || d.vk.AllocateMemory(d.device, &ai, nullptr, &st->memory) != VK_SUCCESS ||
      d.vk.BindImageMemory(d.device, st->image, st->memory, 0) != VK_SUCCESS)
    return nullptr;
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = st->image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = st->format;
  vi.subresourceRange = {VkImageAspectFlags(f.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1};
  if (d.vk.CreateImageView(d.device, &vi, nullptr, &st->view) != VK_SUCCESS) return nullptr;
  d.ringBytes += req.size;  // the layer's memory on the device, as the ring's is counted
  s.stages.push_back(st);
  return st;
}

VkImage stageImage(const SampleStage& stage) { return stage.image; }

VkResult submitFence(DeviceData& d, VkQueue queue, const std::vector<Copy>& copies, const std::vector<Copy>& download,
                     VkFence fence) {
  std::vector<const Copy*> multi;
  for (const Copy& c : copies)
    if (c.samples > 1 && c.stage) multi.push_back(&c);
  if (multi.empty() && download.empty()) return d.vk.QueueSubmit(queue, 0, nullptr, fence);
  SampleState& s = state(d);
  std::lock_guard lock(s.lock);
  const uint32_t family = familyOf(d, queue);
  VkCommandPool pool = family == UINT32_MAX || (!multi.empty() && !makePipelines(d, s)) ? VK_NULL_HANDLE : commandPool(d, s, family);
  if (!pool) {
    report(d, "samples:pipeline", "multisampled targets: the layer could not make its unpacking shader on this queue");
    return VK_ERROR_INITIALIZATION_FAILED;
  }
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (d.vk.AllocateCommandBuffers(d.device, &ai, &cmd) != VK_SUCCESS) return VK_ERROR_OUT_OF_HOST_MEMORY;
  if (d.setLoaderData) d.setLoaderData(d.device, cmd);  // a dispatchable object the loader did not make
  else *reinterpret_cast<void**>(cmd) = *reinterpret_cast<void**>(d.device);
  SampleState::InFlight f{pool, cmd, {}};
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  d.vk.BeginCommandBuffer(cmd, &bi);
  bool ok = true;
  for (const Copy* c : multi) ok = ok && recordUnpack(d, s, cmd, *c, f.sets);
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  if (!multi.empty())
    d.vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                            nullptr);
  if (!download.empty()) recordDownload(d, cmd, download);  // after the unpacking: its planes are in the ring
  d.vk.EndCommandBuffer(cmd);
  VkResult r = VK_ERROR_OUT_OF_POOL_MEMORY;
  if (ok) {
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    r = d.vk.QueueSubmit(queue, 1, &si, fence);
  }
  if (r == VK_SUCCESS) {
    s.inFlight[fence] = std::move(f);
  } else {
    if (!f.sets.empty()) d.vk.FreeDescriptorSets(d.device, s.pool, uint32_t(f.sets.size()), f.sets.data());
    d.vk.FreeCommandBuffers(d.device, pool, 1, &cmd);
  }
  return r;
}

void releaseSamples(DeviceData& d, VkFence fence) {
  if (!d.sampling) return;
  SampleState& s = *d.sampling;
  std::lock_guard lock(s.lock);
  auto it = s.inFlight.find(fence);
  if (it == s.inFlight.end()) return;
  d.vk.WaitForFences(d.device, 1, &fence, VK_TRUE, UINT64_MAX);  // normally signalled already (a frame read)
  if (!it->second.sets.empty())
    d.vk.FreeDescriptorSets(d.device, s.pool, uint32_t(it->second.sets.size()), it->second.sets.data());
  d.vk.FreeCommandBuffers(d.device, it->second.pool, 1, &it->second.cmd);
  s.inFlight.erase(it);
}

void destroySamples(DeviceData& d) {
  if (!d.sampling) return;
  SampleState& s = *d.sampling;
  for (auto& [fence, f] : s.inFlight) d.vk.FreeCommandBuffers(d.device, f.pool, 1, &f.cmd);
  for (auto& [family, pool] : s.commandPools) d.vk.DestroyCommandPool(d.device, pool, nullptr);
  if (s.pool) d.vk.DestroyDescriptorPool(d.device, s.pool, nullptr);
  for (VkPipeline p : {s.colour, s.depth})
    if (p) d.vk.DestroyPipeline(d.device, p, nullptr);
  if (s.pipelineLayout) d.vk.DestroyPipelineLayout(d.device, s.pipelineLayout, nullptr);
  if (s.setLayout) d.vk.DestroyDescriptorSetLayout(d.device, s.setLayout, nullptr);
  if (s.sampler) d.vk.DestroySampler(d.device, s.sampler, nullptr);
  s.stages.clear();  // the recordings that copied into them are gone (the device is idle)
  delete d.sampling;
  d.sampling = nullptr;
}

namespace {

VKAPI_ATTR void VKAPI_CALL GetDeviceQueue(VkDevice device, uint32_t family, uint32_t index, VkQueue* queue) {
  DeviceData& d = *deviceOf(device);
  d.vk.GetDeviceQueue(device, family, index, queue);
  std::unique_lock lock(d.objects);
  d.queueFamilies[*queue] = family;
}

VKAPI_ATTR void VKAPI_CALL GetDeviceQueue2(VkDevice device, const VkDeviceQueueInfo2* info, VkQueue* queue) {
  DeviceData& d = *deviceOf(device);
  d.vk.GetDeviceQueue2(device, info, queue);
  std::unique_lock lock(d.objects);
  d.queueFamilies[*queue] = info->queueFamilyIndex;
}

}  // namespace

std::vector<Hook> queueHooks() { return {GBL_HOOK(GetDeviceQueue), GBL_HOOK(GetDeviceQueue2)}; }

}  // namespace gbl
