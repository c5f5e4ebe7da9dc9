// LightList (Scene::lights): every non-const access draws a new generation, const access never
// does, and no two lists (copies, moved-from lists, other scenes) share one. The renderer skips
// the light upload on an unchanged generation, so a missed bump is a frame with stale lights.
#include <gtest/gtest.h>

#include <functional>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "renderer/core/light_list.h"
#include "renderer/scene/builtin.h"

namespace gb {

namespace {

LightList threeLights() {
  LightList l;
  for (int i = 0; i < 3; ++i) {
    PointLightDesc d;
    d.center = glm::dvec3(i, 0.0, 0.0);
    l.push_back(d);
  }
  return l;
}

}  // namespace

TEST(LightList, ConstAccessKeepsTheGeneration) {
  LightList lights = threeLights();
  const uint64_t g = lights.generation();
  const LightList& c = lights;
  double sum = 0.0;
  for (const PointLightDesc& l : c) sum += l.center.x;
  for (auto it = c.cbegin(); it != c.cend(); ++it) sum += it->radius;
  sum += c[1].center.x + c.at(2).center.x + c.front().radius + c.back().radius + c.data()[0].radius;
  sum += double(c.size()) + (c.empty() ? 1.0 : 0.0) + double(c.vector().size());
  const std::vector<PointLightDesc>& asVector = c;  // the conversion reads
  sum += double(asVector.size());
  for (const PointLightDesc& l : std::as_const(lights)) sum += l.intensity;  // a mutable list read as const
  EXPECT_EQ(sum, 24.0);  // the reads happened
  EXPECT_EQ(lights.generation(), g);
  const LightList copySource = lights;  // copying reads the source
  EXPECT_EQ(lights.generation(), g);
  EXPECT_NE(copySource.generation(), g);
}

TEST(LightList, EveryNonConstAccessDrawsANewGeneration) {
  const std::vector<PointLightDesc> other(2);
  const std::vector<std::pair<std::string, std::function<void(LightList&)>>> edits = {
      {"operator[]", [](LightList& l) { l[1].intensity = 2.0; }},
      {"at", [](LightList& l) { l.at(1).intensity = 2.0; }},
      {"front", [](LightList& l) { l.front().radius = 3.0; }},
      {"back", [](LightList& l) { l.back().radius = 3.0; }},
      {"begin", [](LightList& l) { l.begin()->phase = 1.0; }},
      {"end", [](LightList& l) { (l.end() - 1)->phase = 1.0; }},
      {"range for", [](LightList& l) { for (PointLightDesc& d : l) d.bob = 1.0; }},
      {"data", [](LightList& l) { l.data()[0].bob = 1.0; }},
      {"push_back", [](LightList& l) { l.push_back(PointLightDesc{}); }},
      {"emplace_back", [](LightList& l) { l.emplace_back(); }},
      {"pop_back", [](LightList& l) { l.pop_back(); }},
      {"assign n", [](LightList& l) { l.assign(2, PointLightDesc{}); }},
      {"assign range", [&](LightList& l) { l.assign(other.begin(), other.end()); }},
      {"assign list", [](LightList& l) { l.assign({PointLightDesc{}}); }},
      {"resize", [](LightList& l) { l.resize(5); }},
      {"resize value", [](LightList& l) { l.resize(5, PointLightDesc{}); }},
      {"clear", [](LightList& l) { l.clear(); }},
      {"reserve", [](LightList& l) { l.reserve(100); }},
      {"erase", [](LightList& l) { l.erase(l.cbegin()); }},
      {"erase range", [](LightList& l) { l.erase(l.cbegin(), l.cbegin() + 2); }},
      {"insert", [](LightList& l) { l.insert(l.cbegin(), PointLightDesc{}); }},
      {"insert range", [&](LightList& l) { l.insert(l.cbegin(), other.begin(), other.end()); }},
      {"= list", [](LightList& l) { l = threeLights(); }},
      {"= copy", [](LightList& l) { const LightList c = threeLights(); l = c; }},
      {"= vector", [&](LightList& l) { l = other; }},
      {"= braces", [](LightList& l) { l = {PointLightDesc{}}; }},
      {"swap", [](LightList& l) { LightList o; l.swap(o); }},
  };
  std::set<uint64_t> seen;
  for (const auto& [what, edit] : edits) {
    LightList lights = threeLights();
    const uint64_t before = lights.generation();
    edit(lights);
    EXPECT_NE(lights.generation(), before) << what;
    EXPECT_TRUE(seen.insert(lights.generation()).second) << what << ": a generation drawn twice";
  }
}

TEST(LightList, CopiesMovesAndScenesNeverShareAGeneration) {
  LightList a = threeLights();
  const uint64_t ga = a.generation();
  LightList copy(a);
  EXPECT_NE(copy.generation(), ga);
  EXPECT_EQ(a.generation(), ga);
  LightList moved(std::move(copy));
  EXPECT_NE(moved.generation(), ga);
  EXPECT_NE(copy.generation(), moved.generation());  // NOLINT: the moved-from list changed too
  LightList assigned;
  assigned = std::move(moved);
  EXPECT_NE(assigned.generation(), moved.generation());  // NOLINT
  // Two scenes built alike: the same lights, not the same generation.
  const Scene s1 = builtinTemple(8), s2 = builtinTemple(8);
  EXPECT_EQ(s1.lights.size(), s2.lights.size());
  EXPECT_NE(s1.lights.generation(), s2.lights.generation());
  const Scene s3 = s1;
  EXPECT_NE(s3.lights.generation(), s1.lights.generation());
}

}  // namespace gb
