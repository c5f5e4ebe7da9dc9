// Gathering an import from a RenderDoc capture (see import_renderdoc.h): list it, choose the event,
// read the targets' texels and the camera's buffer, check formats against the layout.
#include "views/import/import_renderdoc.h"

#include <algorithm>
#include <optional>

#include "renderer/core/texels.h"

namespace gb {

namespace {

// The GPU format a layout storage format names, if it is one (rgba16f, d32s8, ...).
std::optional<TexelFormat> gpuFormat(const StorageFormat& f) {
  for (int i = 0; i <= int(TexelFormat::D16); ++i)
    if (f.name == texelFormatInfo(TexelFormat(i)).name) return TexelFormat(i);
  return std::nullopt;
}

// The event every target is read after: --event, the end of --pass, or 0 (after each one's last pass).
bool chooseEvent(const RenderDocImport& r, const RdcListing& l, uint32_t& event, std::string& error) {
  event = 0;
  if (r.event) {
    if (r.event > l.lastEvent) {
      error = r.rdc + ": --event " + std::to_string(r.event) + ": out of range (the capture's events are 1.." +
              std::to_string(l.lastEvent) + ")";
      return false;
    }
    event = r.event;
    return true;
  }
  if (r.pass.empty()) return true;
  std::vector<const RdcPass*> named;
  std::string names;
  for (const RdcPass& p : l.passes) {
    if (p.name == r.pass) named.push_back(&p);
    if (names.find(p.name) == std::string::npos) names += (names.empty() ? "" : ", ") + p.name;
  }
  if (named.empty()) {
    error = r.rdc + ": --pass \"" + r.pass + "\": no pass of that name (passes: " + names + ")";
    return false;
  }
  // Regions of one name nested in the first (a render-pass group and its pass): the end of the outermost.
  for (const RdcPass* p : named)
    if (p->firstEvent < named[0]->firstEvent || p->lastEvent > named[0]->lastEvent) {
      error = r.rdc + ": --pass \"" + r.pass + "\": " + std::to_string(named.size()) +
              " separate passes have that name (see --list); give --event";
      return false;
    }
  event = named[0]->lastEvent;
  return true;
}

// Whether a texture of this name exists and a pass (label region or render pass) up to `event` (0: any)
// writes it: gblens's frames keep 1x1 stand-ins for the targets an option turns off.
bool writtenByAPass(const RdcListing& l, const std::string& texture, uint32_t event) {
  for (const RdcPass& p : l.passes)
    if ((!event || p.firstEvent <= event) && std::find(p.writes.begin(), p.writes.end(), texture) != p.writes.end())
      return true;
  return false;
}

// A texture of this name that is 1x1 while the layout's other targets' textures are larger: a stand-in
// for a target that a turned-off feature would write (gblens's own frames keep one, `absent` in
// its captures), not the frame's data.
bool standIn(const RdcListing& l, const Layout& layout, const std::string& texture) {
  auto size = [&](const std::string& name) -> const RdcTexture* {
    for (const RdcTexture& t : l.textures)
      if (t.name == name) return &t;
    return nullptr;
  };
  const RdcTexture* t = size(texture);
  if (!t || t->width != 1 || t->height != 1) return false;
  for (const LayoutTarget& other : layout.targets) {
    const RdcTexture* o = size(other.source.kind == TargetSource::Kind::RenderDoc ? other.source.resource : other.name);
    if (o && o->width * o->height > 1) return true;
  }
  return false;
}

// The texels of one target as the capture stores them, checked against the layout's format.
bool checkTexels(const Layout& layout, uint32_t t, const RdcTexels& got, std::string& error) {
  const LayoutTarget& lt = layout.targets[t];
  const std::optional<TexelFormat> want = gpuFormat(lt.format);
  const RdcTexture& tex = got.texture;
  bool same = false;
  if (tex.texelFormat)
    same = want == tex.texelFormat;
  else  // a format gblens does not render to (rg16_snorm, r8_unorm, ...): tightly packed texels of its size
    same = !want && got.sampleBytes == size_t(tex.width) * tex.height * lt.format.packedBytes();
  if (!same) {
    error = layoutTargetWhere(layout, t) + ": format: the capture's texture \"" + lt.source.resource + "\" is " + tex.format +
            ", the layout says " + lt.format.name;
    return false;
  }
  return true;
}

}  // namespace

void takeRenderDocTexels(ImportInput& in, const std::string& target, RdcTexels&& texels) {
  in.renderdocSizes[target] = {texels.texture.width, texels.texture.height};
  if (texels.texture.samples > 1) in.renderdocSamples[target] = texels.texture.samples;
  in.renderdocTexels[target] = std::move(texels.bytes);
}

bool readRenderDocImport(const RenderDocImport& r, ImportInput& in, RenderDocImported& info, std::string& error) {
  if (!listRenderDocCapture(r.rdc, info.listing, error, r.replay)) return false;
  uint32_t event = 0;
  if (!chooseEvent(r, info.listing, event, error)) return false;

  // Which texture each target reads; targets without a source read their own name's, when there is one.
  Layout& layout = in.layout;
  std::vector<std::string> textures;
  std::vector<uint32_t> targets;
  for (uint32_t t = 0; t < layout.targets.size(); ++t) {
    LayoutTarget& lt = layout.targets[t];
    if (lt.source.kind == TargetSource::Kind::None) {
      const char* why = !writtenByAPass(info.listing, lt.name, event) ? "no pass of the capture writes a texture of that name"
                        : !lt.width && standIn(info.listing, layout, lt.name)
                            ? "its texture is a 1x1 stand-in (a feature that writes it is off)"
                            : nullptr;
      if (why) {
        in.leftOut.insert(lt.name);
        info.leftOut.push_back({lt.name, why});
        continue;
      }
      lt.source.kind = TargetSource::Kind::RenderDoc;
      lt.source.resource = lt.name;
    }
    if (lt.source.kind != TargetSource::Kind::RenderDoc) continue;  // files: read by importFrame
    textures.push_back(lt.source.resource);
    targets.push_back(t);
  }

  std::vector<RdcTexels> texels;
  if (!textures.empty() && !readRenderDocTexels(r.rdc, event, textures, texels, error, r.replay)) return false;
  for (size_t k = 0; k < texels.size() && k < targets.size(); ++k) {
    const uint32_t t = targets[k];
    if (!checkTexels(layout, t, texels[k], error)) return false;
    const std::string& target = layout.targets[t].name;
    info.reads.push_back({target, texels[k].texture.name, texels[k].texture.format, texels[k].event});
    takeRenderDocTexels(in, target, std::move(texels[k]));
  }

  in.capture = r.rdc;
  const std::optional<LayoutCamera::BufferMatrix>& buffer = layout.camera.renderdoc;
  if (buffer && !r.cameraGiven) {
    RdcBufferRead at;
    if (!readRenderDocBuffer(r.rdc, event, buffer->buffer, in.renderdocCameraBuffer, error, r.replay, &at)) {
      error = (layout.file.empty() ? std::string("layout") : layout.file) + ": camera: renderdoc: buffer: " + error;
      return false;
    }
    in.renderdocCameraBufferAt = info.camera = " (#" + std::to_string(at.id) + ") at event " + std::to_string(at.event);
  }
  return true;
}

}  // namespace gb
