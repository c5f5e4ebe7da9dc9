// The gblens Vulkan layer (VK_LAYER_GBLENS_live, `gblens attach`): what it follows of the
// application (images, views, framebuffers, render passes, buffers, descriptor sets, debug names,
// labels, command buffers), the next layer's functions, the ring its copies land in (ring.h) and the
// stream to the receiver.
// Shared by the layer's files; docs/attach.md describes the whole.
#pragma once
#include <vulkan/vk_layer.h>
#include <vulkan/vulkan.h>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <shared_mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "app/layer/descriptors.h"
#include "app/layer/ring.h"

namespace gbl {

// The next layer's device functions: forwarded to, or called by the layer itself.
#define GBL_DEVICE_FUNCTIONS(X)                                                                                       \
  X(GetDeviceProcAddr) X(DestroyDevice) X(CreateImage) X(DestroyImage) X(CreateImageView) X(DestroyImageView)          \
  X(CreateFramebuffer) X(DestroyFramebuffer) X(CreateRenderPass) X(CreateRenderPass2) X(CreateRenderPass2KHR)          \
  X(DestroyRenderPass) X(CreateSwapchainKHR) X(DestroySwapchainKHR) X(GetSwapchainImagesKHR) X(QueuePresentKHR)        \
  X(CreateBuffer) X(DestroyBuffer) X(BindBufferMemory) X(BindBufferMemory2) X(BindBufferMemory2KHR) X(MapMemory)       \
  X(UnmapMemory) X(FreeMemory) X(AllocateDescriptorSets) X(UpdateDescriptorSets) X(CmdBindDescriptorSets)              \
  X(FreeDescriptorSets) X(ResetDescriptorPool) X(DestroyDescriptorPool)                                                \
  X(AllocateCommandBuffers) X(FreeCommandBuffers) X(BeginCommandBuffer) X(EndCommandBuffer) X(ResetCommandBuffer)     \
  X(ResetCommandPool) X(DestroyCommandPool) X(CmdBeginRenderPass) X(CmdBeginRenderPass2) X(CmdBeginRenderPass2KHR)    \
  X(CmdEndRenderPass) X(CmdEndRenderPass2) X(CmdEndRenderPass2KHR) X(CmdBeginRendering) X(CmdBeginRenderingKHR)       \
  X(CmdEndRendering) X(CmdEndRenderingKHR) X(CmdBeginDebugUtilsLabelEXT) X(CmdEndDebugUtilsLabelEXT)                  \
  X(SetDebugUtilsObjectNameEXT) X(QueueSubmit) X(QueueSubmit2) X(QueueSubmit2KHR) X(CmdPipelineBarrier)               \
  X(CmdCopyImageToBuffer) X(CmdCopyBuffer) X(CreateFence) X(DestroyFence) X(ResetFences) X(WaitForFences)              \
  X(GetFenceStatus) X(AllocateMemory) X(GetBufferMemoryRequirements) X(InvalidateMappedMemoryRanges) X(DeviceWaitIdle)     \
  X(GetMemoryHostPointerPropertiesEXT) X(CmdUpdateBuffer) X(CreateDescriptorSetLayout) X(DestroyDescriptorSetLayout)      \
  X(CreateDescriptorUpdateTemplate) X(CreateDescriptorUpdateTemplateKHR) X(DestroyDescriptorUpdateTemplate)              \
  X(DestroyDescriptorUpdateTemplateKHR) X(UpdateDescriptorSetWithTemplate) X(UpdateDescriptorSetWithTemplateKHR)         \
  X(CmdPushConstants) X(CmdDispatch) X(CmdDispatchIndirect) X(CmdDispatchBase) X(CmdDispatchBaseKHR) X(CmdCopyImage)     \
  X(CmdCopyImage2) X(CmdCopyImage2KHR) X(CmdBlitImage) X(CmdBlitImage2) X(CmdBlitImage2KHR) X(CmdResolveImage)          \
  X(CmdResolveImage2) X(CmdResolveImage2KHR) X(CmdCopyImageToBuffer2) X(CmdCopyImageToBuffer2KHR)                 \
  X(CmdPushDescriptorSetKHR) X(CmdPushDescriptorSetWithTemplateKHR) X(CmdDraw) X(CmdDrawIndexed) X(CmdDrawIndirect)  \
  X(CmdDrawIndexedIndirect) X(CmdDrawIndirectCount) X(CmdDrawIndirectCountKHR) X(CmdDrawIndexedIndirectCount)         \
  X(CmdDrawIndexedIndirectCountKHR) X(CmdDrawMeshTasksEXT) X(CmdDrawMeshTasksIndirectEXT)                            \
  X(GetDeviceQueue) X(GetDeviceQueue2) X(GetImageMemoryRequirements) X(BindImageMemory) X(CreateSampler)               \
  X(DestroySampler) X(CreateShaderModule) X(DestroyShaderModule) X(CreatePipelineLayout) X(DestroyPipelineLayout)      \
  X(CreateComputePipelines) X(DestroyPipeline) X(CreateDescriptorPool) X(CreateCommandPool) X(CmdBindPipeline)        \
  X(CmdClearColorImage) X(CmdClearDepthStencilImage) X(CmdCopyBufferToImage) X(CmdCopyBufferToImage2)                 \
  X(CmdCopyBufferToImage2KHR) X(CmdExecuteCommands) X(CmdPipelineBarrier2) X(CmdPipelineBarrier2KHR) X(CmdWaitEvents)   \
  X(CmdWaitEvents2) X(CmdWaitEvents2KHR) X(CreateQueryPool) X(DestroyQueryPool) X(CmdResetQueryPool)                 \
  X(CmdWriteTimestamp) X(GetQueryPoolResults)                                                                         \

struct DeviceTable {
#define GBL_MEMBER(name) PFN_vk##name name = nullptr;
  GBL_DEVICE_FUNCTIONS(GBL_MEMBER)
#undef GBL_MEMBER
};

struct InstanceData {
  VkInstance instance = VK_NULL_HANDLE;
  PFN_vkGetInstanceProcAddr gipa = nullptr;
  PFN_vkDestroyInstance destroyInstance = nullptr;
  PFN_vkCreateDevice createDevice = nullptr;
  PFN_vkGetPhysicalDeviceMemoryProperties memoryProperties = nullptr;
  PFN_vkGetPhysicalDeviceProperties properties = nullptr;
  PFN_vkGetPhysicalDeviceFormatProperties formatProperties = nullptr;
  PFN_vkGetPhysicalDeviceImageFormatProperties imageFormatProperties = nullptr;
  PFN_vkGetPhysicalDeviceSurfaceCapabilitiesKHR surfaceCapabilities = nullptr;
  PFN_vkEnumerateDeviceExtensionProperties deviceExtensions = nullptr;
  PFN_vkGetPhysicalDeviceProperties2 properties2 = nullptr;
  PFN_vkGetPhysicalDeviceQueueFamilyProperties queueFamilies = nullptr;
  std::string application, engine;
  uint32_t apiVersion = VK_API_VERSION_1_0;  // the application's (VkApplicationInfo)
  // VK_KHR_get_physical_device_properties2 and VK_KHR_external_memory_capabilities are there (core
  // from 1.1; a 1.0 application under attach: enabled by the layer, `addedExtensions`).
  bool externalMemory = false, addedExtensions = false;
};

// ---- formats (formats.cpp)
struct FormatInfo {
  VkFormat format = VK_FORMAT_UNDEFINED;
  const char* vkName = "";    // "VK_FORMAT_R8G8B8A8_SRGB"
  const char* storage = "";   // the layout storage format it is streamed as ("" : none holds it)
  uint32_t bytes = 0;         // a texel (depth/stencil: the depth plane's, as a copy packs it)
  bool depth = false, stencil = false;
  bool bgra = false;          // streamed with R and B swapped (rgba8_*)
};
const FormatInfo& formatInfo(VkFormat f);
std::string formatName(VkFormat f);  // the VK_FORMAT_ name, or "VkFormat N"

// ---- what the layer follows of the application
struct ImageInfo {
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent3D extent{};
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkImageUsageFlags usage = 0;
  std::string name;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;  // a swapchain's image (not the application's to destroy)
  bool transient = false;  // the application made it TRANSIENT_ATTACHMENT (track.cpp: the layer may drop the flag)
};
struct ViewInfo {
  VkImage image = VK_NULL_HANDLE;
  uint32_t mip = 0, layer = 0;
  std::string name;
};
// An attachment's load and store ops as the application gave them, per aspect, and which of its
// DONT_CARE stores the layer patched to STORE (so that it can copy what the pass wrote).
struct AttachmentOps {
  VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_DONT_CARE, stencilLoad = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_DONT_CARE, stencilStore = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  bool storePatched = false, stencilStorePatched = false;
};
struct RenderPassInfo {
  struct Attachment {
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    VkImageLayout finalLayout = VK_IMAGE_LAYOUT_UNDEFINED, stencilFinalLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    bool written = false;     // a colour attachment of a subpass, or depth/stencil in a writable layout
    // The application's own ops (colour or depth aspect; stencil), before the layer patches them.
    AttachmentOps ops;
  };
  std::string name;
  std::vector<Attachment> attachments;
  std::vector<int> colors;  // the last subpass's colour attachments (-1: unused)
  int depth = -1;           // and its depth/stencil attachment
  std::vector<std::vector<int>> subpassColors;  // every subpass's colour attachments
  std::vector<int> subpassDepth;                // and depth attachment (-1: none)
};
struct FramebufferInfo {
  std::vector<VkImageView> views;  // empty: imageless (views given at vkCmdBeginRenderPass)
  std::string name;
};
struct BufferInfo {
  VkDeviceSize size = 0;
  VkBufferUsageFlags usage = 0;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize memoryOffset = 0;
  std::string name;
};

// ---- what the receiver asked for (stream.cpp parses the request)
struct Pick {  // one target of the layout: which attachment of which pass
  int target = 0;
  std::string targetName, format;  // the layout's name and storage format
  bool explicitSource = false;     // the layout names it (else: an image of the target's name, if any)
  std::string pass;                // label or render pass name ("" : any)
  int passIndex = -1;              // ordinal in its command buffer
  std::string name;                // attachment picks: one of these
  int color = -1;
  bool depth = false;
  std::string byFormat;
  int subpass = -1;     // color / depth of this subpass
  int attachment = -1;  // the render pass's attachment index
  int storageSet = -1, storageBinding = -1;  // the storage image a dispatch binds there (dispatch_copies.cpp)
};
// Which render pass: its ordinal in its command buffer, or a label / render pass name.
struct PassPick {
  std::string pass;   // "" : any name
  int passIndex = -1; // -1: any ordinal
  bool on = false;    // asked for at all
};
struct Request {
  std::vector<Pick> picks;
  // camera.live: the matrices' bytes at the end of a pass, from the buffer range bound at set /
  // binding / index there, or from its push constants.
  PassPick liveCamera;
  uint32_t cameraSet = 0, cameraBinding = 0, cameraIndex = 0;
  bool cameraPushConstants = false;
  // bound_buffers: every buffer range bound at the graphics bind point during a pass, and its push
  // constants, copied at its end (the camera search on a live application).
  PassPick boundBuffers;
  VkDeviceSize boundMaxBytes = 4u << 20;
  std::string cameraBuffer;        // debug name of the buffer holding the matrices ("" : none)
  VkDeviceSize cameraBytes = 0;    // bytes of it to read (the matrices' last offset + 64)
  uint32_t every = 1;              // stream frames whose number is a multiple of this
  // --capture-frame N / --capture-frames A..B: stream only the application's frames onlyFrame..lastFrame
  // (0: its first), every one of them (none paced; each held until read, submit.cpp); -1: every N.
  int64_t onlyFrame = -1, lastFrame = -1;
  bool suggest = false;            // report the passes and attachments of one frame
  bool ringOffThread = false;      // the layer's thread makes the ring; frames before it go without copies
  bool paced = false;              // one frame's copies for each `ready` of the receiver's (DeviceData::grants)
  // Some pick names an image (not a pass's attachment by index or format) or a dispatch's storage
  // binding: it may be a storage image written by compute, copied after the dispatches that bind it
  // (dispatch_copies.cpp).
  bool storagePicks = false;
  uint32_t giveUp = 120;           // frames with passes but no match before "nomatch"
};

// What --suggest reports of one render pass.
struct PassReport {
  int ordinal = 0;
  bool dynamic = false;
  std::string renderPass;
  std::vector<std::string> labels;
  struct Attachment {
    std::string role, image, view, format, storage, why;
    uint32_t width = 0, height = 0, samples = 1;
    bool written = false;
    uint32_t imageId = 0;
    bool depth = false, stencil = false;  // the format's aspects
    bool presented = false;               // a swapchain's image
    AttachmentOps ops;
  };
  std::vector<Attachment> attachments;
  // Image ids (imageId) the pass's draws may read through the sets bound at the graphics bind
  // point, and those read after it (compute dispatches, copy/blit/resolve sources) before the next
  // pass of the frame begins.
  std::vector<uint32_t> reads, readsAfter;
  // Storage images the compute dispatches after it (before the next pass) bind, each once: a G-buffer
  // written by compute, which the draft does not hold but the report names with its sources.
  struct Storage {
    Attachment image;  // role "storage"; written: unknown (a storage image may be read or written)
    uint32_t set = 0, binding = 0;
    std::vector<std::string> labels;  // the debug labels open at the first dispatch binding it
  };
  std::vector<Storage> storageAfter;
};

// A render pass being recorded: its attachments and where they are when it ends.
struct PassAttachment {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  int attachment = -1;  // its index in the render pass (dynamic rendering: colours 0.., then depth)
  int color = -1;
  bool depth = false, written = false;
  bool storage = false;  // a storage image a compute dispatch may write (no render pass holds it)
  int storageSet = -1, storageBinding = -1;  // where the dispatch binds it
  AttachmentOps ops;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED, stencilLayout = VK_IMAGE_LAYOUT_UNDEFINED;
};
// A storage image a dispatch bound, copied before the next command that could write it (dispatch_copies.cpp).
struct PendingStorage {
  PassAttachment attachment;
  std::vector<std::string> labels;  // the debug labels open at the dispatch
};
struct OpenPass {
  int ordinal = 0;  // -1: a compute dispatch (its storage images as "attachments", dispatch_copies.cpp)
  bool dynamic = false, suspending = false;
  std::string renderPass;
  std::vector<std::string> labels;
  std::vector<PassAttachment> attachments;
  // Each subpass's colour attachments and depth attachment (render pass indices, -1: unused).
  std::vector<std::vector<int>> subpassColors;
  std::vector<int> subpassDepth;
};

// Push constants as the graphics stages see them: the bytes and the range written so far.
struct PushState {
  std::vector<uint8_t> bytes;
  uint32_t lo = UINT32_MAX, hi = 0;
};
struct BindEvent {
  uint32_t number = 0;  // the set number it was bound at
  BoundSet set;
};

struct CmdState {
  VkCommandPool pool = VK_NULL_HANDLE;
  bool copies = false;          // this recording copies (streaming, and its frame is due or it may be reused)
  // It did not copy though streaming: its frame is not due (every N), every ring slot was held, or
  // the receiver could not have taken it (paced). Its frame's missing targets are no news (not
  // reported, not counted towards giving up).
  bool skipped = false;
  bool paced = false;           // skipped because the receiver could not have taken its frame
  bool suggest = false;         // this recording reports its passes (--suggest, until the report is sent)
  // Descriptor sets bound are followed (--suggest's reads; bound_buffers, camera.live): the sets
  // bound now per bind point, and the graphics sets the open pass's draws see, each once from the
  // first draw that sees it (a set bound before the pass began counts from its first draw; one
  // replaced before any draw does not). structure.cpp.
  bool trackBinds = false;
  std::vector<BoundSet> graphicsSets, computeSets;  // by set number
  // Views of the images a pick names, for the dispatch copies (found at this recording's first dispatch).
  bool namedViewsFound = false;
  std::vector<VkImageView> namedViews;
  std::vector<PendingStorage> pendingStorage;  // bound by the last dispatches, not copied yet
  int passBindsOf = -2;         // the passes whose binds are kept: -1 every pass, N the pass of ordinal N, -2 none
  bool keepPassBinds = false;   // the open pass's are
  std::vector<BindEvent> passBinds;
  PushState push;               // only while bound_buffers or camera.live asks for them
  std::vector<uint32_t> leadingReads;   // --suggest: image ids read before this recording's first pass
  std::vector<PassReport::Storage> leadingStorage;  // --suggest: storage images dispatches bind before it
  std::vector<uint32_t> intoSwapchain;  // --suggest: image ids copied or blitted into a swapchain image
  bool reusable = false;        // it may be submitted again (no ONE_TIME_SUBMIT)
  int passes = 0;               // render passes begun so far
  std::vector<std::string> labels;
  OpenPass open;
  bool inPass = false;
  VkBuffer cameraBuffer = VK_NULL_HANDLE;  // the last bound buffer of the camera's name
  int slot = -1;                // the ring slot this recording copies into
  bool ringPending = false;     // its slot's buffer is being made by the layer's thread (no copies)
  RingRef buffer;               // its buffer as this recording found it
  std::vector<HeldRing> held;   // every buffer this recording copies into
  VkDeviceSize used = 0;        // bytes used of it
  VkDeviceSize total = 0;       // bytes this recording copies in all
  std::vector<Copy> copiesMade;
  std::vector<PassReport> reports;  // --suggest
  void reset() {
    const VkCommandPool p = pool;
    *this = CmdState{};
    pool = p;
  }
};

struct Stream;  // stream.cpp
struct SampleState;  // samples.cpp
struct StagingState;  // staging.cpp

// The staged ring (staging.cpp): whether the device gets it, and the queue the layer adds for its
// downloads (the application's queue infos with one more queue).
struct QueuePlan {
  bool staged = false, ownQueue = false;
  uint32_t family = 0, index = 0;
  VkQueueFlags familyFlags = 0;  // the layer's queue's family (ownQueue)
  std::vector<VkDeviceQueueCreateInfo> infos;
  std::vector<float> priorities;
};

struct DeviceData {
  VkDevice device = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  InstanceData* instance = nullptr;
  DeviceTable vk;
  PFN_vkSetDeviceLoaderData setLoaderData = nullptr;
  VkPhysicalDeviceMemoryProperties memory{};
  bool connected = false;  // a receiver listens: the hooks follow the application
  std::atomic<bool> streaming{false};  // a request arrived and nobody detached

  std::shared_mutex objects;  // the maps below
  std::unordered_map<VkImage, ImageInfo> images;
  std::unordered_map<VkImageView, ViewInfo> views;
  std::unordered_map<VkFramebuffer, FramebufferInfo> framebuffers;
  std::unordered_map<VkRenderPass, RenderPassInfo> renderPasses;
  std::unordered_map<VkBuffer, BufferInfo> buffers;
  std::unordered_map<VkDeviceMemory, uint8_t*> mapped;  // memory -> pointer to its byte 0
  std::unordered_map<VkSwapchainKHR, ImageInfo> swapchains;  // their images' description
  std::unordered_map<VkSwapchainKHR, std::vector<VkImage>> swapchainImages;  // by image index
  std::unordered_map<VkDescriptorSetLayout, std::shared_ptr<const SetLayoutInfo>> setLayouts;
  std::unordered_map<VkDescriptorSet, SetInfo> sets;  // descriptors.cpp
  std::unordered_map<VkDescriptorPool, std::vector<VkDescriptorSet>> poolSets;
  std::unordered_map<VkDescriptorUpdateTemplate, TemplateInfo> templates;

  // --suggest: a small number per image, in the order the report first meets them (structure.cpp).
  std::mutex idLock;
  std::unordered_map<VkImage, uint32_t> imageIds;
  uint32_t nextImageId = 0;

  std::mutex cmdLock;
  std::unordered_map<VkCommandBuffer, std::unique_ptr<CmdState>> cmds;

  std::mutex requestLock;
  std::shared_ptr<const Request> request;

  // Frames (submit.cpp): a frame ends at vkQueuePresentKHR, or, for an application that made no
  // swapchain, at each submission that holds a render pass.
  std::mutex frameLock;
  bool presents = false;
  std::atomic<uint64_t> frame{0};  // frames ended so far: the number of the frame being made
  uint64_t streamed = 0;
  std::unique_ptr<PendingFrame> building;
  std::vector<PassReport> frameReports;
  std::vector<uint32_t> framePresented;  // --suggest: images copied or blitted into a swapchain image this frame
  bool passesThisFrame = false;
  std::atomic<bool> suggestSent{false};  // the passes report went: --suggest's tracking stops
  bool boundBuffersAsked = false;        // the request has bound_buffers (set before any recording)
  bool skippedThisFrame = false;  // a recording of this frame skipped its copies (CmdState::skipped)
  bool pacedThisFrame = false;    // ... because the receiver could not have taken it (CmdState::paced)
  // Pacing (record.cpp): a one-time recording copies only while the receiver can take its frame:
  // fewer than two frames on their way to it (ended with copies, not yet sent or dropped: in the
  // thread's queue or waiting for the receiver's ack), fewer than one while the receiver is busy
  // with a frame. A frame it could not take would be copied for nothing (on a discrete GPU, over
  // PCIe); two in flight keep up with an application's frames in flight when the receiver is quick.
  std::atomic<int> toReceiver{0};
  std::atomic<bool> receiverBusy{false};
  // A paced request (the viewer: it asks for each frame, so that no frame is copied that it would not
  // show): frames copy only while grantsUsed < grants. The connect grants one frame, each `ready`
  // one or two ("frames") beyond those used (grants = grantsUsed + k where that is more: a repeated
  // ready grants nothing more). endFrame counts a whole frame with copies against a grant or, when
  // none is left (it was recorded before the last grant went), does not send it; a granted frame the
  // thread drops before sending gives its grant back, so the receiver never waits for a frame that
  // will not come.
  std::atomic<uint64_t> grants{1}, grantsUsed{0};
  std::atomic<uint64_t> copiedFrames{0};  // frames that ended with copies, sent or not (what the application paid for)
  std::atomic<uint64_t> notAsked{0};      // a paced request's frames due but not asked for (not sent; most not copied)
  // --capture-frame N: once frame N ended with copies, a later submission that copies (a reusable
  // recording writes the same ring buffers) waits until the receiver has read frame N, so that the
  // frame written is exactly N (submit.cpp waitForCapture).
  std::mutex captureLock;
  std::condition_variable captureRead;
  bool captureHeld = false;
  uint32_t framesWithoutMatch = 0;
  uint64_t lastFrameEndNs = 0, frameNsSum = 0, frameIntervals = 0;

  // The ring (ring.cpp): three slots, each a buffer that grows when a recording needs more.
  std::mutex ringLock;
  RingRef slots[3];
  uint32_t nextSlot = 0;
  std::vector<VkFence> freeFences;
  size_t fenceCount = 0;
  VkDeviceSize largestRecording = 0;  // the most bytes one recording copied: a slot's size
  std::atomic<uint64_t> droppedAtSource{0};  // recordings that found every slot held
  bool hostImport = false;          // ring buffers are shared memory (VK_EXT_external_memory_host)
  bool stagedShared = false;        // the staged ring's host buffers are shared memory (staging.cpp)
  VkDeviceSize hostAlignment = 4096;
  std::atomic<uint32_t> nextRingId{0};
  std::atomic<uint64_t> ringBytes{0};
  std::atomic<uint64_t> tileCopies{0};  // attachments copied image to image into the staged ring's tiles
  std::atomic<uint64_t> storageCopies{0};  // storage images copied after dispatches (dispatch_copies.cpp)
  std::unique_ptr<struct CopyTiming> timing;  // GBLENS_LAYER_TIMESTAMPS=1: the copies' GPU time (copy_timing.cpp)
  VkDeviceSize ringWanted = 0;                // a slot's buffer the layer's thread is to make (growRing)
  std::atomic<uint64_t> droppedForRing{0};    // recordings that went without copies meanwhile
  std::atomic<uint64_t> threadAllocNs{0};     // the thread's time making ring buffers (not the application's)

  Stream* stream = nullptr;
  std::atomic<uint64_t> hookNs{0};   // time the layer spent in the application's threads (copies, submissions)
  std::atomic<uint64_t> allocNs{0};  // of which allocating ring buffers (the first frames, resizes)

  // Multisampled attachments (samples.cpp): each queue's family (vkGetDeviceQueue), the families
  // the device was made with, and the layer's images, pipelines and recordings that unpack samples.
  std::unordered_map<VkQueue, uint32_t> queueFamilies;  // under `objects`
  std::vector<uint32_t> createdFamilies;
  SampleState* sampling = nullptr;
  // The staged ring (staging.cpp): device-local ring buffers, downloaded for the frames sent.
  StagingState* staging = nullptr;
  std::vector<uint32_t> ringFamilies;  // the queue families that use the ring (concurrent sharing)
};

// ---- a trace of frames, copies and drops on stderr when GBLENS_LAYER_LOG=1 (layer_main.cpp)
bool logging();
void logLine(const char* format, ...) __attribute__((format(printf, 1, 2)));
#define GBL_LOG(...) (logging() ? logLine(__VA_ARGS__) : void())

// ---- lookups (layer_main.cpp)
DeviceData* deviceOf(const void* dispatchable);  // VkDevice, VkQueue or VkCommandBuffer
InstanceData* instanceOf(const void* dispatchable);
std::shared_ptr<const Request> currentRequest(DeviceData& d);
// A paced request's receiver has a frame granted that no frame has taken yet (DeviceData::grants).
inline bool grantLeft(const DeviceData& d) { return d.grantsUsed < d.grants; }

// ---- hooks: name -> function, per file
struct Hook {
  const char* name;
  PFN_vkVoidFunction function;
};
#define GBL_HOOK(name) Hook{"vk" #name, reinterpret_cast<PFN_vkVoidFunction>(name)}
std::vector<Hook> trackHooks();   // track.cpp
std::vector<Hook> recordHooks();  // record.cpp
std::vector<Hook> descriptorHooks();  // descriptors.cpp
std::vector<Hook> bindHooks();        // structure.cpp (vkCmdBindDescriptorSets)
std::vector<Hook> submitHooks();  // submit.cpp
// structure.cpp: handed out only to a device whose receiver asked for what they follow (--suggest:
// dispatches and image copies; bound_buffers and camera.live: push constants), so that a stream
// that asks for none of it does not pass through them.
std::vector<Hook> structureHooks(const Request& req);

// ---- the frame's structure and the bound sets (structure.cpp)
uint32_t imageId(DeviceData& d, VkImage image);  // 1, 2, ... in the order first asked
void forgetImageId(DeviceData& d, VkImage image);
// A pass begins / ends: the graphics sets bound now start its binds; the image ids its binds read.
void beginPassBinds(CmdState& s);
std::vector<uint32_t> passReads(DeviceData& d, const CmdState& s);
bool passMatches(const PassPick& p, const OpenPass& pass);

// ---- the ring (ring.cpp)
// Room for `bytes` in the recording's ring slot: its buffer and the offset (the slot gets a new,
// larger buffer when the current one is full; the old one lives on while recordings and frames
// still hold it). False when memory is short.
bool reserve(DeviceData& d, CmdState& s, VkDeviceSize bytes, RingRef& buffer, VkDeviceSize& offset);
int takeSlot(DeviceData& d, bool reusable);  // -1: none free for a recording submitted once
VkFence takeFence(DeviceData& d);
// The layer's thread: every slot's buffer at least the size a recording asked for (reserve).
void growRing(DeviceData& d);
void wakeStream(DeviceData& d);  // stream.cpp: the thread looks at its work now
void returnFence(DeviceData& d, VkFence f);
void destroyRing(DeviceData& d);

// ---- command recording (record.cpp)
void recordCopies(DeviceData& d, VkCommandBuffer cmd, CmdState& s);  // copy.cpp: at the open pass's end
// The copies of the targets `pass` holds (a render pass, or a dispatch's storage images: then no
// buffers, and only picks by name or by storage binding); copy.cpp.
void recordPassCopies(DeviceData& d, VkCommandBuffer cmd, CmdState& s, const OpenPass& pass);
// dispatch_copies.cpp: after a dispatch, the picked storage images it binds become pending (replacing
// the same images' pending copies: a later writer supersedes them); flushed (their copies recorded)
// before any command that could write them (a render pass that does not write them as attachments,
// a clear, a copy into an image, a barrier discarding them, secondary command buffers) and at the
// recording's end; a barrier moving one to another layout keeps it pending there.
void dispatchCopies(DeviceData& d, VkCommandBuffer cmd, CmdState& s);
// copy_timing.cpp (GBLENS_LAYER_TIMESTAMPS=1): a block of copies timed on the GPU: its first query
// (-1: not timed), a timestamp `index` into it, the means so far (null: none), the query pool gone.
bool copyTimingOn();
int beginCopyTiming(DeviceData& d, VkCommandBuffer cmd, std::vector<std::string> copies);
void stampCopyTiming(DeviceData& d, VkCommandBuffer cmd, int block, uint32_t index);
nlohmann::json copyTimingJson(DeviceData& d);
void destroyCopyTiming(DeviceData& d);
void flushStorageCopies(DeviceData& d, VkCommandBuffer cmd, CmdState& s);
// A render pass (s.open) is about to begin: a pending image it writes as an attachment is dropped
// (its end copies it), the others are flushed.
void storageBeforePass(DeviceData& d, VkCommandBuffer cmd, CmdState& s);
std::vector<Hook> storageWriterHooks();
void flushBeforeWrite(VkCommandBuffer cmd);  // a hooked command that may write an image is about to be recorded
PassReport reportPass(DeviceData& d, const OpenPass& pass);        // structure.cpp (--suggest)
// Appends `e` unless `list` holds its image already (structure.cpp): each storage image once a pass.
void addStorageOnce(std::vector<PassReport::Storage>& list, const PassReport::Storage& e);
// Why an attachment cannot be streamed as a target of storage format `want` ("" : it can; want ""
// accepts any format a layout can hold). copy.cpp.
std::string refusal(DeviceData& d, const ImageInfo& image, const std::string& want);
// The camera's and the bound buffers' copies at the end of the open pass (`targets`: it copies
// attachments too, and so the camera of a debug name). copy_buffers.cpp.
std::vector<BufferCopy> bufferCopies(DeviceData& d, const CmdState& s, const Request& req, bool targets);
std::string pickText(const Pick& p);                               // "colour attachment 0 of render pass 1"
CmdState* cmdState(DeviceData& d, VkCommandBuffer cmd);


// Frame `number` is one the request wants streamed (every N, or only the frames --capture-frame(s) names).
inline bool frameDue(const Request& r, uint64_t number) {
  return r.onlyFrame >= 0 ? number >= uint64_t(r.onlyFrame) && number <= uint64_t(r.lastFrame) : number % r.every == 0;
}
// --capture-frame(s): the frame asked for is held (its copies not yet read) / read or given up
// (submit.cpp): the next submission that copies waits for it, so no frame of a range is skipped.
void holdCapture(DeviceData& d);
void releaseCapture(DeviceData& d);
// Waits (at most 20 s) until the frame held is read: before a submission that would write its ring
// buffers again or copy the next frame of a range, and before the device goes (stopStream).
void waitForCapture(DeviceData& d);

// ---- multisampled attachments (samples.cpp): every sample, copied at the pass's end into an image
// of the layer's (the application's command buffer), then unpacked into the ring by a compute
// recording of the layer's own, submitted right after the application's submission.
std::string sampleRefusal(DeviceData& d, const ImageInfo& image);  // "" : its samples can be streamed
// The layer's image this attachment's samples are copied into (made on first use; null: out of memory).
std::shared_ptr<SampleStage> sampleStage(DeviceData& d, VkImage image, uint32_t mip, uint32_t layer, const ImageInfo& info);
VkImage stageImage(const SampleStage& stage);
// The layer's fence after the application's submission, with the unpacking of the multisampled
// `copies` and the staged ring's `download` (staging.cpp) before it.
VkResult submitFence(DeviceData& d, VkQueue queue, const std::vector<Copy>& copies, const std::vector<Copy>& download,
                     VkFence fence);
void releaseSamples(DeviceData& d, VkFence fence);  // the fence's frame is read: its recording goes
void destroySamples(DeviceData& d);
std::vector<Hook> queueHooks();  // vkGetDeviceQueue(2): each queue's family

// ---- the staged ring (staging.cpp)
bool planStaging(InstanceData& inst, VkPhysicalDevice physical, const VkDeviceCreateInfo& info, QueuePlan& plan);
void startStaging(DeviceData& d, const QueuePlan& plan);  // after vkCreateDevice
// The staged ring's tile images (ring.h TileImage): wanted on this device, and the one of a copy at
// `offset` of `ring` (made or remade to fit; null: none could be made, the copy uses the buffer).
bool tilesWanted(const DeviceData& d, bool depthStencil);
VkImage ringTile(DeviceData& d, RingBuffer& ring, VkDeviceSize offset, VkFormat format, uint32_t width, uint32_t height);
bool stagedOwnQueue(const DeviceData& d);                 // downloads on the layer's queue (else in its batch)
// The commands that bring `copies` from the device-local ring to its host buffers, and the layer's
// thread doing so on its own queue (waits for it).
void recordDownload(DeviceData& d, VkCommandBuffer cmd, const std::vector<Copy>& copies);
bool downloadFrame(DeviceData& d, const std::vector<Copy>& copies);
void destroyStaging(DeviceData& d);
VkDeviceSize copySize(const Copy& c);  // send.cpp: the bytes a copy wrote into the ring
uint32_t deviceLocalMemoryType(const DeviceData& d, uint32_t bits);  // ring.cpp (UINT32_MAX: none)

// ---- the stream (stream.cpp)
// At vkCreateDevice: the connection to the receiver and its request, before the device is made
// (null when no receiver listens: the layer stays idle); the thread once it exists.
Stream* openStream(InstanceData& instance, VkPhysicalDevice physical);
void startStream(DeviceData& d, Stream* st);
void closeStream(Stream* st);                 // the device was not made after all
void stopStream(DeviceData& d);               // at vkDestroyDevice
void streamFrame(DeviceData& d, std::unique_ptr<PendingFrame> f);  // hands a submitted frame over
void streamPasses(DeviceData& d, const std::vector<PassReport>& passes, const std::vector<uint32_t>& presented,
                  uint64_t frame);
void streamNoMatch(DeviceData& d, uint64_t frames);
// A message for people, sent once per key (a target that never appears, a format mismatch, ...).
void report(DeviceData& d, const std::string& key, const std::string& text);
bool wasReported(DeviceData& d, const std::string& key);

}  // namespace gbl
