// The drafting's order (infer.h): depth targets say where the surfaces are; stored positions are
// found by the pinhole they fit; the camera is searched in the bound buffers (judged by the
// positions); normals and linear depths by the geometry of the surfaces; colours by the pass that
// writes them and by what the light multiplies; what is left is drafted as stored values.
#include "views/infer/infer.h"

#include <algorithm>
#include <cmath>

#include "views/infer/infer_internal.h"
#include "views/infer/suggest_guess.h"

namespace gb {

namespace infer {

bool State::isFree(size_t t, const std::vector<uint32_t>& channels) const {
  for (uint32_t c : channels)
    if (c >= claimed[t].size() || claimed[t][c]) return false;
  return true;
}

void State::add(size_t t, QuantityKind kind, const std::vector<uint32_t>& channels, nlohmann::json fields, const Guess& g,
                const std::string& wanted) {
  std::string base = !wanted.empty() ? wanted : gb::name(kind);
  std::string n = base;
  for (int i = 2; names.count(n); ++i) n = base + std::to_string(i);
  names.insert(n);
  nlohmann::json q = {{"quantity", gb::name(kind)}, {"name", n}, {"channels", channels}};
  if (fields.is_object()) q.update(fields);
  q["guess"] = g.json();
  quantities[t].push_back(q);
  for (uint32_t c : channels) claimed[t][c] = true;
}

double stored(const State& s, size_t target, uint32_t channel, uint32_t x, uint32_t y) {
  return s.image(target)->value(x, y, channel);
}

namespace {

uint32_t channelsOf(QuantityKind k, uint32_t available) {
  switch (k) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Position:
    case QuantityKind::Radiance:
    case QuantityKind::Display: return 3;
    case QuantityKind::Normal: return available >= 3 ? 3 : 2;
    case QuantityKind::Motion: return 2;
    default: return 1;
  }
}

// What a name says, taken only where the evidence could not test it: a kind the geometry tested
// and did not find is not drafted because a name says so.
bool testable(const State& s, size_t t, QuantityKind k) {
  switch (k) {
    case QuantityKind::Normal: return s.normalsTested;
    case QuantityKind::Position: return s.positionTested.count(t) > 0;
    case QuantityKind::Depth: return s.distancesKnown;
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor: return s.colourTested.count(t) > 0;
    case QuantityKind::Stencil:
    case QuantityKind::Id: return true;  // their formats decide
    default: return false;
  }
}

void decideByName(State& s) {
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    if (target.label.empty() || target.format.depth || target.format.encoding == Encoding::Uint) continue;
    uint32_t next = 0;
    for (QuantityKind k : namedKinds(target.label)) {
      while (next < target.format.channels && s.claimed[t][next]) ++next;
      const uint32_t n = channelsOf(k, target.format.channels - next);
      if (next + n > target.format.channels || testable(s, t, k)) continue;
      std::vector<uint32_t> ch;
      for (uint32_t c = 0; c < n; ++c) ch.push_back(next + c);
      if (!s.isFree(t, ch)) continue;
      Guess g;
      g.quantity = name(k);
      g.confidence = 0.6;
      g.evidence = "the name \"" + target.label + "\"; nothing measured could test it";
      nlohmann::json fields = nlohmann::json::object();
      const bool unorm = target.format.encoding != Encoding::Float && target.format.encoding != Encoding::Snorm;
      if (k == QuantityKind::Normal) {
        fields = {{"encoding", n == 3 ? (unorm ? "xyz_unorm" : "xyz") : (unorm ? "octahedral_unorm" : "octahedral")},
                  {"space", "view"}};
        g.undecided = {"encoding", "space"};
      } else if (k == QuantityKind::Position) {
        fields = {{"space", "view"}};
        g.undecided = {"space"};
      } else if (k == QuantityKind::Depth) {
        fields = {{"encoding", "eye"}};
        g.undecided = {"encoding", "scale"};
      } else if (target.format.srgb && n == 3) {
        fields = {{"encoding", "srgb"}};
      }
      s.add(t, k, ch, fields, g);
      next += n;
    }
  }
}

// Channels nothing decided: a varying one is drafted as stored values (unknown); a constant one
// (padding, an unused alpha) is left out; integer channels are ids.
void decideRest(State& s) {
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    const CpuImage* img = s.image(t);
    for (uint32_t c = 0; c < target.format.channels; ++c) {
      if (s.claimed[t][c] || target.format.depth) continue;
      if (target.format.encoding == Encoding::Uint) {
        Guess g;
        g.quantity = "id";
        g.evidence = "an integer channel: ids (compared exactly)";
        g.confidence = 0.6;
        s.add(t, QuantityKind::Id, {c}, nullptr, g);
        continue;
      }
      if (!img) continue;
      double lo = INFINITY, hi = -INFINITY;
      bool integral = target.format.encoding == Encoding::Float;
      std::set<double> distinct;
      for (const glm::uvec2& p : s.pixels) {
        const double v = img->value(p.x, p.y, c);
        lo = std::min(lo, v), hi = std::max(hi, v);
        integral = integral && v == std::floor(v) && v >= 0.0 && v <= 65535.0;
        if (distinct.size() < 1000) distinct.insert(v);
      }
      if (lo == hi) continue;  // the same value at every surface: padding
      if (target.writer == Writer::Later && target.format.channels == 1 && target.format.encoding == Encoding::Unorm &&
          hi == 1.0) {  // a pass of its own after the G-buffer writes one 0..1 value: ambient occlusion
        size_t open = 0;
        for (const glm::uvec2& p : s.pixels) open += img->value(p.x, p.y, c) >= 0.95;
        if (open * 4 >= s.pixels.size()) {
          Guess g;
          g.quantity = "occlusion";
          g.confidence = 0.6;
          g.evidence = "one 0..1 channel a pass after the G-buffer pass writes alone, 1 (open) at " +
                       numText(100.0 * double(open) / double(s.pixels.size())) +
                       " % of the surfaces and darker elsewhere: ambient occlusion (or another mask: check it)";
          s.add(t, QuantityKind::Occlusion, {c}, nullptr, g);
          continue;
        }
      }
      if (integral && (distinct.size() >= 3 || hi > 1.0)) {  // small whole numbers in a float: an index
        Guess g;
        g.quantity = "id";
        g.confidence = 0.7;
        g.evidence = "every value at the surfaces is a whole number (" + std::to_string(distinct.size()) + " of them, " +
                     numText(lo) + " .. " + numText(hi) + ") stored as a float: an index (object, material)";
        s.add(t, QuantityKind::Id, {c}, nullptr, g);
        continue;
      }
      Guess g;
      g.evidence = "channel " + std::to_string(c) + " varies (" + numText(lo) + " .. " + numText(hi) +
                   " over the surfaces) and no evidence says what it holds: shown as stored";
      s.add(t, QuantityKind::Scalar, {c}, nullptr, g);
    }
  }
}

}  // namespace

}  // namespace infer

InferOutput inferLayout(const InferInput& in) {
  infer::State s(in);
  for (const InferTarget& t : in.targets) {
    s.claimed.emplace_back(t.format.channels, false);
    s.quantities.push_back(nlohmann::json::array());
    if (t.texels && !s.width) s.width = t.texels->width, s.height = t.texels->height;
  }
  infer::decideDepthTargets(s);
  infer::decideSurface(s);
  s.pixels = samplePixels(s.surface, s.width, s.height, 6000);
  infer::decidePositions(s);
  infer::decideCamera(s);
  infer::decideNormalsAndDepths(s);
  infer::decideColours(s);
  infer::decideByName(s);
  infer::decideRest(s);
  InferOutput out;
  out.quantities = std::move(s.quantities);
  out.camera = s.cam.present ? s.cam.block : nlohmann::json();
  out.summary = std::move(s.summary);
  out.surface = std::move(s.surface);
  return out;
}

}  // namespace gb
