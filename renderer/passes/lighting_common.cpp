// Helpers the lighting passes share: G-buffer reads per path, descriptors, draws.
#include "renderer/passes/passes.h"
#include "renderer/vk/check.h"

namespace gb {

bool singlePass(const Renderer& r) { return singlePassFrame(r.options); }

static Target positionSource(const Renderer& r) {
  if (r.options.position != PositionSource::Depth) return Target::Position;
  return r.options.eyeDepth ? Target::Depth : Target::DepthStencil;
}

std::vector<Use> gbufferReads(const Renderer& r) {
  Access a = singlePass(r) ? Access::InputAttachment : Access::SampledFragment;
  return {{Target::AlbedoSpecular, a}, {Target::NormalShadow, a}, {positionSource(r), a}};
}

Use hdrUse(Access access, bool clear) {
  Use u{Target::Hdr, access, clear};
  u.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
  return u;
}

Use depthStencilUse(Access access) { return {Target::DepthStencil, access}; }

Shader lightingShader(const Renderer& r, Shader sampled, Shader input) { return singlePass(r) ? input : sampled; }

VkPipelineLayout lightingLayout(const Renderer& r) { return singlePass(r) ? r.pipelineLayoutInput : r.pipelineLayout; }

void bindGBuffer(Renderer& r, const PassContext& pc, std::initializer_list<PassImage> extra, VkPipelineBindPoint bindPoint,
                 std::initializer_list<PassBuffer> buffers) {
  const bool input = singlePass(r);
  const VkDescriptorType type = input ? VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  const VkSampler sampler = input ? VK_NULL_HANDLE : r.samplerPoint;
  Target pos = positionSource(r);
  const Image& posImage = r.targets[size_t(pos)].image;
  VkImageView posView = pos == Target::DepthStencil ? posImage.depthView : posImage.view;
  std::vector<PassImage> images = {
      {gpu::kBindingAlbedo, type, r.targets[size_t(Target::AlbedoSpecular)].image.view,
       pc.layouts[size_t(Target::AlbedoSpecular)], sampler},
      {gpu::kBindingNormal, type, r.targets[size_t(Target::NormalShadow)].image.view,
       pc.layouts[size_t(Target::NormalShadow)], sampler},
      {gpu::kBindingDepth, type, posView, pc.layouts[size_t(pos)], sampler},
  };
  images.insert(images.end(), extra.begin(), extra.end());
  // bindDescriptors takes an initializer_list; push through a small adapter.
  VkPipelineLayout layout = lightingLayout(r);
  vkCmdBindDescriptorSets(pc.cmd, bindPoint, layout, gpu::kSetScene, 1, &frameSlot(r).sceneSet, 0, nullptr);
  std::vector<VkDescriptorImageInfo> infos(images.size());
  std::vector<VkDescriptorBufferInfo> bufferInfos;
  for (const PassBuffer& b : buffers) bufferInfos.push_back({b.buffer, 0, VK_WHOLE_SIZE});
  std::vector<VkWriteDescriptorSet> writes(images.size() + buffers.size(), {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET});
  for (size_t i = 0; i < images.size(); ++i) {
    infos[i] = {images[i].sampler, images[i].view, images[i].layout};
    writes[i].dstBinding = images[i].binding;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = images[i].type;
    writes[i].pImageInfo = &infos[i];
  }
  size_t k = images.size();
  for (const PassBuffer& b : buffers) {
    writes[k].dstBinding = b.binding;
    writes[k].descriptorCount = 1;
    writes[k].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[k].pBufferInfo = &bufferInfos[k - images.size()];
    ++k;
  }
  r.ctx->cmdPushDescriptorSet(pc.cmd, bindPoint, layout, gpu::kSetPass, uint32_t(writes.size()),
                              writes.data());
}

void pushComputeBuffers(Renderer& r, VkCommandBuffer cmd, std::initializer_list<PassBuffer> buffers) {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipelineLayout, gpu::kSetScene, 1, &frameSlot(r).sceneSet, 0, nullptr);
  std::vector<VkDescriptorBufferInfo> infos;
  infos.reserve(buffers.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (const PassBuffer& b : buffers) {
    infos.push_back({b.buffer, 0, VK_WHOLE_SIZE});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = b.binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &infos.back();
    writes.push_back(w);
  }
  r.ctx->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipelineLayout, gpu::kSetPass,
                              uint32_t(writes.size()), writes.data());
}

std::vector<BufferUse> lightReads(const Renderer& r, BufferAccess access) {
  return {{frameSlot(r).lightBuffer.buffer, access}, {frameSlot(r).visibleBuffer.buffer, access},
          {frameSlot(r).visiblePositionBuffer.buffer, access}, {frameSlot(r).lightCountBuffer.buffer, access}};
}

void drawLightVolumes(Renderer& r, VkCommandBuffer cmd, uint32_t first, uint32_t count) {
  if (count == 0) return;
  VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &r.icosahedronBuffer.buffer, &offset);
  vkCmdDraw(cmd, 60, count, 0, first);
}

// The material's textures as pushed descriptors (stand-ins where it has none).
static void pushMaterialTextures(Renderer& r, VkCommandBuffer cmd, const MaterialDesc& m) {
  const Scene& s = *r.scene;
  const size_t white = r.textures.size() - 2, flat = r.textures.size() - 1;
  auto sampler = [&](int t) { return t < 0 || s.textures[t].repeat ? r.samplerRepeat : r.samplerClamp; };
  VkDescriptorImageInfo infos[2] = {
      {sampler(m.baseColorTexture), r.textures[m.baseColorTexture >= 0 ? size_t(m.baseColorTexture) : white].view,
       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {sampler(m.normalTexture), r.textures[m.normalTexture >= 0 ? size_t(m.normalTexture) : flat].view,
       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  for (int i = 0; i < 2; ++i) {
    writes[i].dstBinding = i == 0 ? gpu::kBindingBaseColorTexture : gpu::kBindingNormalTexture;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[i].pImageInfo = &infos[i];
  }
  r.ctx->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipelineLayout, gpu::kSetPass, 2, writes);
}

void drawInstances(Renderer& r, VkCommandBuffer cmd, uint32_t begin, uint32_t end, bool shadowCastersOnly) {
  const Scene& s = *r.scene;
  int lastMaterial = -1;
  VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &r.vertexBuffer.buffer, &offset);
  vkCmdBindIndexBuffer(cmd, r.indexBuffer.buffer, 0, VK_INDEX_TYPE_UINT32);
  VkCullModeFlags lastCull = ~0u;
  VkFrontFace lastFront = VK_FRONT_FACE_MAX_ENUM;
  for (uint32_t k = begin; k < end; ++k) {
    uint32_t i = r.drawOrder[k];
    const Instance& inst = s.instances[i];
    if (shadowCastersOnly && !inst.castsShadow) continue;
    const Mesh& m = s.meshes[inst.mesh];
    const MaterialDesc& mat = s.materials[m.material];
    VkCullModeFlags cull = mat.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    // glTF front faces are counter-clockwise; a mirroring transform reverses the winding.
    bool flipped = glm::determinant(glm::dmat3(inst.worldFromObject)) < 0.0;
    VkFrontFace front = flipped ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
    if (m.material != lastMaterial) pushMaterialTextures(r, cmd, mat);
    lastMaterial = m.material;
    if (cull != lastCull) vkCmdSetCullMode(cmd, lastCull = cull);
    if (front != lastFront) vkCmdSetFrontFace(cmd, lastFront = front);
    vkCmdDrawIndexed(cmd, m.indexCount, 1, m.firstIndex, int32_t(m.firstVertex), i);
  }
}

void bindPipeline(const PassContext& pc, VkPipeline pipeline) {
  vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  VkViewport viewport{0, 0, float(pc.extent.width), float(pc.extent.height), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, pc.extent};
  vkCmdSetViewport(pc.cmd, 0, 1, &viewport);
  vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
}

void sceneGeometryDepthStencil(const Renderer& r, GraphicsPipelineDesc& d) {
  d.depthTest = d.depthWrite = true;
  d.depthCompare = r.options.reversedZ ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
  d.stencilTest = true;
  d.stencil = stencil(VK_COMPARE_OP_ALWAYS, 0xFF, VK_STENCIL_OP_KEEP, VK_STENCIL_OP_REPLACE);
}

VkStencilOpState stencil(VkCompareOp compare, uint32_t compareMask, VkStencilOp depthFail, VkStencilOp pass) {
  VkStencilOpState s{};
  s.failOp = VK_STENCIL_OP_KEEP;
  s.passOp = pass;
  s.depthFailOp = depthFail;
  s.compareOp = compare;
  s.compareMask = compareMask;
  s.writeMask = 0xFF;
  s.reference = gpu::kStencilGeometry;
  return s;
}

}  // namespace gb
