// Captures: a lossless round trip in every storage format the renderer has, determinism,
// --targets reading back only what it names, atomic writes, and EXRs that oiiotool reads with
// the documented channel names.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "renderer/gpu/render_targets.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"
#include "views/capture/exr.h"
#include "views/capture/report.h"

namespace gb {

namespace fs = std::filesystem;

static CaptureMeta testMeta(const GpuContext& ctx, const Scene& scene, const FrameStats& stats) {
  CaptureMeta m;
  m.device = ctx.deviceName;
  m.driver = ctx.driverName;
  m.scene = scene.source;
  m.sceneSha256 = sceneContentSha256(scene);
  m.stats = stats;
  m.commandLine = "test";
  return m;
}

// Renders `o`, captures every available target to `dir`, and returns the live snapshot.
static FrameSnapshot renderAndCapture(GpuTest& t, const Scene& scene, const RenderOptions& o, const std::string& dir) {
  std::vector<Target> all = availableTargets(o, scene.sun.enabled);
  const FrameStats& st = t.render(scene, o, captureRequest(all, o));
  FrameSnapshot live = snapshotFromRenderer(t.renderer(scene), all);
  std::string error;
  EXPECT_TRUE(writeCapture(dir, live, testMeta(GpuTest::ctx(), scene, st), error)) << error;
  return live;
}

TEST_F(GpuTest, CaptureRoundTripIsBitExactInEveryStorageFormat) {
  std::vector<RenderOptions> variants(4, smallCaptureOptions());
  variants[1].normalFormat = NormalFormat::Rgba8Snorm;
  variants[1].depthFormat = DepthFormat::D24S8;
  variants[1].accumFormat = AccumFormat::Rgba32f;
  variants[1].shadowFormat = ShadowFormat::D16;
  variants[2].normalFormat = NormalFormat::OctRg16;
  variants[2].accumFormat = AccumFormat::Rgba8;
  variants[2].path = Path::SinglePass;
  variants[3].normalFormat = NormalFormat::Rgb10a2;
  variants[3].eyeDepth = false;
  variants[3].reversedZ = true;
  variants[3].stencilMask = StencilMask::Shared;
  variants[0].primitiveId = true;  // the optional targets round-trip too
  variants[0].motion = true;       // rg16f
  variants[0].cameraMotion = CameraMotion::Orbit;
  variants[2].motion = true;       // written in the single-pass G-buffer subpass
  variants[2].jitter = Jitter::Halton;
  variants[1].position = PositionSource::Rgba32f;
  variants[2].position = PositionSource::Rgba16f;
  std::set<PixelType> typesSeen;
  for (size_t v = 0; v < variants.size(); ++v) {
    const RenderOptions& o = variants[v];
    Scene scene = builtinTemple(o.lights);
    std::string dir = freshDir("roundtrip" + std::to_string(v));
    FrameSnapshot live = renderAndCapture(*this, scene, o, dir);
    Capture c;
    std::string error;
    ASSERT_TRUE(loadCapture(dir, c, error)) << error;
    for (size_t i = 0; i < kTargetCount; ++i) {
      const CpuImage &a = live.images[i].image, &b = c.frame.images[i].image;
      if (targetAbsence(Target(i), o) != Absent::No) {  // not computed under these options
        EXPECT_TRUE(a.empty() && b.empty()) << targetName(Target(i));
        continue;
      }
      ASSERT_FALSE(a.empty()) << targetName(Target(i));
      typesSeen.insert(a.type);
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.channels, b.channels);
      EXPECT_EQ(a.type, b.type) << a.name;
      EXPECT_EQ(a.encoding, b.encoding) << a.name;
      EXPECT_EQ(a.width, b.width);
      EXPECT_EQ(a.height, b.height);
      EXPECT_TRUE(a.data == b.data) << "variant " << v << ": " << a.name << " differs after the round trip";
    }
    // Everything else the probe uses comes back exactly too; the options with the G-buffer kind
    // that ran (--gbuffer auto resolved before the frame, frameOptions).
    EXPECT_NE(c.frame.options.gbuffer, GBufferKind::Auto);
    EXPECT_EQ(optionsJson(c.frame.options), optionsJson(frameOptions(renderer(scene), o)));
    for (auto [x, y] : {std::pair{&live.camera.clipFromEye, &c.frame.camera.clipFromEye},
                        {&live.camera.eyeFromClip, &c.frame.camera.eyeFromClip},
                        {&live.camera.eyeFromWorld, &c.frame.camera.eyeFromWorld},
                        {&live.camera.worldFromEye, &c.frame.camera.worldFromEye},
                        {&live.camera.clipFromWorld, &c.frame.camera.clipFromWorld},
                        {&live.lightClipFromWorld, &c.frame.lightClipFromWorld}})
      EXPECT_TRUE(*x == *y);
    EXPECT_EQ(live.camera.znear, c.frame.camera.znear);
    EXPECT_EQ(live.camera.reversedZ, c.frame.camera.reversedZ);
    ASSERT_EQ(live.eyeLights.size(), c.frame.eyeLights.size());
    EXPECT_EQ(0, std::memcmp(live.eyeLights.data(), c.frame.eyeLights.data(), live.eyeLights.size() * sizeof(gpu::PointLight)));
    EXPECT_EQ(live.visibleLights, c.frame.visibleLights);
    EXPECT_EQ(live.stencilCount, c.frame.stencilCount);
    EXPECT_TRUE(live.sun.toSun == c.frame.sun.toSun && live.sun.color == c.frame.sun.color);
    EXPECT_TRUE(live.sky.ambient == c.frame.sky.ambient);
    EXPECT_EQ(c.manifest["scene"]["content_sha256"], sceneContentSha256(scene));
  }
  EXPECT_EQ(typesSeen.size(), 7u) << "the variants should exercise every PixelType";
}

TEST_F(GpuTest, TwoCapturesOfTheSameFrameAreIdentical) {
  RenderOptions o = smallCaptureOptions();
  Scene a = builtinTemple(o.lights), b = builtinTemple(o.lights);
  std::string da = freshDir("determinism_a"), db = freshDir("determinism_b");
  renderAndCapture(*this, a, o, da);
  renderAndCapture(*this, b, o, db);
  Capture ca, cb;
  std::string error;
  ASSERT_TRUE(loadCapture(da, ca, error)) << error;
  ASSERT_TRUE(loadCapture(db, cb, error)) << error;
  // Every file (EXRs, final.png, lights.json) has the same bytes: compare the digests.
  EXPECT_EQ(ca.manifest["files"], cb.manifest["files"]);
  for (size_t i = 0; i < kTargetCount; ++i)
    EXPECT_TRUE(ca.frame.images[i].image.data == cb.frame.images[i].image.data) << targetName(Target(i));
}

TEST_F(GpuTest, CaptureReadsBackOnlyTheRequestedTargets) {
  RenderOptions o = smallCaptureOptions();
  Scene scene = builtinTemple(o.lights);
  const std::vector<Target> wanted = {Target::Depth, Target::Final};
  FrameRequest request = captureRequest(wanted, o);
  EXPECT_EQ(request.readback, wanted);
  EXPECT_FALSE(request.cullingStats);  // it would read back coverage_masked
  render(scene, o, request);
  const Renderer& r = renderer(scene);  // a fresh renderer: nothing was read back before
  for (size_t i = 0; i < kTargetCount; ++i) {
    bool asked = std::find(wanted.begin(), wanted.end(), Target(i)) != wanted.end();
    EXPECT_EQ(r.readback[i].empty(), !asked) << targetName(Target(i));
  }
  FrameSnapshot s = snapshotFromRenderer(r, wanted);
  EXPECT_TRUE(s.target(Target::Depth).present());
  EXPECT_FALSE(s.target(Target::Hdr).present());
  EXPECT_EQ(s.absence(Target::Hdr), Absent::NotReadBack);

  // The command line: only the named EXRs, the others listed with their reasons.
  std::string dir = freshDir("targets") + "/cap";
  RunResult run = runGblens("capture --size 64x36 --lights 8 --shadow-map-size 64 --coverage off --validate "
                            "--targets depth,final -o " + dir);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  nlohmann::json m = nlohmann::json::parse(readText(dir + "/manifest.json"));
  std::vector<std::string> names;
  for (auto& t : m["targets"]) names.push_back(t["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"depth", "final"}));
  std::map<std::string, std::string> skipped;
  for (auto& s : m["skipped"]) skipped[s["name"]] = s["reason"];
  EXPECT_EQ(skipped["hdr"], "not requested (--targets)");
  EXPECT_EQ(skipped["coverage_full"], "not computed: coverage off");
  EXPECT_FALSE(fs::exists(dir + "/hdr.exr"));
  EXPECT_TRUE(fs::exists(dir + "/final.png"));

  RunResult bad = runGblens("capture --size 64x36 --coverage off --targets coverage_full -o " + dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.output.find("coverage off"), std::string::npos) << bad.output;
  bad = runGblens("capture --size 64x36 --targets depth,bogus -o " + dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.output.find("unknown target \"bogus\""), std::string::npos) << bad.output;
}

TEST_F(GpuTest, OiiotoolReadsEveryExrAndListsItsChannels) {
  RenderOptions o = smallCaptureOptions();
  o.normalFormat = NormalFormat::Rgba8Snorm;  // raw + decoded channels in normal_shadow too
  Scene scene = builtinTemple(o.lights);
  std::string dir = freshDir("oiiotool");
  renderAndCapture(*this, scene, o, dir);
  nlohmann::json m = nlohmann::json::parse(readText(dir + "/manifest.json"));
  ASSERT_EQ(m["targets"].size(), availableTargets(o).size());
  for (const nlohmann::json& t : m["targets"]) {
    std::string file = dir + "/" + t["file"].get<std::string>();
    RunResult r = runShell("oiiotool --info -v '" + file + "'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("openexr"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("gblens:target: \"" + t["name"].get<std::string>() + "\""), std::string::npos) << r.output;
    for (const nlohmann::json& ch : t["exr_channels"]) {
      std::string expected = ch["name"].get<std::string>();
      EXPECT_NE(r.output.find(expected), std::string::npos) << file << " lacks channel " << expected << ":\n" << r.output;
      EXPECT_EQ(expected.rfind(t["name"].get<std::string>() + ".", 0), 0u) << expected;
    }
  }
  // The documented example name.
  EXPECT_NE(runShell("oiiotool --info -v '" + dir + "/normal_shadow.exr'").output.find("normal_shadow.N.X"),
            std::string::npos);
}

}  // namespace gb

namespace gb {

TEST_F(GpuTest, TransientAndUncomputedTargetsAreSkippedWithTheReason) {
  RenderOptions o = smallCaptureOptions();
  o.path = Path::SinglePass;
  o.keepGBuffer = false;  // the G-buffer stays in tile memory
  o.coverage = false;
  o.primitiveId = false;
  std::vector<Target> all = availableTargets(o);
  EXPECT_EQ(all, (std::vector<Target>{Target::DepthStencil, Target::ShadowMap, Target::Hdr, Target::Final}));
  Scene scene = builtinTemple(o.lights);
  std::string dir = freshDir("transient");
  renderAndCapture(*this, scene, o, dir);
  nlohmann::json m = nlohmann::json::parse(readText(dir + "/manifest.json"));
  std::map<std::string, std::string> skipped;
  for (auto& s : m["skipped"]) skipped[s["name"]] = s["reason"];
  EXPECT_EQ(skipped.size(), kTargetCount - all.size());
  EXPECT_EQ(skipped["normal_shadow"].rfind("transient", 0), 0u) << skipped["normal_shadow"];
  EXPECT_EQ(skipped["coverage_masked"], "not computed: coverage off");
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;
  EXPECT_EQ(absentText(c.frame.absence(Target::Depth)), skipped["depth"]);
  EXPECT_FALSE(m["stats"]["culling"]["valid"].get<bool>());
}

// A scene without a sun has no shadow map: the capture says so instead of storing the 1x1
// placeholder no pass writes (it read back as uninitialized memory).
TEST_F(GpuTest, ASceneWithoutSunCapturesNoShadowMap) {
  RenderOptions o = smallCaptureOptions();
  Scene scene = builtinTemple(o.lights);
  scene.sun.enabled = false;
  std::string dir = freshDir("sunless");
  renderAndCapture(*this, scene, o, dir);
  nlohmann::json m = nlohmann::json::parse(readText(dir + "/manifest.json"));
  bool listed = false;
  for (auto& s : m["skipped"])
    if (s["name"] == "shadow_map") listed = s["reason"].get<std::string>().find("no sun") != std::string::npos;
  EXPECT_TRUE(listed) << m["skipped"].dump();
  for (auto& t : m["targets"]) EXPECT_NE(t["name"], "shadow_map");
  EXPECT_FALSE(fs::exists(dir + "/shadow_map.exr"));
}

}  // namespace gb
