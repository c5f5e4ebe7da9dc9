// What `--method auto`, `--cluster-assign auto` and `--gbuffer auto` decide, against the
// crossovers and measurements as docs/performance.md states them (hand-written here, not read from
// the tables): per device, the method of the largest crossover at or below the light count; the
// G-buffer measured faster on the device, raster where visibility has no G-buffer to resolve.
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

// Raster on a CPU device (lavapipe: the resolve ~180 ms against 16 ms), visibility on a GPU (H200:
// faster in every cell measured); raster for method forward and the single-pass path, saying why.
TEST(MethodChoice, GBufferAutoPicksTheMeasuredKindPerDeviceAndRasterWhereVisibilityCannotRun) {
  RenderOptions o;
  ASSERT_EQ(o.gbuffer, GBufferKind::Auto);
  const GBufferChoice cpu = chooseGBuffer(o, DeviceKind::Cpu);
  EXPECT_EQ(cpu.gbuffer, GBufferKind::Raster);
  EXPECT_EQ(cpu.reason.rfind("auto: raster on a CPU device (lavapipe", 0), 0u) << cpu.reason;
  const GBufferChoice gpu = chooseGBuffer(o, DeviceKind::Gpu);
  EXPECT_EQ(gpu.gbuffer, GBufferKind::Visibility);
  EXPECT_EQ(gpu.reason.rfind("auto: visibility on a GPU (H200", 0), 0u) << gpu.reason;
  for (DeviceKind device : {DeviceKind::Cpu, DeviceKind::Gpu}) {
    RenderOptions forward = o;
    forward.method = Method::Forward;  // no G-buffer at all
    const GBufferChoice f = chooseGBuffer(forward, device);
    EXPECT_EQ(f.gbuffer, GBufferKind::Raster) << name(device);
    EXPECT_EQ(f.reason.rfind("auto: raster (", 0), 0u) << f.reason;
    EXPECT_NE(f.reason.find("method forward has none"), std::string::npos) << f.reason;
    for (Method m : {Method::Auto, Method::Deferred}) {
      RenderOptions single = o;
      single.path = Path::SinglePass;  // the G-buffer stays in the render pass's subpasses
      single.method = m;
      const GBufferChoice sp = chooseGBuffer(single, device);
      EXPECT_EQ(sp.gbuffer, GBufferKind::Raster) << name(device) << " " << name(m);
      EXPECT_EQ(sp.reason.rfind("auto: raster (", 0), 0u) << sp.reason;
      EXPECT_NE(sp.reason.find("two-pass path"), std::string::npos) << sp.reason;
    }
  }
  // A named kind is run as named (the renderer refuses or rasterizes a visibility it cannot run).
  o.gbuffer = GBufferKind::Raster;
  EXPECT_EQ(chooseGBuffer(o, DeviceKind::Gpu).gbuffer, GBufferKind::Raster);
  EXPECT_EQ(chooseGBuffer(o, DeviceKind::Gpu).reason, "--gbuffer raster");
  o.gbuffer = GBufferKind::Visibility;
  EXPECT_EQ(chooseGBuffer(o, DeviceKind::Cpu).gbuffer, GBufferKind::Visibility);
  EXPECT_EQ(chooseGBuffer(o, DeviceKind::Cpu).reason, "--gbuffer visibility");
}

}  // namespace gb
