// Materials: glTF metallic-roughness -> gblens's G-buffer material (albedo, one Blinn-Phong
// specular intensity, alpha mode, double-sided, normal texture, KHR_texture_transform), and the
// textures they sample (one Scene texture per glTF texture and colour space).
//
// Specular mapping (the G-buffer stores one intensity s for a Blinn-Phong lobe of fixed exponent 32,
// white): F0 = mix(0.04, luminance(base colour), metallic); the GGX roughness r corresponds to a
// Blinn-Phong exponent n(r) = 2 / r^4 - 2. A lobe narrower than ours (n > 32) keeps its energy,
// s = F0 * (32 + 8) / (8 pi); a wider one keeps its peak, s = F0 * (n + 8) / (8 pi); s is clamped to
// [0, 1]. With a metallicRoughness texture, s is averaged over (a subsample of) its texels. The
// albedo is the base colour for metals too: without image-based light a metal would be black.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

constexpr double kPi = 3.14159265358979323846;

int imageOf(const Doc& doc, int texture) {
  if (texture < 0) return -1;
  return doc.model.textures[size_t(texture)].source;
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// Mean linear luminance of an sRGB image over at most ~64k texels.
double meanLuminance(const DecodedImage& img) {
  static const auto lut = [] {
    std::array<double, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(i / 255.0);
    return t;
  }();
  size_t texels = size_t(img.width) * img.height, step = std::max<size_t>(1, texels / 65536), n = 0;
  double sum = 0.0;
  for (size_t i = 0; i < texels; i += step, ++n) {
    const uint8_t* p = &img.rgba8[i * 4];
    sum += 0.2126 * lut[p[0]] + 0.7152 * lut[p[1]] + 0.0722 * lut[p[2]];
  }
  return n ? sum / double(n) : 1.0;
}

double specularOf(double metallic, double roughness, double luminance) {
  double f0 = 0.04 + (luminance - 0.04) * std::clamp(metallic, 0.0, 1.0);
  double r = std::clamp(roughness, 0.05, 1.0);
  double n = std::min(2.0 / (r * r * r * r) - 2.0, 32.0);
  return std::clamp(f0 * (n + 8.0) / (8.0 * kPi), 0.0, 1.0);
}

// KHR_texture_transform as the extension's GLSL: translation * rotation * scale.
glm::mat3 textureTransform(const tinygltf::ExtensionMap& ext, int& texCoord) {
  const tinygltf::Value* t = extension(ext, "KHR_texture_transform");
  if (!t) return glm::mat3(1.0f);
  double ox = 0, oy = 0, rotation = 0, sx = 1, sy = 1, uv = 0;
  auto pair = [](const tinygltf::Value* v, double& a, double& b) {
    if (v && v->IsArray() && v->ArrayLen() == 2) {
      number(&v->Get(0), a);
      number(&v->Get(1), b);
    }
  };
  pair(member(*t, "offset"), ox, oy);
  pair(member(*t, "scale"), sx, sy);
  number(member(*t, "rotation"), rotation);
  if (number(member(*t, "texCoord"), uv) && uv >= 0 && uv < 1e6) texCoord = int(uv);
  float c = float(std::cos(rotation)), s = float(std::sin(rotation));
  glm::mat3 translation(1, 0, 0, 0, 1, 0, float(ox), float(oy), 1);
  glm::mat3 rotate(c, s, 0, -s, c, 0, 0, 0, 1);
  glm::mat3 scale(float(sx), 0, 0, 0, float(sy), 0, 0, 0, 1);
  return translation * rotate * scale;
}

int uvSet(const Doc& doc, const std::string& material, const char* slot, int texCoord) {
  if (texCoord <= 1) return texCoord;
  warn(doc, material + ": " + slot + " texture uses TEXCOORD_" + std::to_string(texCoord) +
                "; gblens keeps two UV sets and uses TEXCOORD_0");
  return 0;
}

struct TextureKey {
  int texture;
  bool srgb;
  bool operator<(const TextureKey& o) const { return texture != o.texture ? texture < o.texture : srgb < o.srgb; }
};

}  // namespace

std::vector<bool> imagesNeeded(const Doc& doc) {
  std::vector<bool> needed(doc.model.images.size(), false);
  auto mark = [&](int texture) {
    int image = imageOf(doc, texture);
    if (image >= 0) needed[size_t(image)] = true;
  };
  for (const tinygltf::Material& m : doc.model.materials) {
    mark(m.pbrMetallicRoughness.baseColorTexture.index);
    mark(m.pbrMetallicRoughness.metallicRoughnessTexture.index);
    mark(m.normalTexture.index);
  }
  return needed;
}

namespace {

// Each material's specular intensity from metallic-roughness (see the top of this file), read
// before the pixels move into the scene's textures.
std::vector<float> materialSpecular(const Doc& doc, const std::vector<DecodedImage>& images) {
  const tinygltf::Model& model = doc.model;
  std::vector<float> specular(model.materials.size());
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const auto& pbr = model.materials[i].pbrMetallicRoughness;
    const std::vector<double>& c = pbr.baseColorFactor;
    double luminance = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    int baseImage = imageOf(doc, pbr.baseColorTexture.index);
    if (baseImage >= 0 && !images[size_t(baseImage)].rgba8.empty()) luminance *= meanLuminance(images[size_t(baseImage)]);
    double metallic = std::clamp(pbr.metallicFactor, 0.0, 1.0), roughness = std::clamp(pbr.roughnessFactor, 0.0, 1.0);
    int mrImage = imageOf(doc, pbr.metallicRoughnessTexture.index);
    if (mrImage >= 0 && !images[size_t(mrImage)].rgba8.empty()) {
      const DecodedImage& mr = images[size_t(mrImage)];  // G: roughness, B: metallic
      size_t texels = size_t(mr.width) * mr.height, step = std::max<size_t>(1, texels / 65536), n = 0;
      double sum = 0.0;
      for (size_t t = 0; t < texels; t += step, ++n)
        sum += specularOf(metallic * mr.rgba8[t * 4 + 2] / 255.0, roughness * mr.rgba8[t * 4 + 1] / 255.0, luminance);
      specular[i] = float(n ? sum / double(n) : 0.0);
    } else {
      specular[i] = float(specularOf(metallic, roughness, luminance));
    }
  }
  return specular;
}

// The scene textures: one per (glTF texture, colour space) that a material samples, in first-use
// order; the last user of an image takes its pixels, earlier users copy them. Returns where
// each landed in scene.textures.
std::map<TextureKey, int> buildTextures(Doc& doc, std::vector<DecodedImage>& images) {
  const tinygltf::Model& model = doc.model;
  std::map<TextureKey, int> textureIndex;
  std::vector<TextureKey> order;
  auto want = [&](int texture, bool srgb) {
    if (texture < 0 || imageOf(doc, texture) < 0) return;
    if (textureIndex.emplace(TextureKey{texture, srgb}, int(order.size())).second) order.push_back({texture, srgb});
  };
  for (const tinygltf::Material& m : model.materials) {
    want(m.pbrMetallicRoughness.baseColorTexture.index, true);
    want(m.normalTexture.index, false);
  }
  std::vector<int> usesLeft(images.size(), 0);
  for (const TextureKey& k : order) ++usesLeft[size_t(imageOf(doc, k.texture))];
  for (const TextureKey& k : order) {
    const tinygltf::Texture& gt = model.textures[size_t(k.texture)];
    size_t image = size_t(gt.source);
    Texture t;
    const tinygltf::Image& gi = model.images[image];
    bool fileUri = !gi.uri.empty() && gi.uri.size() < 200 && gi.uri.rfind("data:", 0) != 0;
    t.name = !gt.name.empty() ? gt.name : !gi.name.empty() ? gi.name : fileUri ? gi.uri : "image " + std::to_string(image);
    t.width = images[image].width;
    t.height = images[image].height;
    if (--usesLeft[image] == 0)
      t.rgba8 = std::move(images[image].rgba8);
    else
      t.rgba8 = images[image].rgba8;
    t.srgb = k.srgb;
    if (gt.sampler >= 0) {
      const tinygltf::Sampler& s = model.samplers[size_t(gt.sampler)];
      t.repeat = !(s.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE && s.wrapT == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
      if (s.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT || s.wrapT == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
        ignored(doc, "MIRRORED_REPEAT wrap mode (drawn as REPEAT)");
      if ((s.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) != (s.wrapT == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE))
        ignored(doc, "different wrap modes for S and T (drawn as REPEAT)");
    }
    doc.scene->textures.push_back(std::move(t));
  }
  return textureIndex;
}

// Material i as gblens draws it: base colour and normal textures with their UV sets and
// transforms, alpha mode, double-sided, specular; what the G-buffer cannot hold is reported.
MaterialDesc materialDesc(Doc& doc, size_t i, const std::map<TextureKey, int>& textureIndex, float specular) {
  const tinygltf::Material& m = doc.model.materials[i];
  const auto& pbr = m.pbrMetallicRoughness;
  const std::string el = named("material", i, m.name);
  MaterialDesc d;
  d.name = m.name.empty() ? "material " + std::to_string(i) : m.name;
  d.baseColor = glm::vec4(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]), float(pbr.baseColorFactor[2]),
                          float(pbr.baseColorFactor[3]));
  auto lookup = [&](int texture, bool srgb) {
    auto it = textureIndex.find({texture, srgb});
    return it == textureIndex.end() ? -1 : it->second;
  };
  if (pbr.baseColorTexture.index >= 0) {
    d.baseColorTexture = lookup(pbr.baseColorTexture.index, true);
    int uv = pbr.baseColorTexture.texCoord;
    d.baseUvTransform = textureTransform(pbr.baseColorTexture.extensions, uv);
    d.baseColorUv = uvSet(doc, el, "baseColor", uv);
  }
  if (m.normalTexture.index >= 0) {
    d.normalTexture = lookup(m.normalTexture.index, false);
    int uv = m.normalTexture.texCoord;
    d.normalUvTransform = textureTransform(m.normalTexture.extensions, uv);
    d.normalUv = uvSet(doc, el, "normal", uv);
    d.normalScale = std::isfinite(m.normalTexture.scale) ? float(m.normalTexture.scale) : 1.0f;
  }
  if (m.alphaMode == "MASK") {
    d.alphaMode = AlphaMode::Mask;
    d.alphaCutoff = float(m.alphaCutoff);
  } else if (m.alphaMode == "BLEND") {
    d.alphaMode = AlphaMode::Blend;
    d.alphaCutoff = 0.5f;
    warn(doc, el + ": alphaMode BLEND drawn as MASK at alpha 0.5 (a deferred G-buffer holds one surface per pixel)");
  }
  d.doubleSided = m.doubleSided;
  d.specular = specular;
  if (m.emissiveTexture.index >= 0 ||
      (m.emissiveFactor.size() == 3 && (m.emissiveFactor[0] > 0 || m.emissiveFactor[1] > 0 || m.emissiveFactor[2] > 0)))
    ignored(doc, "emissive colour (the G-buffer has no emission target)");
  if (m.occlusionTexture.index >= 0) ignored(doc, "occlusion textures");
  return d;
}

}  // namespace

void buildMaterials(Doc& doc, std::vector<DecodedImage>& images) {
  const std::vector<float> specular = materialSpecular(doc, images);
  const std::map<TextureKey, int> textureIndex = buildTextures(doc, images);
  for (size_t i = 0; i < doc.model.materials.size(); ++i)
    doc.scene->materials.push_back(materialDesc(doc, i, textureIndex, specular[i]));
}

}  // namespace gb::gltf
