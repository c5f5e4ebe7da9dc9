// An offscreen canvas the GPU view tests draw views into (views/ui/view_map.h drawView), 1:1, and
// read back: what the viewer puts on screen for a view, as bytes.
#pragma once
#include <vector>

#include "renderer/vk/check.h"
#include "views/ui/view_map.h"

namespace gb {

// An offscreen RGBA8 attachment the views are drawn into, 1:1, then read back.
struct Canvas {
  Image image;
  VkRenderPass pass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  Buffer readback;

  Canvas(GpuContext& ctx, uint32_t w, uint32_t h) {
    ImageDesc d;
    d.format = VK_FORMAT_R8G8B8A8_UNORM;
    d.width = w;
    d.height = h;
    d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    image = createImage(ctx, d);
    VkAttachmentDescription a{};
    a.format = d.format;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &ref;
    VkSubpassDependency dep{};  // the copy after the pass waits for the colour writes
    dep.srcSubpass = 0;
    dep.dstSubpass = VK_SUBPASS_EXTERNAL;
    dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dep.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    ci.attachmentCount = 1;
    ci.pAttachments = &a;
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    ci.dependencyCount = 1;
    ci.pDependencies = &dep;
    VK_CHECK(vkCreateRenderPass(ctx.device, &ci, nullptr, &pass));
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = pass;
    fi.attachmentCount = 1;
    fi.pAttachments = &image.view;
    fi.width = w;
    fi.height = h;
    fi.layers = 1;
    VK_CHECK(vkCreateFramebuffer(ctx.device, &fi, nullptr, &framebuffer));
    readback = createBuffer(ctx, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
  }
  void destroy(GpuContext& ctx) {
    vkDestroyFramebuffer(ctx.device, framebuffer, nullptr);
    vkDestroyRenderPass(ctx.device, pass, nullptr);
    destroyImage(ctx, image);
    destroyBuffer(ctx, readback);
  }

  // Draws one view at 1:1 (texel (x, y) -> canvas pixel (x, y)) and returns the canvas bytes.
  std::vector<uint8_t> draw(ViewMapper& m, Renderer& r, const ViewImage& source, const gpu::ViewParams& params) {
    GpuContext& ctx = *r.ctx;
    const uint32_t w = image.desc.width, h = image.desc.height;
    submitOnce(ctx, [&](VkCommandBuffer cmd) {
      VkClearValue clear{};
      VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
      bi.renderPass = pass;
      bi.framebuffer = framebuffer;
      bi.renderArea = {{0, 0}, {w, h}};
      bi.clearValueCount = 1;
      bi.pClearValues = &clear;
      vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
      drawView(m, r, cmd, pass, image.desc.format, source, params, {{0, 0}, {w, h}}, {{0, 0}, {w, h}});
      vkCmdEndRenderPass(cmd);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {w, h, 1};
      vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &copy);
      hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });
    const uint8_t* p = static_cast<const uint8_t*>(readback.mapped);
    return std::vector<uint8_t>(p, p + size_t(w) * h * 4);
  }
};

}  // namespace gb
