// What the layer knows of descriptor sets (descriptors.cpp): each set's layout and, per descriptor,
// the buffer range or image view written into it (vkUpdateDescriptorSets, copies, update
// templates), so that the sets a pass binds say which buffers its draws see (the camera, the
// bound buffers a receiver asks for) and which images they may read (--suggest, structure.cpp).
#pragma once
#include <vulkan/vulkan.h>

#include <memory>
#include <vector>

namespace gbl {

struct DeviceData;

// A set layout's bindings in binding order, each with its first descriptor in SetInfo::slots.
struct SetLayoutInfo {
  struct Binding {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    uint32_t count = 0;  // followed (a huge bindless array: its first kMaxFollowed descriptors)
    uint32_t first = 0;
  };
  std::vector<Binding> bindings;
  uint32_t total = 0;         // descriptors followed
  uint32_t dynamicCount = 0;  // dynamic buffer descriptors: the dynamic offsets a bind of it takes
};
// Descriptors followed per set: a bindless table is followed only this far (memory per set).
constexpr uint32_t kMaxFollowed = 4096;

struct Descriptor {
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;  // MAX_ENUM: never written
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, range = 0;
  VkImageView view = VK_NULL_HANDLE;
};
struct SetInfo {
  std::shared_ptr<const SetLayoutInfo> layout;  // outlives a layout the application destroys
  std::vector<Descriptor> slots;
};
struct TemplateInfo {
  std::vector<VkDescriptorUpdateTemplateEntry> entries;
  VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;  // a push-descriptor template's
};

bool bufferDescriptor(VkDescriptorType t);  // uniform or storage buffer, dynamic or not
bool imageDescriptor(VkDescriptorType t);   // sampled, combined image sampler, storage image, input attachment

// One written descriptor of a bound set as a draw sees it: the dynamic offset applied, the range
// resolved (VK_WHOLE_SIZE: to the buffer's end, when the layer knows its size).
struct BoundDescriptor {
  uint32_t set = 0, binding = 0, index = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0, range = 0;
  VkImageView view = VK_NULL_HANDLE;
};
// A set bound by vkCmdBindDescriptorSets, with its share of the dynamic offsets; or the
// descriptors vkCmdPushDescriptorSetKHR pushed at that set number (`pushed`, no set).
struct BoundSet {
  VkDescriptorSet set = VK_NULL_HANDLE;
  std::vector<uint32_t> dynamicOffsets;
  std::shared_ptr<const std::vector<BoundDescriptor>> pushed;
  bool fresh = false;  // bound since the open pass's last draw (structure.cpp: what its draws see)
  bool bound() const { return set || pushed; }
};
// The descriptors of `bound` at set number `number`, in binding order (the caller holds d.objects).
void boundDescriptors(const DeviceData& d, uint32_t number, const BoundSet& bound, std::vector<BoundDescriptor>& out);
// The descriptors vkCmdPushDescriptorSetKHR's writes push (array elements as given: push sets have
// no layout the layer follows), or vkCmdPushDescriptorSetWithTemplateKHR's data (takes d.objects).
std::vector<BoundDescriptor> pushedDescriptors(uint32_t count, const VkWriteDescriptorSet* writes);
std::vector<BoundDescriptor> pushedDescriptors(DeviceData& d, VkDescriptorUpdateTemplate t, const void* data);
// Splits vkCmdBindDescriptorSets's dynamic offsets among its sets, by their layouts (takes d.objects).
std::vector<BoundSet> splitDynamicOffsets(DeviceData& d, uint32_t count, const VkDescriptorSet* sets,
                                          uint32_t dynamicCount, const uint32_t* dynamicOffsets);

}  // namespace gbl
