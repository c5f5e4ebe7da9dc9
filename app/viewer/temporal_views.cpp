// A sequence's temporal views (gblens view SEQ; docs/temporal.md "Viewer timeline"): the motion check
// of the pair ending at the frame shown (views/analysis/motion.h checkMotionPair, as `gblens motion`
// checks each pair) and the flicker of a view over the whole sequence (temporal.h flickerSequence, as
// `gblens flicker`), computed in worker threads (temporal_work.cpp). Their maps are views of the frame
// (quantity -1), appended to its views as reference_error.cpp appends the reference error's: decoded
// images drawn, hovered, printed in texels and probed like a capture's. The strip's second row
// (views/ui/timeline_panel.cpp) says the pair's verdict in words and holds the Flicker button.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "app/viewer/temporal_work.h"
#include "views/analysis/visualize.h"

namespace gb {

const std::vector<std::string> kMotionClassNames = {"none", "static", "moving", "disoccluded", "wrong"};
static const char* const kClassWhy[] = {
    "no surface", "agrees with the camera's motion, the previous frame holds the point",
    "disagrees, and the previous frame shows the same surface where the vector points",
    "the point was off screen or hidden in the previous frame",
    "the vector lands on another surface (or says static where the previous frame saw something else)"};

static const Quantity* motionQuantity(const Viewer& v) { return v.captureA.frame.layout.find(QuantityKind::Motion); }

// ---- the views and their images ----------------------------------------------------------------

void appendTemporalViews(const Viewer& v, std::vector<ViewDef>& views) {
  if (!v.sequence) return;
  if (motionQuantity(v)) {
    ViewDef e;
    e.name = "Motion error";
    e.kind = QuantityKind::Count, e.visual = Visual::Count;  // the heat map, from 0 to the largest error
    e.componentNames = {"error"};
    e.channels = 0x1, e.autoRange = true, e.negativeSuspicious = false;
    e.unit = "px: |stored - expected| under the layout's convention";
    e.space = "the motion check of the pair ending at this frame (gblens motion -o: pair_NNNN.exr motion.error)";
    views.push_back(e);
    ViewDef c;
    c.name = "Motion class";
    c.kind = QuantityKind::Id, c.visual = Visual::Id, c.integer = true;
    c.componentNames = {"class"};
    c.channels = 0x1, c.negativeSuspicious = false;
    c.space = "the motion check's pixel classes (gblens motion -o: motion.class)";
    views.push_back(c);
  }
  if (v.temporal && v.temporal->flicker) {
    const TemporalWork& w = *v.temporal;
    for (const char* name : {"Flicker stddev", "Flicker max step"}) {
      ViewDef d;
      d.name = name;
      d.kind = QuantityKind::Scalar, d.visual = Visual::Scalar;
      d.components = std::min(w.flicker->report.components, 4u);
      for (uint32_t c = 0; c < d.components; ++c)
        d.componentNames.push_back(c < w.flickerOf.componentNames.size() ? w.flickerOf.componentNames[c] : std::to_string(c));
      d.channels = 0x1, d.autoRange = true, d.falseColor = true, d.negativeSuspicious = false;
      d.unit = std::string(name == std::string("Flicker stddev") ? "temporal standard deviation" : "largest frame-to-frame change") +
               " of " + w.flickerOf.name;
      d.space = "gblens flicker --quantity " + w.flickerOf.name + ", at the reference frame's pixels";
      views.push_back(d);
    }
  }
}

// An f32 map of `n` channels as a decoded view image (RGBA32F); NaN -> the empty texel (nothing there).
CpuImage decodedFloats(const CpuImage& map, uint32_t n, const std::string& name) {
  CpuImage img = decodedViewImage(name, map.width, map.height);
  uint32_t* out = reinterpret_cast<uint32_t*>(img.data.data());
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      uint32_t* t = out + (size_t(y) * map.width + x) * 4;
      const bool none = std::isnan(map.value(x, y, 0));
      for (uint32_t c = 0; c < 4; ++c) {
        const float f = c < n ? float(map.value(x, y, c)) : 0.0f;
        std::memcpy(&t[c], &f, 4);
        if (none) t[c] = gpu::kEmptyTexel;
      }
    }
  return img;
}

CpuImage decodedClasses(const CpuImage& map) {
  CpuImage img = map;  // u32, one channel: what the GPU's id mapping reads
  img.name = "Motion class";
  img.encoding = Encoding::Uint;
  return img;
}

static std::string sizeNote(const CpuImage& img, const FrameSnapshot& f) {
  if (img.width == f.camera.width && img.height == f.camera.height) return "";
  return "computed for a " + std::to_string(img.width) + "x" + std::to_string(img.height) + " frame; this one is " +
         std::to_string(f.camera.width) + "x" + std::to_string(f.camera.height);
}

// Why the motion views cannot show the frame shown ("" they can).
static std::string motionStatus(const Viewer& v, const TemporalWork* w) {
  const ViewerModel::TimelineUi& t = v.model.timeline;
  const size_t i = size_t(t.shown);
  if (i == 0) return "frame " + std::to_string(t.numbers[0]) + " is the sequence's first: no previous frame to check its motion against";
  if (!w || !w->motion || w->motion->index != i)
    return "checking the motion of frames " + std::to_string(t.numbers[i - 1]) + " -> " + std::to_string(t.numbers[i]) + " ...";
  if (!w->motion->error.empty()) return w->motion->error;
  return sizeNote(w->motionError, v.captureA.frame);
}

void fillTemporalViews(Viewer& v) {
  ViewerModel& m = v.model;
  const TemporalWork* w = v.temporal.get();
  m.classNames["Motion class"] = kMotionClassNames;
  for (size_t k = 0; k < m.views.size() && k < v.decodedA.size(); ++k) {
    const std::string& name = m.views[k].name;
    if (m.views[k].quantity >= 0) continue;
    v.decodedA[k] = CpuImage{};
    std::string& why = m.unavailable[k];
    if (name == "Motion error" || name == "Motion class") {
      why = motionStatus(v, w);
      if (why.empty()) v.decodedA[k] = name == "Motion error" ? w->motionError : w->motionClass;
    } else if (w && w->flicker && (name == "Flicker stddev" || name == "Flicker max step")) {
      const size_t ref = w->flicker->index;
      why = size_t(m.timeline.shown) == ref ? sizeNote(w->flickerStddev, v.captureA.frame)
                                            : "flicker of " + w->flickerOf.name + " at frame " + std::to_string(m.timeline.numbers[ref]) +
                                                  "'s pixels (its reference): show that frame, or F here for this one";
      if (why.empty()) v.decodedA[k] = name == "Flicker stddev" ? w->flickerStddev : w->flickerMaxStep;
    }
    v.rangeKeys.resize(m.views.size());
    v.rangeKeys[k].clear();  // the automatic range of the new image
  }
}

// The maps changed (a result came): the images uploaded again; new views (flicker) rebuild the list.
void refreshTemporalViews(Viewer& v, bool newViews) {
  if (newViews) return setCaptureViews(v);
  fillTemporalViews(v);
  uploadViewImages(v.imagesA, v.ctx, v.decodedA);
  v.model.uiChanged = true;
}

// ---- hover ---------------------------------------------------------------------------------------

std::string temporalHoverText(const Viewer& v, int view, glm::ivec2 texel) {
  const ViewerModel& m = v.model;
  if (view < 0 || size_t(view) >= m.views.size() || size_t(view) >= v.decodedA.size()) return "";
  const ViewDef& d = m.views[size_t(view)];
  const CpuImage& img = v.decodedA[size_t(view)];
  if (d.quantity >= 0 || img.empty() || texel.x < 0 || texel.y < 0 || uint32_t(texel.x) >= img.width || uint32_t(texel.y) >= img.height)
    return "";
  const uint32_t x = uint32_t(texel.x), y = uint32_t(texel.y);
  const TemporalWork& w = *v.temporal;
  char text[400];
  if (d.name == "Motion error" || d.name == "Motion class") {
    const MotionPair& p = w.motion->pair;
    const uint32_t c = w.motionClass.raw(x, y, 0);
    const std::string cls = c < kMotionClassNames.size() ? kMotionClassNames[c] : std::to_string(c);
    if (d.name == "Motion class") {
      std::snprintf(text, sizeof text, "Motion class: %u (%s: %s), frames %lld -> %lld", c, cls.c_str(),
                    c < kMotionClassNames.size() ? kClassWhy[c] : "?", (long long)p.previous, (long long)p.current);
      return text;
    }
    if (img.raw(x, y, 0) == gpu::kEmptyTexel) return "Motion error: no surface (class " + cls + ")";
    std::snprintf(text, sizeof text, "Motion error: %.9g px (|stored - expected| under the layout's convention, frames %lld -> %lld), class %s",
                  img.value(x, y, 0), (long long)p.previous, (long long)p.current, cls.c_str());
    return text;
  }
  const FlickerReport& r = w.flicker->report;
  const int seen = int(r.seen.value(x, y, 0));
  std::string values;
  if (img.raw(x, y, 0) == gpu::kEmptyTexel) values = "no value (fewer than two frames saw the point)";
  else
    for (uint32_t c = 0; c < d.components; ++c) {
      char part[64];
      std::snprintf(part, sizeof part, "%s%s %.6g", c ? " " : "", d.componentNames[c].c_str(), img.value(x, y, c));
      values += part;
    }
  std::snprintf(text, sizeof text, "%s of %s at frame %lld's pixels: %s (seen in %d of %zu frames)", d.name.c_str(),
                w.flickerOf.name.c_str(), (long long)r.reference, values.c_str(), seen, r.frames);
  return text;
}

// A temporal view's value printed in its texel at high zoom: the error, the class and its name, or
// the flicker's selected components (as the hover gives them).
std::optional<TexelValue> temporalTexelValue(const Viewer& v, int view, glm::ivec2 t) {
  const CpuImage& img = v.decodedA[size_t(view)];
  if (img.empty() || t.x < 0 || t.y < 0 || uint32_t(t.x) >= img.width || uint32_t(t.y) >= img.height) return std::nullopt;
  const ViewDef& d = v.model.views[size_t(view)];
  const uint32_t x = uint32_t(t.x), y = uint32_t(t.y);
  TexelValue out;
  char line[64];
  if (d.integer) {
    const uint32_t c = img.raw(x, y, 0);
    out.lines = {std::to_string(c), c < kMotionClassNames.size() ? kMotionClassNames[c] : ""};
    out.value[0] = float(c), out.empty = false;
    return out;
  }
  if (img.raw(x, y, 0) == gpu::kEmptyTexel) return out;  // nothing there
  const uint32_t shown = v.model.settings[size_t(view)].channels;
  for (uint32_t c = 0; c < d.components; ++c) {
    out.value[c] = float(img.value(x, y, c));
    if (!(shown & (1u << c)) && d.components > 1) continue;
    std::snprintf(line, sizeof line, "%s%.4g", d.components > 1 ? (d.componentNames[c] + " ").c_str() : "", img.value(x, y, c));
    out.lines.push_back(line);
  }
  out.empty = false;
  return out;
}

}  // namespace gb
