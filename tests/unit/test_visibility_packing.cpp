// The visibility id's packing (renderer/core/visibility.h): triangle bits per scene, the draws the
// rest can name, the refusal beyond them, and the options --gbuffer visibility cannot run with.
#include <gtest/gtest.h>

#include "renderer/core/visibility.h"
#include "views/import/import.h"

namespace gb {

TEST(VisibilityPacking, TriangleBitsHoldTheLargestMeshAndTheRestNameTheDraws) {
  VisibilityPacking p;
  std::string error;
  ASSERT_TRUE(visibilityPacking(3, 1, p, error));
  EXPECT_EQ(p.triangleBits, 1u);
  ASSERT_TRUE(visibilityPacking(100, 65536, p, error));  // triangles 0..65535: 16 bits
  EXPECT_EQ(p.triangleBits, 16u);
  EXPECT_EQ(p.maxDraws, 65535u);
  ASSERT_TRUE(visibilityPacking(4095, 1u << 20, p, error));
  EXPECT_EQ(p.triangleBits, 20u);
  EXPECT_EQ(p.maxDraws, 4095u);
  for (uint32_t draw : {0u, 17u, 4094u})
    for (uint32_t triangle : {0u, 1u, (1u << 20) - 1}) {
      const uint32_t id = packVisibility(p, draw, triangle);
      EXPECT_NE(id, 0u);
      uint32_t d = 0, t = 0;
      ASSERT_TRUE(unpackVisibility(p, id, d, t));
      EXPECT_EQ(d, draw);
      EXPECT_EQ(t, triangle);
    }
  uint32_t d = 0, t = 0;
  EXPECT_FALSE(unpackVisibility(p, 0, d, t));  // no geometry
}

TEST(VisibilityPacking, ScenesBeyondTheIdAndOptionsWithoutAGBufferAreRefused) {
  VisibilityPacking p;
  std::string error;
  EXPECT_FALSE(visibilityPacking(4096, 1u << 20, p, error));
  EXPECT_NE(error.find("4096 draws"), std::string::npos) << error;
  EXPECT_NE(error.find("room for 4095"), std::string::npos) << error;
  EXPECT_FALSE(visibilityPacking(2, uint64_t(1) << 32, p, error));  // one mesh of 2^32 triangles: no draw bits
  RenderOptions o;
  EXPECT_EQ(visibilityOptionsRefusal(o), "");  // raster: nothing to refuse
  o.gbuffer = GBufferKind::Visibility;
  EXPECT_EQ(visibilityOptionsRefusal(o), "");
  EXPECT_TRUE(visibilityFrame(o));
  o.method = Method::Forward;
  EXPECT_NE(visibilityOptionsRefusal(o).find("forward"), std::string::npos);
  EXPECT_FALSE(visibilityFrame(o));
  o.method = Method::Deferred;
  o.path = Path::SinglePass;
  EXPECT_NE(visibilityOptionsRefusal(o).find("two-pass"), std::string::npos);
  EXPECT_FALSE(visibilityFrame(o));
}

// builtin:visibility-buffer: what an engine that ships a visibility buffer stores, depth and the id.
TEST(VisibilityPacking, TheShippedVisibilityBufferLayoutHoldsHardwareDepthAndAnId) {
  Layout l;
  std::string error, dir;
  ASSERT_TRUE(loadImportLayout("builtin:visibility-buffer", {}, l, dir, error)) << error;
  ASSERT_EQ(l.targets.size(), 2u);
  int ids = 0, depths = 0;
  for (const Quantity& q : l.quantities) {
    ids += q.kind == QuantityKind::Id;
    depths += q.kind == QuantityKind::Depth;
  }
  EXPECT_EQ(ids, 1);
  EXPECT_EQ(depths, 1);
}

}  // namespace gb
