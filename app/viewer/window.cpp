// The window: GLFW, its Vulkan surface and swapchain, and Dear ImGui's GLFW + Vulkan backends.
// ImGui 1.86's Vulkan backend has no user textures (ImGui_ImplVulkan_AddTexture came later), so
// views are drawn by an ImDrawList callback that records the renderer's view pipeline
// (renderer/view_map) inside ImGui's own draw order: panels overlap and clip views correctly.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>
#include <imgui/backends/imgui_impl_vulkan.h>

#include <chrono>
#include <cstdio>

#include "app/viewer/viewer.h"
#include "renderer/vk/check.h"

namespace gb {

static Viewer* g_viewer = nullptr;  // the ImDrawList callback's context (one viewer per process)

static void checkVk(VkResult r) {
  if (r != VK_SUCCESS) vkFail(r, "ImGui Vulkan backend", __FILE__, __LINE__);
}

bool openWindow(Viewer& v, uint32_t width, uint32_t height) {
  glfwSetErrorCallback([](int code, const char* text) { std::fprintf(stderr, "gblens view: GLFW error %d: %s\n", code, text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "gblens view: cannot open a window (no display? set DISPLAY, or use gblens render)\n");
    return false;
  }
  if (!glfwVulkanSupported()) {
    std::fprintf(stderr, "gblens view: GLFW finds no Vulkan loader\n");
    glfwTerminate();
    return false;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  if (!v.args.windowGiven) {  // no --window: most of the monitor, at most 1920x1080
    if (GLFWmonitor* monitor = glfwGetPrimaryMonitor())
      if (const GLFWvidmode* mode = glfwGetVideoMode(monitor)) {
        width = uint32_t(std::min(1920.0, std::max(640.0, mode->width * 0.85)));
        height = uint32_t(std::min(1080.0, std::max(480.0, mode->height * 0.85)));
      }
  }
  // What the window shows: the scene rendered, the capture(s) opened, or the attached application.
  std::string title = "gblens - " + v.args.scene;
  if (v.args.attach) title = "gblens - attached application";
  else if (!v.args.compare.empty()) title = "gblens - capture " + v.args.capture + " vs " + v.args.compare;
  else if (!v.args.capture.empty()) title = "gblens - capture " + v.args.capture;
  v.window = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!v.window) {
    std::fprintf(stderr, "gblens view: cannot create a %ux%u window\n", width, height);
    glfwTerminate();
    return false;
  }
  return true;
}

bool recreateSwapchain(Viewer& v) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(v.window, &w, &h);
  v.swapchainValid = createSwapchain(v.ctx, v.swapchain, uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0)));
  if (v.swapchainValid && v.imguiPool) ImGui_ImplVulkan_SetMinImageCount(v.swapchain.minImageCount);
  return v.swapchainValid;
}

void initImGui(Viewer& v) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // layout is fixed; nothing to remember between runs
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 0.0f;
  style.ScrollbarRounding = 2.0f;
  ImGui_ImplGlfw_InitForVulkan(v.window, false);  // input reaches it through the viewer's queue (input.cpp)

  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pci.maxSets = 8;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = sizes;
  VK_CHECK(vkCreateDescriptorPool(v.ctx.device, &pci, nullptr, &v.imguiPool));

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = v.ctx.instance;
  info.PhysicalDevice = v.ctx.physical;
  info.Device = v.ctx.device;
  info.QueueFamily = v.ctx.queueFamily;
  info.Queue = v.ctx.queue;
  info.DescriptorPool = v.imguiPool;
  info.MinImageCount = v.swapchain.minImageCount;
  info.ImageCount = uint32_t(std::max<size_t>(v.swapchain.images.size(), v.swapchain.minImageCount));
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkVk;
  ImGui_ImplVulkan_Init(&info, v.swapchain.renderPass);
  submitOnce(v.ctx, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  g_viewer = &v;
}

void shutdownImGui(Viewer& v) {
  if (!v.imguiPool) return;
  vkDeviceWaitIdle(v.ctx.device);
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(v.ctx.device, v.imguiPool, nullptr);
  v.imguiPool = VK_NULL_HANDLE;
  g_viewer = nullptr;
}

void closeWindow(Viewer& v) {
  destroySwapchain(v.ctx, v.swapchain);
  if (v.swapchain.surface) vkDestroySurfaceKHR(v.ctx.instance, v.swapchain.surface, nullptr);
  v.swapchain.surface = VK_NULL_HANDLE;
  if (v.window) glfwDestroyWindow(v.window);
  v.window = nullptr;
  glfwTerminate();
}

// ImDrawList callback: one view, clipped to the draw command's clip rectangle.
static void drawViewCallback(const ImDrawList*, const ImDrawCmd* cmd) {
  Viewer& v = *g_viewer;
  size_t index = size_t(reinterpret_cast<intptr_t>(cmd->UserCallbackData));
  if (index >= v.draws.size() || !v.frameValid) return;
  const ViewDraw& d = v.draws[index];
  ImDrawData* dd = ImGui::GetDrawData();
  const ImVec2 scale = dd->FramebufferScale, pos = dd->DisplayPos;
  const VkExtent2D ext = v.swapchain.extent;
  float x0 = std::max(0.0f, (cmd->ClipRect.x - pos.x) * scale.x), y0 = std::max(0.0f, (cmd->ClipRect.y - pos.y) * scale.y);
  float x1 = std::min(float(ext.width), (cmd->ClipRect.z - pos.x) * scale.x);
  float y1 = std::min(float(ext.height), (cmd->ClipRect.w - pos.y) * scale.y);
  if (x1 <= x0 || y1 <= y0 || d.rect.w < 1 || d.rect.h < 1) return;
  VkRect2D viewport{{int32_t(d.rect.x), int32_t(d.rect.y)}, {uint32_t(d.rect.w), uint32_t(d.rect.h)}};
  auto draw = [&](Renderer& r, const ViewImage& image, float from, float to, const ViewImage* b) {
    from = std::max(from, x0);
    to = std::min(to, x1);
    if (to <= from || !image.valid() || (b && !b->valid())) return;
    VkRect2D scissor{{int32_t(from), int32_t(y0)}, {uint32_t(int32_t(to) - int32_t(from)), uint32_t(y1 - int32_t(y0))}};
    if (scissor.extent.width == 0 || scissor.extent.height == 0) return;
    drawView(v.mapper, r, v.swapchain.cmd, v.swapchain.renderPass, v.swapchain.format.format, image, d.params, viewport,
             scissor, b);
  };
  const ViewerModel& m = v.model;
  if (m.source == FrameSource::Live) {
    if (m.views[size_t(d.view)].quantity < 0)  // a reference map (reference_error.cpp)
      draw(v.renderer, referenceViewImage(v, d.view), x0, x1, nullptr);
    else if (std::optional<ViewSource> src = nativeSource(m.frameLayout, m.views[size_t(d.view)]))
      draw(v.renderer, targetImage(v.renderer, *src), x0, x1, nullptr);
    return;
  }
  const ViewImage a = viewImageOf(v.imagesA, size_t(d.view)), b = viewImageOf(v.imagesB, size_t(d.view));
  if (d.splitX >= 0.0 && v.hasB) {  // compare split: A on the left, B on the right
    draw(v.renderer, a, x0, float(d.splitX), nullptr);
    draw(v.renderer, b, float(d.splitX), x1, nullptr);
  } else if (d.side == FrameSide::B && v.hasB) {
    draw(v.renderer, b, x0, x1, nullptr);
  } else if (d.side == FrameSide::Difference && v.hasB) {
    draw(v.renderer, a, x0, x1, &b);
  } else if (d.side == FrameSide::Flip) {
    draw(v.renderer, viewImageOf(v.imagesFlip, size_t(d.view)), x0, x1, nullptr);
  } else {
    draw(v.renderer, a, x0, x1, nullptr);
  }
}

ViewDrawCallback viewDrawCallback() { return drawViewCallback; }

bool presentFrame(Viewer& v) {
  auto start = std::chrono::steady_clock::now();
  uint32_t image = 0;
  const float clear[4] = {0.06f, 0.06f, 0.07f, 1.0f};
  if (!beginSwapchainFrame(v.ctx, v.swapchain, image, clear)) return false;
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), v.swapchain.cmd);
  bool ok = endSwapchainFrame(v.ctx, v.swapchain, image);
  // Wait for the frame: the next renderFrame rewrites the buffers the views read (one frame in flight).
  VK_CHECK(vkWaitForFences(v.ctx.device, 1, &v.swapchain.fence, VK_TRUE, UINT64_MAX));
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  v.model.presentMs = ms;
  v.presentMs.push_back(ms);
  v.model.framesPresented++;
  return ok;
}

}  // namespace gb
