// What each descriptor set holds (descriptors.h): set layouts, then per set the buffer range or image
// view written at each binding and array element, by vkUpdateDescriptorSets (writes and copies,
// which run on into the next binding as Vulkan's do) and by update templates. Sets are forgotten
// when their pool frees, resets or destroys them: an application that allocates sets every frame
// leaves nothing behind.
#include "app/layer/descriptors.h"

#include <algorithm>

#include "app/layer/layer.h"

namespace gbl {

bool bufferDescriptor(VkDescriptorType t) {
  return t == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || t == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC ||
         t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC;
}

bool imageDescriptor(VkDescriptorType t) {
  return t == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE || t == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER ||
         t == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE || t == VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
}

namespace {

bool dynamicDescriptor(VkDescriptorType t) {
  return t == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC || t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC;
}

// The slot of (binding, element) advanced by k descriptors (a write longer than its binding goes
// on at element 0 of the next binding), or -1 when it lies past what is followed.
int64_t slotOf(const SetLayoutInfo& l, uint32_t binding, uint32_t element, uint32_t k) {
  auto b = std::lower_bound(l.bindings.begin(), l.bindings.end(), binding,
                            [](const SetLayoutInfo::Binding& x, uint32_t n) { return x.binding < n; });
  if (b == l.bindings.end() || b->binding != binding) return -1;
  const uint64_t slot = uint64_t(b->first) + element + k;
  return slot < l.total ? int64_t(slot) : -1;
}

VKAPI_ATTR VkResult VKAPI_CALL CreateDescriptorSetLayout(VkDevice device, const VkDescriptorSetLayoutCreateInfo* info,
                                                         const VkAllocationCallbacks* alloc, VkDescriptorSetLayout* layout) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.CreateDescriptorSetLayout(device, info, alloc, layout);
  if (r != VK_SUCCESS) return r;
  auto l = std::make_shared<SetLayoutInfo>();
  for (uint32_t i = 0; i < info->bindingCount; ++i) {
    const VkDescriptorSetLayoutBinding& b = info->pBindings[i];
    if (dynamicDescriptor(b.descriptorType)) l->dynamicCount += b.descriptorCount;
    if (b.descriptorCount) l->bindings.push_back({b.binding, b.descriptorType, b.descriptorCount, 0});
  }
  std::sort(l->bindings.begin(), l->bindings.end(), [](const auto& a, const auto& b) { return a.binding < b.binding; });
  for (SetLayoutInfo::Binding& b : l->bindings) {
    b.first = l->total;
    b.count = std::min(b.count, kMaxFollowed - l->total);
    l->total += b.count;
  }
  std::unique_lock lock(d.objects);
  d.setLayouts[*layout] = std::move(l);
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyDescriptorSetLayout(VkDevice device, VkDescriptorSetLayout layout,
                                                      const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  {
    std::unique_lock lock(d.objects);
    d.setLayouts.erase(layout);  // sets made with it keep their copy
  }
  d.vk.DestroyDescriptorSetLayout(device, layout, alloc);
}

VKAPI_ATTR VkResult VKAPI_CALL AllocateDescriptorSets(VkDevice device, const VkDescriptorSetAllocateInfo* info,
                                                      VkDescriptorSet* sets) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.AllocateDescriptorSets(device, info, sets);
  if (r == VK_SUCCESS) {
    std::unique_lock lock(d.objects);
    std::vector<VkDescriptorSet>& pool = d.poolSets[info->descriptorPool];
    for (uint32_t i = 0; i < info->descriptorSetCount; ++i) {
      auto l = d.setLayouts.find(info->pSetLayouts[i]);
      SetInfo& s = d.sets[sets[i]];  // a handle used before starts afresh
      s.layout = l == d.setLayouts.end() ? nullptr : l->second;
      s.slots.assign(s.layout ? s.layout->total : 0, Descriptor{});
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
    for (VkDescriptorSet s : held) d.sets.erase(s);
    d.poolSets.erase(it);
    return;
  }
  for (uint32_t i = 0; i < n; ++i) {
    d.sets.erase(sets[i]);
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

// One descriptor written: what the layer follows of it (buffers and image views; the rest: the type).
void store(SetInfo& s, int64_t slot, VkDescriptorType type, const VkDescriptorBufferInfo* b, const VkDescriptorImageInfo* i) {
  if (slot < 0) return;
  Descriptor& out = s.slots[size_t(slot)];
  out = Descriptor{};
  out.type = type;
  if (bufferDescriptor(type) && b) out.buffer = b->buffer, out.offset = b->offset, out.range = b->range;
  if (imageDescriptor(type) && i) out.view = i->imageView;
}

VKAPI_ATTR void VKAPI_CALL UpdateDescriptorSets(VkDevice device, uint32_t writeCount, const VkWriteDescriptorSet* writes,
                                                uint32_t copyCount, const VkCopyDescriptorSet* copies) {
  DeviceData& d = *deviceOf(device);
  d.vk.UpdateDescriptorSets(device, writeCount, writes, copyCount, copies);
  std::unique_lock lock(d.objects);
  for (uint32_t i = 0; i < writeCount; ++i) {
    const VkWriteDescriptorSet& w = writes[i];
    auto s = d.sets.find(w.dstSet);
    if (s == d.sets.end() || !s->second.layout) continue;
    for (uint32_t k = 0; k < w.descriptorCount; ++k)
      store(s->second, slotOf(*s->second.layout, w.dstBinding, w.dstArrayElement, k), w.descriptorType,
            bufferDescriptor(w.descriptorType) && w.pBufferInfo ? &w.pBufferInfo[k] : nullptr,
            imageDescriptor(w.descriptorType) && w.pImageInfo ? &w.pImageInfo[k] : nullptr);
  }
  for (uint32_t i = 0; i < copyCount; ++i) {
    const VkCopyDescriptorSet& c = copies[i];
    auto src = d.sets.find(c.srcSet), dst = d.sets.find(c.dstSet);
    if (src == d.sets.end() || dst == d.sets.end() || !src->second.layout || !dst->second.layout) continue;
    for (uint32_t k = 0; k < c.descriptorCount; ++k) {
      const int64_t from = slotOf(*src->second.layout, c.srcBinding, c.srcArrayElement, k);
      const int64_t to = slotOf(*dst->second.layout, c.dstBinding, c.dstArrayElement, k);
      if (to >= 0) dst->second.slots[size_t(to)] = from >= 0 ? src->second.slots[size_t(from)] : Descriptor{};
    }
  }
}

// ---- update templates

VkResult createTemplate(PFN_vkCreateDescriptorUpdateTemplate next, VkDevice device,
                        const VkDescriptorUpdateTemplateCreateInfo* info, const VkAllocationCallbacks* alloc,
                        VkDescriptorUpdateTemplate* t) {
  DeviceData& d = *deviceOf(device);
  VkResult r = next(device, info, alloc, t);
  if (r == VK_SUCCESS) {  // descriptor-set and push-descriptor templates alike
    std::unique_lock lock(d.objects);
    TemplateInfo& ti = d.templates[*t];
    ti.entries.assign(info->pDescriptorUpdateEntries, info->pDescriptorUpdateEntries + info->descriptorUpdateEntryCount);
    ti.bindPoint = info->pipelineBindPoint;
  }
  return r;
}
VKAPI_ATTR VkResult VKAPI_CALL CreateDescriptorUpdateTemplate(VkDevice device, const VkDescriptorUpdateTemplateCreateInfo* info,
                                                              const VkAllocationCallbacks* alloc, VkDescriptorUpdateTemplate* t) {
  return createTemplate(deviceOf(device)->vk.CreateDescriptorUpdateTemplate, device, info, alloc, t);
}
VKAPI_ATTR VkResult VKAPI_CALL CreateDescriptorUpdateTemplateKHR(VkDevice device, const VkDescriptorUpdateTemplateCreateInfo* info,
                                                                 const VkAllocationCallbacks* alloc, VkDescriptorUpdateTemplate* t) {
  return createTemplate(deviceOf(device)->vk.CreateDescriptorUpdateTemplateKHR, device, info, alloc, t);
}

void destroyTemplate(PFN_vkDestroyDescriptorUpdateTemplate next, VkDevice device, VkDescriptorUpdateTemplate t,
                     const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  {
    std::unique_lock lock(d.objects);
    d.templates.erase(t);
  }
  next(device, t, alloc);
}
VKAPI_ATTR void VKAPI_CALL DestroyDescriptorUpdateTemplate(VkDevice device, VkDescriptorUpdateTemplate t, const VkAllocationCallbacks* a) {
  destroyTemplate(deviceOf(device)->vk.DestroyDescriptorUpdateTemplate, device, t, a);
}
VKAPI_ATTR void VKAPI_CALL DestroyDescriptorUpdateTemplateKHR(VkDevice device, VkDescriptorUpdateTemplate t, const VkAllocationCallbacks* a) {
  destroyTemplate(deviceOf(device)->vk.DestroyDescriptorUpdateTemplateKHR, device, t, a);
}

// The template's entries read from the application's data as vkUpdateDescriptorSets's writes are.
void updateWithTemplate(PFN_vkUpdateDescriptorSetWithTemplate next, VkDevice device, VkDescriptorSet set,
                        VkDescriptorUpdateTemplate t, const void* data) {
  DeviceData& d = *deviceOf(device);
  next(device, set, t, data);
  std::unique_lock lock(d.objects);
  auto tmpl = d.templates.find(t);
  auto s = d.sets.find(set);
  if (tmpl == d.templates.end() || s == d.sets.end() || !s->second.layout || !data) return;
  const auto* bytes = static_cast<const uint8_t*>(data);
  for (const VkDescriptorUpdateTemplateEntry& e : tmpl->second.entries) {
    if (e.descriptorType == VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK) continue;  // bytes, not descriptors
    for (uint32_t k = 0; k < e.descriptorCount; ++k) {
      const uint8_t* at = bytes + e.offset + size_t(k) * e.stride;
      store(s->second, slotOf(*s->second.layout, e.dstBinding, e.dstArrayElement, k), e.descriptorType,
            reinterpret_cast<const VkDescriptorBufferInfo*>(at), reinterpret_cast<const VkDescriptorImageInfo*>(at));
    }
  }
}
VKAPI_ATTR void VKAPI_CALL UpdateDescriptorSetWithTemplate(VkDevice device, VkDescriptorSet set, VkDescriptorUpdateTemplate t,
                                                           const void* data) {
  updateWithTemplate(deviceOf(device)->vk.UpdateDescriptorSetWithTemplate, device, set, t, data);
}
VKAPI_ATTR void VKAPI_CALL UpdateDescriptorSetWithTemplateKHR(VkDevice device, VkDescriptorSet set, VkDescriptorUpdateTemplate t,
                                                              const void* data) {
  updateWithTemplate(deviceOf(device)->vk.UpdateDescriptorSetWithTemplateKHR, device, set, t, data);
}

}  // namespace

// VK_WHOLE_SIZE as the bytes from the offset to the buffer's end (0 when the layer does not know it).
void resolveRange(const DeviceData& d, BoundDescriptor& o) {
  if (!o.buffer || o.range != VK_WHOLE_SIZE) return;
  auto info = d.buffers.find(o.buffer);
  o.range = info == d.buffers.end() || info->second.size < o.offset ? 0 : info->second.size - o.offset;
}

void boundDescriptors(const DeviceData& d, uint32_t number, const BoundSet& bound, std::vector<BoundDescriptor>& out) {
  if (bound.pushed) {
    for (BoundDescriptor b : *bound.pushed) {
      b.set = number;
      resolveRange(d, b);
      out.push_back(b);
    }
    return;
  }
  auto s = d.sets.find(bound.set);
  if (s == d.sets.end() || !s->second.layout) return;
  size_t dynamic = 0;  // dynamic offsets go to the dynamic descriptors in binding order
  for (const SetLayoutInfo::Binding& b : s->second.layout->bindings)
    for (uint32_t e = 0; e < b.count; ++e) {
      const Descriptor& desc = s->second.slots[b.first + e];
      const bool isDynamic = dynamicDescriptor(b.type);
      const VkDeviceSize extra = isDynamic && dynamic < bound.dynamicOffsets.size() ? bound.dynamicOffsets[dynamic] : 0;
      dynamic += isDynamic;
      if (desc.type == VK_DESCRIPTOR_TYPE_MAX_ENUM) continue;
      BoundDescriptor o{number, b.binding, e, desc.type, desc.buffer, desc.offset + extra, desc.range, desc.view};
      resolveRange(d, o);
      out.push_back(o);
    }
}

std::vector<BoundDescriptor> pushedDescriptors(uint32_t count, const VkWriteDescriptorSet* writes) {
  std::vector<BoundDescriptor> out;
  for (uint32_t i = 0; i < count; ++i) {
    const VkWriteDescriptorSet& w = writes[i];
    for (uint32_t k = 0; k < w.descriptorCount; ++k) {
      BoundDescriptor b{0, w.dstBinding, w.dstArrayElement + k, w.descriptorType, VK_NULL_HANDLE, 0, 0, VK_NULL_HANDLE};
      if (bufferDescriptor(w.descriptorType) && w.pBufferInfo)
        b.buffer = w.pBufferInfo[k].buffer, b.offset = w.pBufferInfo[k].offset, b.range = w.pBufferInfo[k].range;
      if (imageDescriptor(w.descriptorType) && w.pImageInfo) b.view = w.pImageInfo[k].imageView;
      out.push_back(b);
    }
  }
  return out;
}

std::vector<BoundDescriptor> pushedDescriptors(DeviceData& d, VkDescriptorUpdateTemplate t, const void* data) {
  std::vector<BoundDescriptor> out;
  std::shared_lock lock(d.objects);
  auto tmpl = d.templates.find(t);
  if (tmpl == d.templates.end() || !data) return out;
  for (const VkDescriptorUpdateTemplateEntry& e : tmpl->second.entries)
    for (uint32_t k = 0; k < e.descriptorCount && e.descriptorType != VK_DESCRIPTOR_TYPE_INLINE_UNIFORM_BLOCK; ++k) {
      const uint8_t* at = static_cast<const uint8_t*>(data) + e.offset + size_t(k) * e.stride;
      BoundDescriptor b{0, e.dstBinding, e.dstArrayElement + k, e.descriptorType, VK_NULL_HANDLE, 0, 0, VK_NULL_HANDLE};
      if (bufferDescriptor(e.descriptorType)) {
        const auto* info = reinterpret_cast<const VkDescriptorBufferInfo*>(at);
        b.buffer = info->buffer, b.offset = info->offset, b.range = info->range;
      }
      if (imageDescriptor(e.descriptorType)) b.view = reinterpret_cast<const VkDescriptorImageInfo*>(at)->imageView;
      out.push_back(b);
    }
  return out;
}

std::vector<BoundSet> splitDynamicOffsets(DeviceData& d, uint32_t count, const VkDescriptorSet* sets, uint32_t dynamicCount,
                                          const uint32_t* dynamicOffsets) {
  std::vector<BoundSet> out(count);
  std::shared_lock lock(d.objects);
  uint32_t used = 0;
  for (uint32_t i = 0; i < count; ++i) {
    out[i].set = sets[i];
    auto s = d.sets.find(sets[i]);
    const uint32_t n = s == d.sets.end() || !s->second.layout ? 0 : s->second.layout->dynamicCount;
    for (uint32_t k = 0; k < n && used < dynamicCount; ++k) out[i].dynamicOffsets.push_back(dynamicOffsets[used++]);
  }
  return out;
}

std::vector<Hook> descriptorHooks() {
  return {GBL_HOOK(CreateDescriptorSetLayout),       GBL_HOOK(DestroyDescriptorSetLayout),
          GBL_HOOK(AllocateDescriptorSets),          GBL_HOOK(FreeDescriptorSets),
          GBL_HOOK(ResetDescriptorPool),             GBL_HOOK(DestroyDescriptorPool),
          GBL_HOOK(UpdateDescriptorSets),            GBL_HOOK(CreateDescriptorUpdateTemplate),
          GBL_HOOK(CreateDescriptorUpdateTemplateKHR), GBL_HOOK(DestroyDescriptorUpdateTemplate),
          GBL_HOOK(DestroyDescriptorUpdateTemplateKHR), GBL_HOOK(UpdateDescriptorSetWithTemplate),
          GBL_HOOK(UpdateDescriptorSetWithTemplateKHR)};
}

}  // namespace gbl
