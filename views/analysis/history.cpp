// A history target checked on one pair N-1 -> N (history.h): the comparable pixels are N's surface
// points that N-1 saw where its camera puts them (the depth a bilinear sample of N-1 reads there is
// the point's, the same id at its four texels where the layout has ids); there each hypothesis predicts the stored
// history, and the median of |H - prediction| over the storages' rounding says which ones fit.
#include "views/analysis/history.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/decode.h"
#include "renderer/core/statistics.h"
#include "views/analysis/decoded_image.h"
#include "views/analysis/view_table.h"

namespace gb {

namespace {

// A quantity's decoded values over a whole frame, and what its storage rounds by.
struct HistoryPlane {
  std::vector<double> values;
  uint32_t components = 0, width = 0;
  const Quantity* q = nullptr;
  PixelType type = PixelType::F32;
  Encoding encoding = Encoding::Float;
  bool srgb = false;
  const double* at(uint32_t x, uint32_t y) const { return &values[(size_t(y) * width + x) * components]; }
};

bool historyPlane(const FrameSnapshot& f, const std::string& name, HistoryPlane& out) {
  const Quantity* q = f.layout.findByName(name);
  const std::vector<ViewDef> views = layoutViews(f.layout);
  const int v = findView(views, name);
  const TargetImage* img = q ? layoutImage(f, q->target) : nullptr;
  if (!q || v < 0 || !img || img->image.width != f.camera.width || img->image.height != f.camera.height) return false;
  out.q = q, out.width = f.camera.width;
  out.values = decodedImage<double>(f, views[size_t(v)]);
  out.components = decodedComponents(f, views[size_t(v)]);
  out.type = img->image.type, out.encoding = img->image.encoding;
  out.srgb = q->color == ColorEncoding::Srgb || out.encoding == Encoding::Srgb;
  return true;
}

double srgbDecoded(double s) { return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4); }
double srgbEncoded(double l) { return l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

// One storage step at a decoded value, in decoded units.
double decodedUlp(const HistoryPlane& p, double v) {
  if (p.srgb) {
    const double s = srgbEncoded(std::clamp(v, 0.0, 1.0)), u = storageUlp(p.type, p.encoding, s);
    return 0.5 * (srgbDecoded(std::min(1.0, s + u)) - srgbDecoded(std::max(0.0, s - u)));
  }
  const double scale = p.q->scale != 0.0 ? p.q->scale : 1.0;
  return storageUlp(p.type, p.encoding, (v - p.q->bias) / scale) * std::fabs(scale);
}

// The four texels a bilinear sample at continuous pixel coordinates reads (texel centres at i + 0.5).
struct Taps {
  uint32_t x0 = 0, y0 = 0;
  double fx = 0.0, fy = 0.0;
};
std::optional<Taps> tapsAt(glm::dvec2 at, uint32_t w, uint32_t h) {
  const glm::dvec2 s = at - glm::dvec2(0.5);
  const double x0 = std::floor(s.x), y0 = std::floor(s.y);
  if (!(x0 >= 0.0 && y0 >= 0.0 && x0 + 1.0 < w && y0 + 1.0 < h)) return std::nullopt;
  return Taps{uint32_t(x0), uint32_t(y0), s.x - x0, s.y - y0};
}

bool bilinear(const HistoryPlane& p, const Taps& t, uint32_t n, double* out) {
  const double* a = p.at(t.x0, t.y0);
  const double* b = p.at(t.x0 + 1, t.y0);
  const double* c = p.at(t.x0, t.y0 + 1);
  const double* d = p.at(t.x0 + 1, t.y0 + 1);
  for (uint32_t k = 0; k < n; ++k) {
    out[k] = (a[k] * (1 - t.fx) + b[k] * t.fx) * (1 - t.fy) + (c[k] * (1 - t.fx) + d[k] * t.fx) * t.fy;
    if (!std::isfinite(out[k])) return false;
  }
  return true;
}

// Whether `to` saw `world` (shown at `from`'s texel (x, y)) where a bilinear sample reads: the depths
// of the four texels, interpolated as the sample is, within 1 % of the point's depth there (a depth
// edge between the texels fails it), and the same id at each texel where the layout has ids.
bool sawPoint(const FrameSnapshot& from, uint32_t x, uint32_t y, const FrameSnapshot& to, glm::dvec2 jitter, const Taps& t,
              const glm::dvec3& world) {
  const std::optional<double> here = viewDepthOf(to.camera, world);
  if (!here) return false;
  const Quantity* id = from.layout.find(QuantityKind::Id);
  const bool ids = id && holds(from, *id, x, y);
  double depth = 0.0;
  for (uint32_t k = 0; k < 4; ++k) {
    const uint32_t tx = t.x0 + (k & 1), ty = t.y0 + (k >> 1);
    const std::optional<glm::dvec3> p = surfacePoint(to, tx, ty, jitter);
    const std::optional<double> there = p ? viewDepthOf(to.camera, *p) : std::nullopt;
    if (!there) return false;
    depth += *there * ((k & 1) ? t.fx : 1.0 - t.fx) * ((k >> 1) ? t.fy : 1.0 - t.fy);
    if (ids && (!holds(to, *id, tx, ty) || decodeInteger(to, *id, tx, ty) != decodeInteger(from, *id, x, y))) return false;
  }
  return std::fabs(depth - *here) <= 0.01 * *here + 1e-4;
}

// Per hypothesis: the difference and the difference over the bound at each pixel it was evaluated on.
struct Tally {
  std::vector<double> diff, ratio;
};

void tally(Tally& t, const double* h, const HistoryPlane& H, const double* pred, const HistoryPlane& P, uint32_t n,
           double fixed) {
  double d = 0.0, r = 0.0;
  for (uint32_t k = 0; k < n; ++k) {
    if (!std::isfinite(pred[k])) return;
    const double e = std::fabs(h[k] - pred[k]);
    const double b = fixed > 0.0 ? fixed : decodedUlp(H, h[k]) + decodedUlp(P, pred[k]);
    d = std::max(d, e), r = std::max(r, e / std::max(b, 1e-300));
  }
  t.diff.push_back(d), t.ratio.push_back(r);
}

enum Hyp : size_t { kPrevious, kCurrent, kStale, kFrozen, kThisFrame, kHypotheses };
const char* const kHypNames[kHypotheses] = {"previous", "current", "stale", "frozen", "this_frame"};

// The stale prediction under history_space current: X(N-2) sampled where N-1's point was in N-2.
bool staleCurrent(const FrameSnapshot& P, glm::dvec2 jp, const FrameSnapshot& B, glm::dvec2 jb, const HistoryPlane& Xb,
                  uint32_t x, uint32_t y, uint32_t n, double* out) {
  const std::optional<glm::dvec3> p = surfacePoint(P, x, y, jp);
  const std::optional<glm::dvec2> u = p ? projectToPixel(B.camera, *p) : std::nullopt;
  const std::optional<Taps> t = u ? tapsAt(*u + jb, B.camera.width, B.camera.height) : std::nullopt;
  return t && sawPoint(P, x, y, B, jb, *t, *p) && bilinear(Xb, *t, n, out);
}

// The hypothesis that alone fits (others clearly above the bound), "none", or "" with the reason.
void decide(const std::vector<Tally>& tallies, uint64_t comparable, uint64_t zeros, HistoryPair& out) {
  const size_t least = std::max<size_t>(16, comparable / 10);
  for (size_t k = 0; k < kHypotheses; ++k) {
    HistoryHypothesis h;
    h.name = kHypNames[k];
    h.pixels = tallies[k].diff.size();
    h.tested = h.pixels >= least;
    if (h.tested) {
      h.medianDifference = median(tallies[k].diff), h.medianRatio = median(tallies[k].ratio);
      h.fits = h.medianRatio <= 1.0;
    }
    out.hypotheses.push_back(h);
  }
  if (comparable < 16) {
    out.undecided = "fewer than 16 pixels of frame " + std::to_string(out.current) + " show a point frame " +
                    std::to_string(out.previous) + " saw there (no depth, or everything moved)";
    return;
  }
  if (double(zeros) >= 0.99 * double(comparable)) {
    out.undecided = "the history is empty (zero) in frame " + std::to_string(out.current) + ": the first frame, or a reset";
    return;
  }
  const HistoryHypothesis* best = nullptr;
  for (const HistoryHypothesis& h : out.hypotheses)
    if (h.tested && (!best || h.medianRatio < best->medianRatio)) best = &h;
  if (!best->fits) {
    out.found = "none";
    return;
  }
  for (const HistoryHypothesis& h : out.hypotheses)
    if (&h != best && h.tested && h.medianRatio <= 2.0) {
      out.undecided = "\"" + best->name + "\" and \"" + h.name + "\" fit alike (" + out.of +
                      " or the camera hardly changed between the frames)";
      return;
    }
  out.found = best->name;
}

}  // namespace

std::vector<std::string> historyDifferences(const std::string& declared, const std::string& found) {
  if (found.empty() || found == declared) return {};
  if (found == "none")
    return {"the history holds none of the previous frame's X (same pixels or reprojected), X two frames back, the previous "
            "history or this frame's X: another quantity, or filtered beyond the bound"};
  if (found == "previous")
    return {"the history is not reprojected (it holds the previous frame's X at the same pixels; the layout says "
            "history_space current)"};
  if (found == "current")
    return {"the history is reprojected into this frame's pixels (the layout says history_space previous)"};
  if (found == "stale") return {"the history is one frame stale (it holds X of two frames back)"};
  if (found == "frozen") return {"the history never updates (each frame holds the previous frame's history)"};
  return {"the history is this frame's X, not the previous one's"};
}

bool checkHistoryPair(const TemporalFrame* before, const TemporalFrame& previous, const TemporalFrame& current,
                      const Quantity& history, const HistoryOptions& o, HistoryPair& out, std::string& error) {
  out = HistoryPair{};
  out.previous = previous.number, out.current = current.number;
  out.history = history.name, out.of = history.historyOf, out.declared = history.historyCurrent ? "current" : "previous";
  const FrameSnapshot& C = *current.frame;
  const FrameSnapshot& P = *previous.frame;
  const FrameSnapshot* B = before ? before->frame : nullptr;
  const uint32_t w = C.camera.width, h = C.camera.height;
  HistoryPlane H, Xn, Xp, Hp, Xb;
  for (auto [f, name, plane] : {std::tuple{&C, &history.name, &H}, {&C, &history.historyOf, &Xn}, {&P, &history.historyOf, &Xp}})
    if (f->camera.width != w || f->camera.height != h || !historyPlane(*f, *name, *plane)) {
      error = "frame " + std::to_string(f == &C ? current.number : previous.number) + ": no quantity " + *name +
              " over the whole " + std::to_string(w) + "x" + std::to_string(h) + " image";
      return false;
    }
  const bool frozen = historyPlane(P, history.name, Hp) && Hp.components == H.components;
  const bool stale = B && B->camera.width == w && B->camera.height == h && historyPlane(*B, history.historyOf, Xb);
  const uint32_t n = std::min({H.components, Xn.components, Xp.components, stale ? Xb.components : 4u, 4u});
  const glm::dvec2 jc = current.jitter.value_or(glm::dvec2(0.0)), jp = previous.jitter.value_or(glm::dvec2(0.0));
  const glm::dvec2 jb = before ? before->jitter.value_or(glm::dvec2(0.0)) : glm::dvec2(0.0);
  std::vector<Tally> t(kHypotheses);
  uint64_t zeros = 0;
  double pred[4];
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double *hv = H.at(x, y), *xn = Xn.at(x, y);
      if (!std::all_of(hv, hv + n, [](double v) { return std::isfinite(v); })) continue;
      const std::optional<glm::dvec3> p = surfacePoint(C, x, y, jc);
      const std::optional<glm::dvec2> u = p ? projectToPixel(P.camera, *p) : std::nullopt;
      const std::optional<Taps> taps = u ? tapsAt(*u + jp, w, h) : std::nullopt;
      if (!taps || !sawPoint(C, x, y, P, jp, *taps, *p) || !bilinear(Xp, *taps, n, pred)) continue;
      ++out.comparable;
      zeros += std::all_of(hv, hv + n, [](double v) { return v == 0.0; });
      tally(t[kCurrent], hv, H, pred, Xp, n, o.bound);
      tally(t[kPrevious], hv, H, Xp.at(x, y), Xp, n, o.bound);
      tally(t[kThisFrame], hv, H, xn, Xn, n, o.bound);
      if (frozen) tally(t[kFrozen], hv, H, Hp.at(x, y), Hp, n, o.bound);
      if (stale && !history.historyCurrent) tally(t[kStale], hv, H, Xb.at(x, y), Xb, n, o.bound);
      if (stale && history.historyCurrent && staleCurrent(P, jp, *B, jb, Xb, x, y, n, pred))
        tally(t[kStale], hv, H, pred, Xb, n, o.bound);
    }
  decide(t, out.comparable, zeros, out);
  out.differences = historyDifferences(out.declared, out.found);
  return true;
}

}  // namespace gb
