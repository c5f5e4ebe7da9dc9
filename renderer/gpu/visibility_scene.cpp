// --gbuffer visibility on the GPU: the id's packing for the scene, each draw's place in the index
// and vertex buffers (DrawGeometry), and gbuffer_resolve's descriptors: set 1 pushed per frame
// (the shadow map, the visibility id, the G-buffer's storage views, a texture group's two
// textures) and set 2 written once (the scene's vertices and indices as storage buffers, the
// draws' geometry). Texture groups: the distinct (base colour, normal) texture pairs of the drawn
// materials, group 0 the untextured; gbuffer_resolve dispatches once per group (a device without
// descriptor indexing, lavapipe's, can bind no texture chosen per pixel).
#include "renderer/gpu/visibility_scene.h"

#include <algorithm>

#include "renderer/vk/check.h"

namespace gb {

static bool packScene(Renderer& r) {
  const Scene& s = *r.scene;
  uint64_t maxTriangles = 1;
  for (const Instance& inst : s.instances) maxTriangles = std::max<uint64_t>(maxTriangles, s.meshes[inst.mesh].indexCount / 3);
  if (!r.ctx->features.visibilityResolve) {
    r.visibilityRefusal = "--gbuffer visibility: the device " + r.ctx->deviceName +
                          " lacks what it needs (shaderStorageImageWriteWithoutFormat, geometryShader for gl_PrimitiveID)";
    return false;
  }
  return visibilityPacking(s.instances.size(), maxTriangles, r.visibilityPacking, r.visibilityRefusal);
}

static void createLayouts(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  std::vector<VkDescriptorSetLayoutBinding> pass = {
      {gpu::kResolveBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
      {gpu::kResolveBindingVisibility, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr}};
  for (uint32_t b = gpu::kResolveBindingAlbedo; b <= gpu::kResolveBindingMotion; ++b)
    pass.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr});
  for (uint32_t b : {gpu::kResolveBindingBaseTexture, gpu::kResolveBindingNormalTexture})
    pass.push_back({b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr});
  r.resolveSetLayout = createSetLayout(ctx, pass, VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR, "set1.resolve");
  r.resolveSceneSetLayout =
      createSetLayout(ctx,
                {{gpu::kResolveBindingVertices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr},
                 {gpu::kResolveBindingIndices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr},
                 {gpu::kResolveBindingGeometry, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr}},
                0, "set2.resolve_scene");
  const VkPushConstantRange push{cs, 0, 16};  // uvec4: x the dispatch's texture group
  VkDescriptorSetLayout layouts[] = {r.sceneSetLayout, r.resolveSetLayout, r.resolveSceneSetLayout};
  VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pci.setLayoutCount = 3;
  pci.pSetLayouts = layouts;
  pci.pushConstantRangeCount = 1;
  pci.pPushConstantRanges = &push;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pci, nullptr, &r.resolveLayout));
  setName(ctx, uint64_t(r.resolveLayout), VK_OBJECT_TYPE_PIPELINE_LAYOUT, "pipeline_layout.resolve");
}

// Each draw's geometry: index and vertex offsets, triangles, first primitive_id, its textures and
// their group (r.textureGroups, in order of first use; 0: none).
static void uploadDrawGeometry(Renderer& r) {
  const Scene& s = *r.scene;
  const std::vector<uint32_t> firstPrimitive = firstPrimitiveIds(s);
  std::vector<gpu::DrawGeometry> geometry(std::max<size_t>(s.instances.size(), 1));
  r.textureGroups = {{-1, -1}};
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const Mesh& m = s.meshes[s.instances[i].mesh];
    const MaterialDesc& mat = s.materials[m.material];
    const std::pair<int, int> pair{mat.baseColorTexture, mat.normalTexture};
    auto group = std::find(r.textureGroups.begin(), r.textureGroups.end(), pair);
    if (group == r.textureGroups.end() && m.indexCount) group = r.textureGroups.insert(group, pair);
    const int index = group == r.textureGroups.end() ? 0 : int(group - r.textureGroups.begin());
    geometry[i].info = glm::uvec4(m.firstIndex, m.firstVertex, m.indexCount / 3, firstPrimitive[i]);
    geometry[i].textures = glm::ivec4(mat.baseColorTexture, mat.normalTexture, index, 0);
  }
  r.drawGeometryBuffer = createBuffer(*r.ctx, geometry.size() * sizeof(gpu::DrawGeometry),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      MemoryUse::Device, "draw_geometry");
  uploadBuffer(*r.ctx, r.drawGeometryBuffer, geometry.data(), geometry.size() * sizeof(gpu::DrawGeometry));
}

static void writeSceneSet(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = sizes;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pci, nullptr, &r.resolvePool));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = r.resolvePool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &r.resolveSceneSetLayout;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &ai, &r.resolveSceneSet));
  setName(ctx, uint64_t(r.resolveSceneSet), VK_OBJECT_TYPE_DESCRIPTOR_SET, "set2.resolve_scene");

  const VkDescriptorBufferInfo buffers[] = {{r.vertexBuffer.buffer, 0, VK_WHOLE_SIZE},
                                            {r.indexBuffer.buffer, 0, VK_WHOLE_SIZE},
                                            {r.drawGeometryBuffer.buffer, 0, VK_WHOLE_SIZE}};
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t b = 0; b < 3; ++b) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = r.resolveSceneSet;
    w.dstBinding = b;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &buffers[b];
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(ctx.device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void createVisibilityScene(Renderer& r) {
  static_assert(sizeof(Vertex) == gpu::kVertexFloats * sizeof(float), "gbuffer_resolve reads Vertex as 14 floats");
  if (!packScene(r)) return;
  createLayouts(r);
  uploadDrawGeometry(r);
  writeSceneSet(r);
}

void destroyVisibilityScene(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  destroyBuffer(ctx, r.drawGeometryBuffer);
  if (r.resolvePool) vkDestroyDescriptorPool(ctx.device, r.resolvePool, nullptr);
  if (r.resolveLayout) vkDestroyPipelineLayout(ctx.device, r.resolveLayout, nullptr);
  for (VkDescriptorSetLayout l : {r.resolveSetLayout, r.resolveSceneSetLayout})
    if (l) vkDestroyDescriptorSetLayout(ctx.device, l, nullptr);
}

std::string visibilityRefusal(const Renderer& r, const RenderOptions& o) {
  if (o.gbuffer != GBufferKind::Visibility) return "";
  const std::string options = visibilityOptionsRefusal(o);
  return options.empty() ? r.visibilityRefusal : options;
}

}  // namespace gb
