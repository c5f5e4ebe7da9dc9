// The scene on the GPU: vertex/index buffers, textures, materials, samplers, and the layout of
// descriptor set 0 that every pipeline shares (one set per frame slot, renderer/frame/frame_slots.cpp; set 1 is
// pushed per pass).
#include "renderer/gpu/gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "renderer/scene/mesh_builder.h"
#include "renderer/vk/check.h"

namespace gb {

static VkSampler makeSampler(GpuContext& ctx, VkFilter filter, VkSamplerAddressMode mode, bool compare,
                             float maxLod, const char* name) {
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = ci.minFilter = filter;
  ci.mipmapMode = filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  ci.addressModeU = ci.addressModeV = ci.addressModeW = mode;
  ci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;  // shadow map: outside is lit
  ci.compareEnable = compare;
  ci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the receiver is not behind the stored depth
  ci.maxLod = maxLod;
  VkSampler s;
  VK_CHECK(vkCreateSampler(ctx.device, &ci, nullptr, &s));
  setName(ctx, uint64_t(s), VK_OBJECT_TYPE_SAMPLER, name);
  return s;
}

static gpu::Material toGpu(const MaterialDesc& m) {
  gpu::Material g{};
  g.baseColor = m.baseColor;
  g.params = glm::vec4(m.specular, m.alphaMode == AlphaMode::Opaque ? -1.0f : m.alphaCutoff, m.normalScale, 0.0f);
  g.textures = glm::ivec4(m.baseColorTexture, m.normalTexture, m.baseColorUv, m.normalUv);
  g.flags = glm::uvec4(uint32_t(m.alphaMode), m.doubleSided ? 1u : 0u, m.unlit ? 1u : 0u, 0u);
  auto rows = [](const glm::mat3& t, glm::vec4& r0, glm::vec4& r1) {
    r0 = glm::vec4(t[0][0], t[1][0], t[2][0], 0.0f);
    r1 = glm::vec4(t[0][1], t[1][1], t[2][1], 0.0f);
  };
  rows(m.baseUvTransform, g.baseUv0, g.baseUv1);
  rows(m.normalUvTransform, g.normalUv0, g.normalUv1);
  return g;
}

static uint32_t mipCount(uint32_t w, uint32_t h) {
  uint32_t n = 1;
  while ((w | h) >> n) ++n;
  return n;
}

uint32_t drawVariant(const Scene& scene, uint32_t instance) {
  const MaterialDesc& m = scene.materials[scene.meshes[scene.instances[instance].mesh].material];
  return (m.alphaMode != AlphaMode::Opaque ? 4u : 0u) + (m.normalTexture >= 0 ? 2u : 0u) + (m.baseColorTexture >= 0 ? 1u : 0u);
}

std::string drawVariantName(uint32_t v) {
  const DrawVariantBits b = drawVariantBits(v);
  return std::string(b.alpha ? ".alpha" : ".opaque") + (b.normalMap ? ".normal_map" : "") + (b.baseTexture ? ".base_texture" : "");
}

void uploadScene(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  const Scene& scene = *r.scene;
  const VkBufferUsageFlags dst = VK_BUFFER_USAGE_TRANSFER_DST_BIT;

  // Geometry. Empty scenes still get valid (tiny) buffers.
  VkDeviceSize vbytes = std::max<VkDeviceSize>(scene.vertices.size() * sizeof(Vertex), 64);
  VkDeviceSize ibytes = std::max<VkDeviceSize>(scene.indices.size() * sizeof(uint32_t), 64);
  // Also storage buffers: gbuffer_resolve (--gbuffer visibility) fetches each pixel's triangle.
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  r.vertexBuffer = createBuffer(ctx, vbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | storage | dst, MemoryUse::Device, "vertices");
  r.indexBuffer = createBuffer(ctx, ibytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | storage | dst, MemoryUse::Device, "indices");
  uploadBuffer(ctx, r.vertexBuffer, scene.vertices.data(), scene.vertices.size() * sizeof(Vertex));
  uploadBuffer(ctx, r.indexBuffer, scene.indices.data(), scene.indices.size() * sizeof(uint32_t));

  // The light volume: a non-indexed icosahedron, 60 vertices.
  const Icosahedron& ico = icosahedron();
  std::vector<glm::vec3> icoVerts;
  for (uint16_t i : ico.indices) icoVerts.push_back(ico.vertices[i]);
  r.icosahedronBuffer = createBuffer(ctx, icoVerts.size() * sizeof(glm::vec3), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | dst,
                                     MemoryUse::Device, "light_volume");
  uploadBuffer(ctx, r.icosahedronBuffer, icoVerts.data(), icoVerts.size() * sizeof(glm::vec3));

  std::vector<gpu::Material> materials;
  for (const MaterialDesc& m : scene.materials) materials.push_back(toGpu(m));
  if (materials.empty()) materials.push_back(toGpu(MaterialDesc{}));
  r.materialBuffer = createBuffer(ctx, materials.size() * sizeof(gpu::Material),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | dst, MemoryUse::Device, "materials");
  uploadBuffer(ctx, r.materialBuffer, materials.data(), materials.size() * sizeof(gpu::Material));

  // Textures (RGBA8, full mip chain), then the stand-ins for materials without textures:
  // white base colour and a flat normal.
  std::vector<Texture> textures = scene.textures;
  textures.push_back(Texture{"white", 1, 1, {255, 255, 255, 255}, true, true});
  textures.push_back(Texture{"flat_normal", 1, 1, {128, 128, 255, 255}, false, true});
  for (const Texture& t : textures) {
    ImageDesc d;
    d.format = t.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    d.width = t.width;
    d.height = t.height;
    d.mipLevels = mipCount(t.width, t.height);
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.name = t.name.c_str();
    Image img = createImage(ctx, d);
    uploadTexture(ctx, img, t.rgba8);
    r.textures.push_back(img);
  }
}

void createDescriptors(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  r.samplerRepeat =
      makeSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, false, VK_LOD_CLAMP_NONE, "sampler.repeat");
  r.samplerClamp =
      makeSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false, VK_LOD_CLAMP_NONE, "sampler.clamp");
  r.samplerShadow = makeSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER, true, 0.0f, "sampler.shadow");
  r.samplerPoint = makeSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false, 0.0f, "sampler.point");

  // Set 0: scene + frame.
  const VkShaderStageFlags all = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
  VkDescriptorSetLayoutBinding sceneBindings[] = {
      {gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, all, nullptr},
      {gpu::kBindingDraws, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingMaterials, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingVisible, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingLightCounts, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingVisiblePositions, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
  };
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.bindingCount = uint32_t(std::size(sceneBindings));
  lci.pBindings = sceneBindings;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &lci, nullptr, &r.sceneSetLayout));
  setName(ctx, uint64_t(r.sceneSetLayout), VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, "set0.scene");

  // Set 1: pushed per pass.
  VkDescriptorSetLayoutBinding passBindings[] = {
      {gpu::kBindingAlbedo, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {gpu::kBindingNormal, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {gpu::kBindingDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {gpu::kBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {gpu::kBindingHdr, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, all, nullptr},
      {gpu::kBindingTileLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingBaseColorTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {gpu::kBindingNormalTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
      {gpu::kBindingHdrStorage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, all, nullptr},
      {gpu::kBindingClusterHeader, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingClusters, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingPixelClusters, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingLightLists, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingBinBits, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingBinBoxes, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingLightDescs, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingLightScratch, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingFairyBits, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingClearTarget, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, all, nullptr},
      {gpu::kBindingGridCells, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {gpu::kBindingGridLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
  };
  static_assert(gpu::kBindingGridLights == 21 && gpu::kPassBindingCount == 22, "passBindings is indexed by binding");
  lci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  lci.bindingCount = gpu::kPassBindingCount;
  lci.pBindings = passBindings;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &lci, nullptr, &r.passSetLayout));
  setName(ctx, uint64_t(r.passSetLayout), VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, "set1.pass");
  // The single-pass path reads the G-buffer and hdr as subpass inputs at the same bindings.
  for (uint32_t b : {gpu::kBindingAlbedo, gpu::kBindingNormal, gpu::kBindingDepth, gpu::kBindingHdr}) {
    passBindings[b].descriptorType = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
    passBindings[b].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
  }
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &lci, nullptr, &r.passSetLayoutInput));
  setName(ctx, uint64_t(r.passSetLayoutInput), VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, "set1.pass_input");

  VkDescriptorSetLayout layouts[] = {r.sceneSetLayout, r.passSetLayout};
  VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pci.setLayoutCount = 2;
  pci.pSetLayouts = layouts;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pci, nullptr, &r.pipelineLayout));
  setName(ctx, uint64_t(r.pipelineLayout), VK_OBJECT_TYPE_PIPELINE_LAYOUT, "pipeline_layout");
  layouts[1] = r.passSetLayoutInput;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pci, nullptr, &r.pipelineLayoutInput));
  setName(ctx, uint64_t(r.pipelineLayoutInput), VK_OBJECT_TYPE_PIPELINE_LAYOUT, "pipeline_layout.input");
}

void sortDraws(Renderer& r) {
  const Scene& scene = *r.scene;
  // Draw order by pipeline variant: opaque before alpha-tested (early depth before discard),
  // without before with a normal texture; by material within a variant (fewer texture pushes).
  for (uint32_t variant = 0; variant < kDrawVariants; ++variant) {
    r.drawVariants[variant] = uint32_t(r.drawOrder.size());
    size_t begin = r.drawOrder.size();
    for (uint32_t i = 0; i < scene.instances.size(); ++i)
      if (scene.meshes[scene.instances[i].mesh].indexCount && drawVariant(scene, i) == variant) r.drawOrder.push_back(i);
    std::stable_sort(r.drawOrder.begin() + begin, r.drawOrder.end(), [&](uint32_t a, uint32_t b) {
      return scene.meshes[scene.instances[a].mesh].material < scene.meshes[scene.instances[b].mesh].material;
    });
  }
  r.drawVariants[kDrawVariants] = uint32_t(r.drawOrder.size());
}

}  // namespace gb
