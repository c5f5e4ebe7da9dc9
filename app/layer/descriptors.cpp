// Which buffers each descriptor set holds, so that the camera's buffer is the one of its name a
// descriptor set bound where the pass runs (record.cpp). Sets are forgotten when their pool frees,
// resets or destroys them: an application that allocates sets every frame leaves nothing behind.
#include <algorithm>

#include "app/layer/layer.h"

namespace gbl {

namespace {

bool bufferDescriptor(VkDescriptorType t) {
  return t == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || t == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC ||
         t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC;
}

void hold(std::vector<VkBuffer>& held, VkBuffer b) {
  if (std::find(held.begin(), held.end(), b) == held.end() && held.size() < 64) held.push_back(b);
}

VKAPI_ATTR VkResult VKAPI_CALL AllocateDescriptorSets(VkDevice device, const VkDescriptorSetAllocateInfo* info,
                                                      VkDescriptorSet* sets) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.AllocateDescriptorSets(device, info, sets);
  if (r == VK_SUCCESS) {
    std::unique_lock lock(d.objects);
    std::vector<VkDescriptorSet>& pool = d.poolSets[info->descriptorPool];
    for (uint32_t i = 0; i < info->descriptorSetCount; ++i) {
      d.setBuffers.erase(sets[i]);  // a handle used before
      pool.push_back(sets[i]);
    }
  }
  return r;
}

void forgetSets(DeviceData& d, VkDescriptorPool pool, const VkDescriptorSet* sets, uint32_t n) {
  std::unique_lock lock(d.objects);
  auto it = d.poolSets.find(pool);
  if (it == d.poolSets.end()) return;
  std::vector<VkDescriptorSet>& held = it->second;
  if (!sets) {  // the whole pool
    for (VkDescriptorSet s : held) d.setBuffers.erase(s);
    d.poolSets.erase(it);
    return;
  }
  for (uint32_t i = 0; i < n; ++i) {
    d.setBuffers.erase(sets[i]);
    std::erase(held, sets[i]);
  }
}

VKAPI_ATTR VkResult VKAPI_CALL FreeDescriptorSets(VkDevice device, VkDescriptorPool pool, uint32_t n, const VkDescriptorSet* sets) {
  DeviceData& d = *deviceOf(device);
  forgetSets(d, pool, sets, n);
  return d.vk.FreeDescriptorSets(device, pool, n, sets);
}

VKAPI_ATTR VkResult VKAPI_CALL ResetDescriptorPool(VkDevice device, VkDescriptorPool pool, VkDescriptorPoolResetFlags flags) {
  DeviceData& d = *deviceOf(device);
  forgetSets(d, pool, nullptr, 0);
  return d.vk.ResetDescriptorPool(device, pool, flags);
}

VKAPI_ATTR void VKAPI_CALL DestroyDescriptorPool(VkDevice device, VkDescriptorPool pool, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  forgetSets(d, pool, nullptr, 0);
  d.vk.DestroyDescriptorPool(device, pool, alloc);
}

VKAPI_ATTR void VKAPI_CALL UpdateDescriptorSets(VkDevice device, uint32_t writeCount, const VkWriteDescriptorSet* writes,
                                                uint32_t copyCount, const VkCopyDescriptorSet* copies) {
  DeviceData& d = *deviceOf(device);
  d.vk.UpdateDescriptorSets(device, writeCount, writes, copyCount, copies);
  std::unique_lock lock(d.objects);
  for (uint32_t i = 0; i < writeCount; ++i) {
    if (!bufferDescriptor(writes[i].descriptorType) || !writes[i].pBufferInfo) continue;
    std::vector<VkBuffer>& held = d.setBuffers[writes[i].dstSet];
    for (uint32_t k = 0; k < writes[i].descriptorCount; ++k) hold(held, writes[i].pBufferInfo[k].buffer);
  }
  for (uint32_t i = 0; i < copyCount; ++i) {
    auto src = d.setBuffers.find(copies[i].srcSet);
    if (src == d.setBuffers.end()) continue;
    const std::vector<VkBuffer> from = src->second;
    for (VkBuffer b : from) hold(d.setBuffers[copies[i].dstSet], b);
  }
}

}  // namespace

std::vector<Hook> descriptorHooks() {
  return {GBL_HOOK(AllocateDescriptorSets), GBL_HOOK(FreeDescriptorSets), GBL_HOOK(ResetDescriptorPool),
          GBL_HOOK(DestroyDescriptorPool), GBL_HOOK(UpdateDescriptorSets)};
}

}  // namespace gbl
