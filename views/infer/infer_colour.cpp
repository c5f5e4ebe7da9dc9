// Colours (infer_internal.h): what a pass after the G-buffer pass (or a forward pass) writes is lit
// colour — radiance in a float format, display colour otherwise — never albedo. A G-buffer colour
// in [0, 1] is albedo when it is what the light multiplies: across its edges on one surface the lit
// colour jumps with it while lit ÷ albedo does not (the same test picks sRGB or linear decoding).
// Values above 1 are light, not a reflectance. A display image's encoding: decoded as sRGB or as
// linear, which one a common tone map of the radiance (with an exposure fitted) explains.
#include <algorithm>
#include <cmath>

#include "views/infer/infer_internal.h"
#include "views/infer/suggest_guess.h"

namespace gb::infer {

namespace {

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

glm::dvec3 colourAt(const CpuImage& img, uint32_t x, uint32_t y, bool srgbDecode) {
  glm::dvec3 c(channelValues(img, x, y, {0, 1, 2}));
  if (srgbDecode) c = {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)};
  return c;
}

// The lit colour to test albedo against: a float colour a later pass writes.
int radianceTarget(const State& s) {
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    if (target.writer == Writer::Later && target.format.encoding == Encoding::Float && target.format.channels >= 3 &&
        s.image(t))
      return int(t);
  }
  return -1;
}

struct Multiply {
  size_t edges = 0;
  double ratioJump = INFINITY, litJump = INFINITY;  // medians at the candidate's edges
};

// At neighbouring surface pixels where the candidate changes by more than 15 %: how much the lit
// colour and lit ÷ candidate change (relative, luminance). Pixels at a depth step are left out.
Multiply multiplyTest(const State& s, size_t t, int lit, bool srgbDecode) {
  Multiply m;
  const CpuImage& a = *s.image(t);
  const CpuImage& l = *s.image(size_t(lit));
  std::vector<double> ratio, litJump;
  const std::optional<DepthSource> depth = s.hardware ? s.hardware : s.linear;
  for (const glm::uvec2& p : s.pixels)
    for (const glm::uvec2 q : {glm::uvec2(p.x + 1, p.y), glm::uvec2(p.x, p.y + 1)}) {
      if (q.x >= s.width || q.y >= s.height || !s.surface.surface(q.x, q.y)) continue;
      if (depth) {
        const double dp = stored(s, depth->target, depth->channel, p.x, p.y),
                     dq = stored(s, depth->target, depth->channel, q.x, q.y);
        if (std::abs(dp - dq) > 2e-3 * std::max(std::abs(dp), 1e-6) + 1e-6) continue;
      }
      const double ap = luminance(colourAt(a, p.x, p.y, srgbDecode)), aq = luminance(colourAt(a, q.x, q.y, srgbDecode));
      if (std::min(ap, aq) < 0.02 || std::abs(ap - aq) < 0.15 * std::max(ap, aq)) continue;
      const double lp = luminance(colourAt(l, p.x, p.y, false)), lq = luminance(colourAt(l, q.x, q.y, false));
      if (!(std::max(lp, lq) > 0.0)) continue;
      const double rp = lp / ap, rq = lq / aq;
      ratio.push_back(std::abs(rp - rq) / std::max(rp, rq));
      litJump.push_back(std::abs(lp - lq) / std::max(lp, lq));
    }
  m.edges = ratio.size();
  if (m.edges >= 30) m.ratioJump = quantileOf(ratio, 0.5), m.litJump = quantileOf(litJump, 0.5);
  return m;
}

// The tone maps engines use (each applied per channel, to exposure * radiance), for telling how a
// display image is encoded: display = encoding(tonemap(e * radiance)) for one e.
struct ToneMap {
  const char* name;
  double (*map)(double);
};
double clampMap(double x) { return std::min(x, 1.0); }
double reinhard(double x) { return x / (1.0 + x); }
double acesFilm(double x) { return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
double hablePart(double x) { return (x * (0.15 * x + 0.05) + 0.004) / (x * (0.15 * x + 0.5) + 0.06) - 0.0666667; }
double hable(double x) { return hablePart(x) / hablePart(11.2); }
double exponential(double x) { return 1.0 - std::exp(-x); }
const ToneMap kToneMaps[] = {{"none", clampMap}, {"Reinhard", reinhard}, {"ACES (Narkowicz)", acesFilm},
                             {"Hable", hable}, {"exponential", exponential}};

struct Fit {
  double residual = INFINITY;  // median |decoded display - tonemap(e * radiance)|
  std::string model;
  double exposure = 1.0;
};

// The tone map and exposure that best explain the display from the radiance, decoding the display
// as sRGB or as linear.
Fit toneMapFit(const State& s, size_t t, int lit, bool srgbDecode) {
  std::vector<std::pair<double, double>> samples;  // (radiance, decoded display) per channel
  for (size_t i = 0; i < s.pixels.size(); i += 2) {
    const glm::uvec2 p = s.pixels[i];
    const glm::dvec3 d(channelValues(*s.image(t), p.x, p.y, {0, 1, 2})), l = colourAt(*s.image(size_t(lit)), p.x, p.y, false);
    for (int c = 0; c < 3; ++c)
      if (d[c] > 0.02 && d[c] < 0.98 && l[c] > 0.0) samples.push_back({l[c], srgbDecode ? srgbToLinear(d[c]) : d[c]});
  }
  Fit best;
  if (samples.size() < 100) return best;
  for (const ToneMap& m : kToneMaps)
    for (double e = 1.0 / 256.0; e <= 256.0; e *= std::pow(2.0, 0.125)) {
      std::vector<double> r;
      r.reserve(samples.size());
      for (auto [l, d] : samples) r.push_back(std::abs(d - m.map(e * l)));
      const double med = quantileOf(r, 0.5);
      if (med < best.residual) best = {med, m.name, e};
    }
  return best;
}

void draftLit(State& s, size_t t, int lit) {
  const InferTarget& target = s.in.targets[t];
  const bool radiance = target.format.encoding == Encoding::Float;
  Guess g;
  g.quantity = radiance ? "radiance" : "display";
  g.confidence = 0.9;
  g.evidence = std::string(target.writer == Writer::Forward ? "written by the pass that draws the frame (no G-buffer)"
                                                             : "written after the G-buffer pass") +
               (target.presented ? ", presented" : "") + ": lit colour, " +
               (radiance ? "linear light (a float format)" : "display-referred (a normalised format)");
  nlohmann::json fields = nlohmann::json::object();
  if (!radiance) {
    if (target.format.srgb) {
      fields["encoding"] = "srgb";
      g.evidence += "; sRGB-encoded: the format is";
    } else if (lit >= 0 && lit != int(t)) {
      const Fit asSrgb = toneMapFit(s, t, lit, true), asLinear = toneMapFit(s, t, lit, false);
      const bool srgb = asSrgb.residual < asLinear.residual;
      const Fit& b = srgb ? asSrgb : asLinear;
      const Fit& o = srgb ? asLinear : asSrgb;
      const std::string text = "decoded " + std::string(srgb ? "as sRGB" : "linear") + ", it is " + b.model +
                               " of the radiance times " + numText(b.exposure) + " (median error " + numText(b.residual) +
                               "; decoded " + (srgb ? "linear" : "as sRGB") + ": " + o.model + ", " + numText(o.residual) + ")";
      if (b.residual < 0.02 && b.residual < 0.5 * o.residual) {
        if (srgb) fields["encoding"] = "srgb";
        g.evidence += "; " + text + ": " + (srgb ? "sRGB-encoded by the shader" : "stored linear");
      } else {
        g.undecided.push_back("encoding");
        g.evidence += "; its encoding is not decided: " + text;
      }
    } else {
      g.undecided.push_back("encoding");
      g.evidence += "; its encoding is not in the evidence (no radiance target to compare with): shown linear";
    }
  }
  s.add(t, radiance ? QuantityKind::Radiance : QuantityKind::Display, {0, 1, 2}, fields, g);
}

}  // namespace

void decideColours(State& s) {
  const int lit = radianceTarget(s);
  std::vector<size_t> albedo;  // G-buffer colours in [0, 1]
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    const StorageFormat& f = target.format;
    if (f.depth || f.channels < 3 || f.encoding == Encoding::Uint || !s.image(t) || !s.isFree(t, {0, 1, 2})) continue;
    if (target.writer != Writer::GBuffer) {
      draftLit(s, t, lit);
      continue;
    }
    double hi = 0.0;
    for (const glm::uvec2& p : s.pixels) hi = std::max(hi, std::max({s.image(t)->value(p.x, p.y, 0), s.image(t)->value(p.x, p.y, 1), s.image(t)->value(p.x, p.y, 2)}));
    if (f.encoding == Encoding::Float && hi > 1.001) {
      // Light: emission when the name says so (the values cannot tell it from lighting).
      const std::vector<QuantityKind> named = namedKinds(target.label);
      const bool emission = std::find(named.begin(), named.end(), QuantityKind::Emission) != named.end();
      Guess g;
      g.quantity = emission ? "emission" : "radiance";
      g.confidence = 0.7;
      g.evidence = "a G-buffer colour with values up to " + numText(hi) + ": light, not a reflectance" +
                   (emission ? "; emission by its name \"" + target.label + "\"" : " (emission or lighting)");
      s.add(t, emission ? QuantityKind::Emission : QuantityKind::Radiance, {0, 1, 2}, nullptr, g);
      continue;
    }
    albedo.push_back(t);
  }
  // An sRGB format is a colour; others must show that the light multiplies them when there is more than one.
  std::stable_sort(albedo.begin(), albedo.end(), [&](size_t a, size_t b) {
    return s.in.targets[a].format.srgb > s.in.targets[b].format.srgb;
  });
  for (size_t i = 0; i < albedo.size(); ++i) {
    const size_t t = albedo[i];
    const StorageFormat& f = s.in.targets[t].format;
    Guess g;
    g.quantity = "albedo";
    nlohmann::json fields = nlohmann::json::object();
    Multiply asStored, asSrgb;
    s.colourTested.insert(t);
    if (lit >= 0) {
      asStored = multiplyTest(s, t, lit, false);
      if (!f.srgb) asSrgb = multiplyTest(s, t, lit, true);
    }
    const bool srgb = f.srgb || asSrgb.ratioJump < asStored.ratioJump;
    const Multiply& m = srgb && !f.srgb ? asSrgb : asStored;
    const bool tested = std::isfinite(m.ratioJump);
    const std::string structure = "written by the G-buffer pass" + std::string(s.in.targets[t].readLater ? " and read by a later pass" : "") +
                                  ", values in [0, 1]";
    if (tested && m.ratioJump < 0.5 * m.litJump && m.ratioJump < 0.15) {
      g.confidence = marginConfidence(m.ratioJump, m.litJump);
      g.evidence = structure + "; what the light multiplies: at " + std::to_string(m.edges) + " of its edges on one surface " +
                   "the lit colour jumps " + numText(100 * m.litJump) + " % (median), lit ÷ it only " + numText(100 * m.ratioJump) + " %";
      if (!f.srgb) {
        const Multiply& o = srgb ? asStored : asSrgb;
        g.evidence += std::string("; decoded ") + (srgb ? "as sRGB" : "linear") + " (the other way " + numText(100 * o.ratioJump) + " %)";
        g.rejected.push_back({srgb ? "albedo stored linear" : "albedo stored sRGB", "lit ÷ it jumps " + numText(100 * o.ratioJump) + " %"});
      }
    } else if (tested) {
      g.quantity = "unknown";
      g.confidence = 0.0;
      g.evidence = structure + "; but not what the light multiplies: lit ÷ it jumps " + numText(100 * m.ratioJump) + " % at " +
                   std::to_string(m.edges) + " of its edges (the lit colour " + numText(100 * m.litJump) + " %)";
    } else if (i == 0) {
      g.confidence = f.srgb ? 0.8 : 0.6;
      g.evidence = structure + (f.srgb ? ", an sRGB format" : "") + "; no edges on one surface to test what the light multiplies";
      if (!f.srgb) g.undecided.push_back("encoding");
    } else {
      g.quantity = "unknown";
      g.evidence = structure + ", but another target is the albedo and no edge shows the light multiplying this one";
    }
    if (!g.decided()) continue;  // left to the stored values (decideRest), with nothing claimed
    if (srgb) fields["encoding"] = "srgb";
    s.add(t, QuantityKind::Albedo, {0, 1, 2}, fields, g);
  }
}

}  // namespace gb::infer
