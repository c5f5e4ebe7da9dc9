// Pass roles from the frame's structure (roles.h): reads after each pass decide the G-buffer pass,
// then its stored outputs and the frame-sized colour outputs of later passes are the targets.
#include "views/infer/roles.h"

#include <algorithm>

namespace gb {

namespace {

bool readAfter(const FrameFacts& f, const std::string& image, uint32_t after) {
  for (const auto& [name, events] : f.reads)
    if (name == image && std::any_of(events.begin(), events.end(), [&](uint32_t e) { return e > after; })) return true;
  return false;
}

struct Score {
  int readColours = 0, colours = 0;
  bool depth = false;
};

Score scoreOf(const FrameFacts& f, const PassFacts& p) {
  Score s;
  for (const PassFacts::Output& o : p.outputs) {
    if (!o.usable || !o.stored) continue;
    if (o.depth) {
      s.depth = true;
      continue;
    }
    ++s.colours;
    s.readColours += readAfter(f, o.image, p.last);
  }
  return s;
}

// The G-buffer pass: the most colour outputs read later (at least two), then a depth, then more
// outputs, then the earlier; -1 when no pass's outputs are read together (forward rendering).
int gbufferByReads(const FrameFacts& f) {
  int best = -1;
  Score b;
  for (size_t i = 0; i < f.passes.size(); ++i) {
    const Score s = scoreOf(f, f.passes[i]);
    if (s.readColours < 2) continue;
    const PassFacts& p = f.passes[i];
    const bool tie = best >= 0 && s.readColours == b.readColours && s.depth == b.depth && s.colours == b.colours;
    const bool better = best < 0 || s.readColours > b.readColours ||
                        (s.readColours == b.readColours && (s.depth > b.depth || (s.depth == b.depth && s.colours > b.colours))) ||
                        (tie && p.last - p.first < f.passes[size_t(best)].last - f.passes[size_t(best)].first);
    if (better) best = int(i), b = s;
  }
  return best;
}

// Without reads: the pass writing the most colour targets with a depth target (the innermost of
// equals: the shortest span).
int gbufferByOutputs(const FrameFacts& f, bool needDepth) {
  int best = -1;
  int bestScore = -1;
  for (size_t i = 0; i < f.passes.size(); ++i) {
    const Score s = scoreOf(f, f.passes[i]);
    if (needDepth && !s.depth) continue;
    const int score = s.colours * 2 + s.depth;
    const PassFacts& p = f.passes[i];
    if (score > bestScore ||
        (score == bestScore && best >= 0 && p.last - p.first < f.passes[size_t(best)].last - f.passes[size_t(best)].first))
      best = int(i), bestScore = score;
  }
  return bestScore > 0 ? best : -1;
}

std::string outputName(const PassFacts& p, const PassFacts::Output& o) {
  return (o.depth ? "the depth attachment " : "") + o.image + " of " + p.name;
}

}  // namespace

PassRoles decideRoles(const FrameFacts& f, int forced) {
  PassRoles r;
  if (forced >= 0 && size_t(forced) < f.passes.size()) {
    r.gbuffer = forced;
    r.notes.push_back("G-buffer pass: " + f.passes[size_t(forced)].name + " (as asked)");
  } else if (f.readsKnown && (r.gbuffer = gbufferByReads(f)) >= 0) {
    const Score s = scoreOf(f, f.passes[size_t(r.gbuffer)]);
    r.notes.push_back("G-buffer pass: " + f.passes[size_t(r.gbuffer)].name + " (" + std::to_string(s.readColours) +
                      " of its colour targets are read by later passes" + (s.depth ? ", with its depth" : "") + ")");
  } else if (f.readsKnown) {
    r.forward = true;
    r.gbuffer = gbufferByOutputs(f, true);
    if (r.gbuffer < 0) r.gbuffer = gbufferByOutputs(f, false);
    if (r.gbuffer >= 0)
      r.notes.push_back("no G-buffer: no pass's colour targets are read together by a later pass; " +
                        f.passes[size_t(r.gbuffer)].name + " draws the frame (forward rendering)");
  } else if ((r.gbuffer = gbufferByOutputs(f, false)) >= 0) {
    r.notes.push_back("G-buffer pass: " + f.passes[size_t(r.gbuffer)].name +
                      " (the most colour targets with a depth target; the frame says nothing of what reads them)");
  }
  if (r.gbuffer < 0) return r;
  const PassFacts& g = f.passes[size_t(r.gbuffer)];
  std::set<std::string> taken;
  auto add = [&](size_t pass, size_t output, Writer w) {
    const PassFacts& p = f.passes[pass];
    const PassFacts::Output& o = p.outputs[output];
    if (!o.usable || !taken.insert(o.image).second) return;
    if (!o.stored) {
      r.notes.push_back(outputName(p, o) + ": storeOp DONT_CARE, not stored by the application: no quantity");
      return;
    }
    PassTarget t{pass, output, w, readAfter(f, o.image, p.last), f.presented.count(o.image) > 0, o.stencilStored};
    if (o.depth && !o.stencilStored)
      r.notes.push_back(outputName(p, o) + ": its stencil's storeOp is DONT_CARE (not stored): the stencil is no quantity");
    r.targets.push_back(t);
  };
  for (size_t o = 0; o < g.outputs.size(); ++o) add(size_t(r.gbuffer), o, r.forward ? Writer::Forward : Writer::GBuffer);
  uint32_t width = 0, height = 0;
  for (const PassFacts::Output& o : g.outputs)
    if (o.usable && !width) width = o.width, height = o.height;
  for (size_t i = size_t(r.gbuffer) + 1; i < f.passes.size(); ++i) {
    const PassFacts& p = f.passes[i];
    if (p.first <= g.last) continue;  // nested inside the G-buffer pass's region
    for (size_t o = 0; o < p.outputs.size(); ++o) {
      const PassFacts::Output& out = p.outputs[o];
      if (out.width != width || out.height != height || taken.count(out.image)) continue;
      if (out.depth) {
        r.notes.push_back(outputName(p, out) + ": a later pass's own depth, not the G-buffer's: left out");
        taken.insert(out.image);
        continue;
      }
      add(i, o, Writer::Later);
    }
  }
  return r;
}

}  // namespace gb
