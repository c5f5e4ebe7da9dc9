// Values in texels for the live frame (texel_values.h draws them at high zoom): the screen targets
// read back in 64x64 tiles around the texels asked for, decoded as a capture's texels are
// (viewValue, texelValueLines); a new frame reads them again.
#include <memory>
#include <vector>

#include "app/viewer/viewer.h"
#include "views/analysis/view_text.h"
#include "views/analysis/visualize.h"

namespace gb {

namespace {
constexpr int kTile = 64;
struct Tile {
  uint64_t frame = 0;
  glm::ivec2 origin{0};
  FrameSnapshot snapshot;
};
}  // namespace

void installLiveTexelValues(Viewer& v) {
  auto tiles = std::make_shared<std::vector<Tile>>();
  v.model.texelValue = [&v, tiles](int view, FrameSide side, glm::ivec2 t) -> std::optional<TexelValue> {
    ViewerModel& m = v.model;
    Renderer& r = v.renderer;
    // A reduced frame's texels are not the full frame's; the shadow map and reference maps have none here.
    if (side != FrameSide::A || m.reducedBy > 1 || view < 0 || size_t(view) >= m.views.size()) return std::nullopt;
    const ViewDef& d = m.views[size_t(view)];
    if (d.quantity < 0 || d.sun || t.x < 0 || t.y < 0 || t.x >= int(r.options.width) || t.y >= int(r.options.height))
      return std::nullopt;
    const glm::ivec2 origin = (t / kTile) * kTile;
    Tile* tile = nullptr;
    for (Tile& k : *tiles)
      if (k.frame == m.framesRendered && k.origin == origin) tile = &k;
    if (!tile) {
      std::erase_if(*tiles, [&](const Tile& k) { return k.frame != m.framesRendered; });
      const int w = std::min(kTile, int(r.options.width) - origin.x), h = std::min(kTile, int(r.options.height) - origin.y);
      tiles->push_back({m.framesRendered, origin, screenRegionSnapshot(r, origin.x, origin.y, w, h)});
      tile = &tiles->back();
    }
    TexelValue out;
    const std::optional<std::array<double, 4>> value = viewValue(tile->snapshot, d, uint32_t(t.x), uint32_t(t.y));
    out.lines = texelValueLines(tile->snapshot, d, value, m.settings[size_t(view)].channels);
    if (value) {
      for (int c = 0; c < 4; ++c) out.value[size_t(c)] = float((*value)[size_t(c)]);
      out.empty = false;
    }
    return out;
  };
}

}  // namespace gb
