// The layout as the gblens layer streams it (which attachment each target is), the request that
// tells the layer so, and a streamed frame decoded through import's assembly (import.h).
#include <algorithm>
#include <atomic>

#include "renderer/core/layout_json.h"
#include "renderer/core/texels.h"
#include "views/import/import.h"
#include "views/live/live.h"
#include "views/live/live_wire.h"

namespace gb {

namespace {

// Targets the layout gives a source (else: the image of the target's own name, if the application
// has one), told apart in the request so that the layer reports only those when they never come.
std::vector<bool> explicitSources(const Layout& original) {
  std::vector<bool> e;
  for (const LayoutTarget& t : original.targets) e.push_back(t.source.kind != TargetSource::Kind::None);
  return e;
}

}  // namespace

bool liveLayout(Layout& layout, std::string& error) {
  for (uint32_t t = 0; t < layout.targets.size(); ++t) {
    TargetSource& s = layout.targets[t].source;
    switch (s.kind) {
      case TargetSource::Kind::Live: break;
      case TargetSource::Kind::None:
        s.kind = TargetSource::Kind::Live;
        s.live.name = layout.targets[t].name;
        break;
      case TargetSource::Kind::RenderDoc:
        if (!s.resource.empty() && s.resource[0] == '#') {
          error = layoutTargetWhere(layout, t) + ": source.renderdoc: \"" + s.resource +
                  "\" is a RenderDoc resource id; a running application's image is named by {\"live\": ...}";
          return false;
        }
        s.kind = TargetSource::Kind::Live;
        s.live.name = s.resource;  // a RenderDoc texture name is the image's debug name
        break;
      default:
        error = layoutTargetWhere(layout, t) + ": source.file: gblens attach streams render-pass attachments; give "
                "{\"live\": ...} (docs/layout-format.md) or no source (the image of the target's name)";
        return false;
    }
  }
  return true;
}

nlohmann::json liveRequest(const Layout& original, const LiveOptions& o) {
  Layout live = original;
  std::string unused;
  liveLayout(live, unused);
  const std::vector<bool> given = explicitSources(original);
  nlohmann::json targets = nlohmann::json::array();
  for (uint32_t t = 0; t < live.targets.size(); ++t) {
    const LayoutTarget& lt = live.targets[t];
    targets.push_back({{"name", lt.name}, {"format", lt.format.name}, {"explicit", bool(given[t])},
                       {"live", livePickJson(lt.source.live)}});
  }
  nlohmann::json camera = nullptr;
  if (const auto& b = original.camera.renderdoc)
    camera = {{"buffer", b->buffer}, {"bytes", std::max(b->viewOffset, b->clipOffset) + 64}};
  if (const auto& b = original.camera.live) {
    nlohmann::json live = {{"pass", b->passIndex >= 0 ? nlohmann::json(b->passIndex) : nlohmann::json(b->pass)},
                           {"set", b->set}, {"binding", b->binding}, {"index", b->index}, {"push_constants", b->pushConstants}};
    camera = {{"live", live}, {"bytes", std::max(b->matrices.viewOffset, b->matrices.clipOffset) + 64}};
  }
  nlohmann::json r = {{"type", wire::kRequest}, {"version", wire::kVersion}, {"every", o.every},
                      {"suggest", o.suggest}, {"give_up", o.giveUpFrames}, {"camera", camera}, {"targets", targets}};
  if (o.captureFrame >= 0) r["only_frame"] = o.captureFrame;
  if (o.captureFrame >= 0 && o.captureLast > o.captureFrame) r["last_frame"] = o.captureLast;
  if (o.ringOffThread) r["ring_off_thread"] = true;
  if (o.paced) r["paced"] = true;
  if (o.boundBuffersPass >= 0) r["bound_buffers"] = {{"pass", o.boundBuffersPass}, {"max_bytes", o.boundBuffersMaxBytes}};
  return r;
}

const uint8_t* LiveSession::bytesAt(const nlohmann::json& where, size_t& bytes) const {
  auto it = buffers_.find(where.value("buffer", 0u));
  const uint64_t offset = where.value("offset", uint64_t(0));
  bytes = where.value("bytes", size_t(0));
  if (it == buffers_.end() || offset > it->second.size || bytes > it->second.size - offset) return nullptr;
  return it->second.data + offset;
}

bool LiveSession::untouched(const nlohmann::json& frame) const {
  for (const nlohmann::json& w : frame.value("writes", nlohmann::json::array())) {
    auto it = buffers_.find(w[0].get<uint32_t>());
    if (it == buffers_.end() || it->second.size < sizeof(uint64_t)) return false;
    // The layer's std::atomic<uint64_t> at the start of the file (lock-free: the same in both processes).
    const auto* count = reinterpret_cast<const std::atomic<uint64_t>*>(it->second.data);
    if (count->load() != w[1].get<uint64_t>()) return false;
  }
  return true;
}

namespace {

bool samePick(const TargetSource::LivePick& a, const TargetSource::LivePick& b) {
  return a.pass == b.pass && a.passIndex == b.passIndex && a.name == b.name && a.color == b.color && a.depth == b.depth &&
         a.format == b.format;
}

}  // namespace

// The same buffer source of the camera (the same bytes are copied).
static bool sameCamera(const LayoutCamera& a, const LayoutCamera& b) {
  if (a.renderdoc.has_value() != b.renderdoc.has_value() || a.live.has_value() != b.live.has_value()) return false;
  if (a.renderdoc && a.renderdoc->buffer != b.renderdoc->buffer) return false;
  if (a.live && (a.live->pass != b.live->pass || a.live->passIndex != b.live->passIndex || a.live->set != b.live->set ||
                 a.live->binding != b.live->binding || a.live->index != b.live->index ||
                 a.live->pushConstants != b.live->pushConstants))
    return false;
  return true;
}

bool LiveSession::setLayout(const nlohmann::json& json, std::string& error) {
  Layout l;
  if (!parseLayout(json, "layout", l, error) || !liveLayout(l, error)) return false;
  if (l.targets.size() != layout_.targets.size()) {
    error = "the layout has " + std::to_string(l.targets.size()) + " targets, the stream " + std::to_string(layout_.targets.size());
    return false;
  }
  for (size_t t = 0; t < l.targets.size(); ++t)
    if (l.targets[t].format.name != layout_.targets[t].format.name ||
        l.targets[t].source.kind != layout_.targets[t].source.kind ||
        !samePick(l.targets[t].source.live, layout_.targets[t].source.live)) {
      error = "target \"" + l.targets[t].name + "\": its format or live source is not the stream's \"" + layout_.targets[t].name + "\"";
      return false;
    }
  // A camera the stream copies from the start is the stream's; a camera.live that the bound buffers
  // this stream copies hold (attach --suggest's refined draft) can come later.
  const bool fromBound = l.camera.live && !layout_.camera.live && !layout_.camera.renderdoc &&
                         options_.boundBuffersPass >= 0 && l.camera.live->passIndex == options_.boundBuffersPass;
  if (!fromBound && (l.camera.renderdoc || layout_.camera.renderdoc || l.camera.live || layout_.camera.live) &&
      !sameCamera(l.camera, layout_.camera)) {
    error = "camera: a layout reading the camera from a buffer is streamed from the start";
    return false;
  }
  layout_ = std::move(l);
  return true;
}

// bound_buffers: each range's bytes out of the shared memory, as a RenderDoc draw state's binding.
bool LiveSession::decodeBoundBuffers(const nlohmann::json& frame, std::string& error) {
  decodedBound_.clear();
  for (const nlohmann::json& b : frame.value("bound_buffers", nlohmann::json::array())) {
    size_t bytes = 0;
    const uint8_t* data = bytesAt(b.value("data", nlohmann::json::object()), bytes);
    if (!data) {
      error = "frame " + std::to_string(frame.value("stream", 0)) + ": a bound buffer lies outside the shared memory";
      return false;
    }
    RdcBinding r;
    r.kind = b.value("kind", "");
    r.bound = true;
    r.offset = b.value("offset", uint64_t(0));
    r.data.assign(data, data + bytes);
    if (r.kind == "push_constants") {
      r.name = "push constants";
      r.range = r.bytes = b.value("size", uint64_t(0));
    } else {
      r.set = b.value("set", 0u), r.binding = b.value("binding", 0u), r.index = b.value("index", 0u);
      r.name = b.value("name", "");
      if (r.name.empty()) r.name = "set " + std::to_string(r.set) + " binding " + std::to_string(r.binding);
      r.range = b.value("range", uint64_t(0));
      r.bytes = b.value("size", uint64_t(0));
    }
    decodedBound_.push_back(std::move(r));
  }
  return true;
}

namespace {
std::vector<CpuImage*> planes(TargetImage& t) {  // the image and every sample's plane
  std::vector<CpuImage*> all{&t.image};
  for (size_t k = 1; k < t.samples.size(); ++k) all.push_back(&t.samples[k]);
  if (!t.samples.empty()) all.push_back(&t.samples[0]);
  return all;
}
}  // namespace

void LiveSession::recycle(FrameSnapshot&& frame) {
  size_t buffers = 0;
  for (const TargetImage& t : frame.images) buffers += 1 + t.samples.size();
  pool_.give(std::move(frame), buffers);  // one frame: the next decode takes them all
}

bool LiveSession::decode(const nlohmann::json& frame, FrameSnapshot& out, LiveFrameInfo* info, std::string& error) {
  ImportInput in;
  in.pool = &pool_;
  in.layout = layout_;
  in.layoutDir = layoutDir_;
  const Layout& l = layout_;
  std::vector<std::string> sources(l.targets.size()), absent;
  for (const nlohmann::json& t : frame.value("targets", nlohmann::json::array())) {
    const auto wire = std::find(wireNames_.begin(), wireNames_.end(), t.value("name", ""));
    if (wire == wireNames_.end()) continue;
    const size_t index = size_t(wire - wireNames_.begin());
    const LayoutTarget& lt = l.targets[index];
    if (t.value("format", "") != lt.format.name) {  // the layer refuses these; never decoded as another format
      absent.push_back(lt.name + ": the attachment is " + t.value("format", "?") + ", the layout says " + lt.format.name);
      continue;
    }
    size_t bytes = 0;
    const uint8_t* texels = bytesAt(t, bytes);
    if (!texels) {
      error = "frame " + std::to_string(frame.value("stream", 0)) + ": target \"" + lt.name + "\" lies outside the shared memory";
      return false;
    }
    in.liveTexels[lt.name] = {texels, bytes, t.value("width", 0u), t.value("height", 0u), std::max(1u, t.value("samples", 1u)),
                              t.value("sample_stride", size_t(0))};
    const std::string pass = t.value("pass_name", "");
    const int ordinal = t.value("pass", 0);  // -1: a storage image, copied after the dispatches that bind it
    sources[index] = (ordinal < 0 ? std::string("compute dispatch") : "render pass " + std::to_string(ordinal)) +
                     (pass.empty() ? "" : " \"" + pass + "\"") + ", " + t.value("vk_format", "");
  }
  for (const LayoutTarget& lt : l.targets)
    if (!in.liveTexels.count(lt.name)) {
      in.leftOut.insert(lt.name);
      if (std::none_of(absent.begin(), absent.end(), [&](const std::string& a) { return a.rfind(lt.name + ":", 0) == 0; }))
        absent.push_back(lt.name + ": not in this frame");
    }
  if (in.liveTexels.empty()) {
    error = "frame " + std::to_string(frame.value("stream", 0)) + ": no target of the layout is in it";
    return false;
  }
  if (!decodeBoundBuffers(frame, error)) return false;
  const RdcBinding* bound = nullptr;  // camera.live's range among the bound buffers the frame carries
  if (l.camera.live) {  // decoded as a capture's camera buffer, its matrices at offsets from the bound range's start
    in.layout.camera.renderdoc = l.camera.live->matrices;
    in.layout.camera.renderdoc->buffer = liveCameraText(*l.camera.live);
    in.layout.camera.live.reset();
    const LayoutCamera::LiveBinding& c = *l.camera.live;
    if (c.passIndex == options_.boundBuffersPass)
      for (const RdcBinding& b : decodedBound_)
        if (c.pushConstants ? b.kind == "push_constants"
                            : b.kind != "push_constants" && b.set == c.set && b.binding == c.binding && b.index == c.index)
          bound = &b;
  }
  if (bound) {
    in.renderdocCameraBuffer = bound->data;
  } else if (const auto& b = in.layout.camera.renderdoc) {
    const nlohmann::json& c = frame["camera"];
    if (!c.is_object()) {
      error = std::string("camera: ") + (l.camera.live ? "live: " + b->buffer : "buffer \"" + b->buffer + "\"") +
              " was not copied with this frame (see the layer's reports)";
      return false;
    }
    size_t bytes = 0;
    const uint8_t* camera = bytesAt(c, bytes);
    if (!camera) {
      error = "camera: its bytes lie outside the shared memory";
      return false;
    }
    in.renderdocCameraBuffer.assign(camera, camera + bytes);  // the matrices at the layout's offsets
  }
  if (!importFrame(in, out, error)) return false;
  setImportedOptions(out, options_.options, options_.given);
  // B8G8R8A8 attachments come as the GPU stored them: R and B swapped back here (rgba8 in the layout).
  for (const nlohmann::json& t : frame.value("targets", nlohmann::json::array()))
    if (t.value("bgra", false) && out.indexOf(t.value("name", "")) >= 0) {
      TargetImage& ti = out.images[size_t(out.indexOf(t.value("name", "")))];
      for (CpuImage* image : planes(ti)) swapRedBlue(*image);
    }
  if (info) {
    info->stream = frame.value("stream", uint64_t(0));
    info->appFrame = frame.value("app_frame", uint64_t(0));
    info->sources = sources;
    info->absent = absent;
  }
  return true;
}

}  // namespace gb
