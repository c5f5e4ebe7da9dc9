// What `--method auto` and `--cluster-assign auto` decide, against the crossovers as
// docs/performance.md states them (hand-written here, not read from the table): per device, the
// method of the largest crossover at or below the light count.
#include <gtest/gtest.h>

#include "renderer/core/method_choice.h"

namespace gb {

TEST(MethodChoice, AutoPicksTheMeasuredMethodPerDeviceAndLightCount) {
  RenderOptions o;
  ASSERT_EQ(o.method, Method::Auto);
  const struct {
    DeviceKind device;
    size_t lights;
    Method expected;
  } cases[] = {{DeviceKind::Cpu, 0, Method::Deferred},      {DeviceKind::Cpu, 16, Method::Deferred},
               {DeviceKind::Cpu, 63, Method::Deferred},     {DeviceKind::Cpu, 64, Method::Clustered},
               {DeviceKind::Cpu, 256, Method::Clustered},   {DeviceKind::Cpu, 65536, Method::Clustered},
               {DeviceKind::Gpu, 0, Method::Tiled},         {DeviceKind::Gpu, 256, Method::Tiled},
               {DeviceKind::Gpu, 4095, Method::Tiled},      {DeviceKind::Gpu, 4096, Method::Clustered},
               {DeviceKind::Gpu, 65536, Method::Clustered}};
  for (const auto& c : cases) {
    const MethodChoice m = chooseMethod(o, c.device, c.lights);
    EXPECT_EQ(m.method, c.expected) << name(c.device) << ", " << c.lights << " lights";
    EXPECT_EQ(m.reason.rfind("auto: ", 0), 0u) << m.reason;
    EXPECT_NE(m.reason.find(name(c.expected)), std::string::npos) << m.reason;
    EXPECT_NE(m.reason.find(name(c.device)), std::string::npos) << m.reason;
  }
  o.path = Path::SinglePass;  // only deferred has the single-pass path
  EXPECT_EQ(chooseMethod(o, DeviceKind::Gpu, 65536).method, Method::Deferred);
  o.path = Path::TwoPass;
  o.method = Method::Forward;  // a named method is run as named
  const MethodChoice named = chooseMethod(o, DeviceKind::Cpu, 256);
  EXPECT_EQ(named.method, Method::Forward);
  EXPECT_EQ(named.reason, "--method forward");
}

TEST(MethodChoice, TheClusterGridIsFilledOnTheCpuOnlyForClusteredOnACpuDeviceOrWhenAsked) {
  RenderOptions o;
  std::string why;
  EXPECT_TRUE(clusterGridOn(o, DeviceKind::Cpu, Method::Clustered, why)) << why;
  EXPECT_FALSE(clusterGridOn(o, DeviceKind::Gpu, Method::Clustered, why)) << why;
  EXPECT_FALSE(clusterGridOn(o, DeviceKind::Cpu, Method::Tiled, why)) << why;
  o.clusterAssign = ClusterAssign::Cpu;
  EXPECT_TRUE(clusterGridOn(o, DeviceKind::Gpu, Method::Clustered, why)) << why;
  EXPECT_NE(why.find("--cluster-assign cpu"), std::string::npos) << why;
  o.clusterAssign = ClusterAssign::Gpu;
  EXPECT_FALSE(clusterGridOn(o, DeviceKind::Cpu, Method::Clustered, why)) << why;
  // Lights set up on the GPU cannot fill a grid on the CPU: auto takes the occupied clusters.
  o.clusterAssign = ClusterAssign::Auto;
  o.lightSetup = LightSetup::Gpu;
  EXPECT_FALSE(clusterGridOn(o, DeviceKind::Cpu, Method::Clustered, why)) << why;
  EXPECT_NE(why.find("--light-setup gpu"), std::string::npos) << why;
}

}  // namespace gb
