// gblens import of hand-made G-buffers (issue 15): EXR (multi-layer, multi-part, half), PNG, TIFF and raw
// dumps with analytic contents (tests/cli/import_fixtures.h) in two sets of conventions are imported, the
// capture read back, and every pixel's decoded normal, depth and position compared with the analytic
// value within the bound its encoding allows (derived at each check). Every malformed input gives one
// line naming the file, the target and the field, exit 2, and nothing at -o.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "renderer/core/decode.h"
#include "tests/cli/import_fixtures.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace fixtures;

// One float's rounding at v: the distance to the next float (a full ulp: twice the worst rounding).
double ulp(double v) {
  const float f = float(std::abs(v));
  return double(std::nextafter(f, INFINITY)) - double(f);
}

// The largest angle between a unit vector and that vector plus an error of length e: asin(e).
double angleBound(double e) { return std::asin(std::min(1.0, e)); }

double angle(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The worst error / bound over the surface pixels, with where it was.
struct Worst {
  double ratio = 0.0, error = 0.0, bound = 0.0;
  uint32_t x = 0, y = 0;
  void add(double e, double b, uint32_t px, uint32_t py) {
    const double r = std::isfinite(e) ? e / b : INFINITY;
    if (r > ratio || std::isnan(e)) ratio = std::isnan(e) ? INFINITY : r, error = e, bound = b, x = px, y = py;
  }
};
#define EXPECT_WITHIN(worst, what)                                                                              \
  EXPECT_LE((worst).ratio, 1.0) << (what) << ": error " << (worst).error << " > bound " << (worst).bound << " at " \
                                << (worst).x << "," << (worst).y

const Quantity& quantity(const FrameSnapshot& f, const std::string& name) {
  const Quantity* q = f.layout.findByName(name);
  if (!q) throw std::runtime_error("the imported layout has no quantity " + name);
  return *q;
}

Capture importAndLoad(const std::string& args, const std::string& out) {
  RunResult r = runGblens("import " + args + " -o '" + out + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  Capture c;
  std::string error;
  EXPECT_TRUE(loadCapture(out, c, error)) << error;
  return c;
}

// Surfaces where the scene has one, and the hardware depth's positions and eye depths within the bound
// one rounding of the stored float allows: the eye depth of d +- 1 ulp, by the projection inverted by hand.
void expectHardwareDepth(const FrameSnapshot& f, const Scene& s, const Quantity& q, double (*stored)(const Scene&, const glm::dvec3&),
                         double (*eyeDepth)(const Scene&, double), const char* what) {
  Worst depth, position;
  size_t surfaces = 0, wrong = 0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Truth& t = s.at(x, y);
      wrong += hasSurface(f, x, y) != t.hit;
      if (!t.hit) continue;
      ++surfaces;
      const double d = stored(s, t.eye), u = ulp(d), z = -t.eye.z;
      const double bound = std::max(std::abs(eyeDepth(s, d + u) - z), std::abs(eyeDepth(s, d - u) - z)) + 1e-12 * z;
      std::optional<double> got = decodeEyeDepth(f, q, x, y);
      depth.add(got ? std::abs(*got - z) : INFINITY, bound, x, y);
      std::optional<glm::dvec3> p = decodePosition(f, q, x, y);
      // The position lies on the pixel's ray (z = -1 at unit depth): its error is the depth's times |ray|.
      position.add(p ? glm::length(*p - t.eye) : INFINITY, bound * glm::length(t.eye) / z + 1e-12, x, y);
    }
  EXPECT_GT(surfaces, size_t(kW * kH / 2));
  EXPECT_LT(surfaces, size_t(kW * kH));  // some sky, so background values are tested too
  EXPECT_EQ(wrong, 0u) << what << ": pixels whose surface/background differs from the scene";
  EXPECT_WITHIN(depth, std::string(what) + " eye depth");
  EXPECT_WITHIN(position, std::string(what) + " position from depth");
}

// Normals within asin(|e|), e the largest error the storage puts on the vector (per component: `perComponent`,
// or one float ulp of each component when 0).
void expectNormals(const FrameSnapshot& f, const Scene& s, const Quantity& q, double perComponent, const char* what) {
  Worst worst;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Truth& t = s.at(x, y);
      if (!t.hit) continue;
      double e = std::sqrt(3.0) * perComponent;
      if (perComponent == 0.0) {
        glm::dvec3 u(ulp(t.normalWorld.x), ulp(t.normalWorld.y), ulp(t.normalWorld.z));
        e = glm::length(u);
      }
      worst.add(angle(decodeNormal(f, q, x, y).unit, t.normalEye), angleBound(e) + 1e-12, x, y);
    }
  EXPECT_WITHIN(worst, what);
  std::printf("%-28s worst angle %.3g rad (bound %.3g)\n", what, worst.error, worst.bound);
}

// Stored world positions (float): within one ulp of each component, a length kept by the rigid view.
void expectStoredPositions(const FrameSnapshot& f, const Scene& s, const Quantity& q, const char* what) {
  Worst worst;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Truth& t = s.at(x, y);
      if (!t.hit) continue;
      const double bound = glm::length(glm::dvec3(ulp(t.world.x), ulp(t.world.y), ulp(t.world.z))) + 1e-12;
      std::optional<glm::dvec3> p = decodePosition(f, q, x, y);
      worst.add(p ? glm::length(*p - t.eye) : INFINITY, bound, x, y);
    }
  EXPECT_WITHIN(worst, what);
}

TEST(Import, HandMadeGlGBufferDecodesToTheAnalyticValues) {
  const std::string dir = freshDir("import-fixture-a");
  const Scene s = makeScene();
  writeFixtureA(dir, s);
  // Files given on the command line (matched by name), one not: beside the layout.
  Capture c = importAndLoad("'" + dir + "/gbuffer.exr' '" + dir + "/normal_view.png' --layout '" + dir + "/a.json'",
                            dir + "/imported");
  const FrameSnapshot& f = c.frame;
  ASSERT_EQ(f.images.size(), 7u);
  for (const TargetImage& ti : f.images) ASSERT_TRUE(ti.present());
  EXPECT_FALSE(f.camera.reversedZ);

  // Float world normals: one ulp a component. Unorm8 n * 0.5 + 0.5: the file's rounding (0.5 / 255) doubled,
  // 1/255 a component. Octahedral snorm16: each coordinate within d = 0.5 / 32767; the unnormalised
  // vector (x, y, 1 - |x| - |y|) (folded: each coordinate 1-Lipschitz) moves by at most sqrt(6) d and
  // is at least 1/sqrt(3) long, so the direction turns by at most asin(sqrt(18) d) = asin(sqrt(3) * (sqrt(6) d)).
  expectNormals(f, s, quantity(f, "Nworld"), 0.0, "A world normals (xyz float)");
  expectNormals(f, s, quantity(f, "Nunorm"), 1.0 / 255.0, "A view normals (xyz_unorm 8)");
  expectNormals(f, s, quantity(f, "Noct"), std::sqrt(6.0) * 0.5 / 32767.0, "A view normals (octahedral 16)");
  expectHardwareDepth(f, s, quantity(f, "Zhw"), glWindowDepth, eyeDepthFromGlWindowDepth, "A standard GL depth");
  expectStoredPositions(f, s, quantity(f, "P"), "A stored world positions");

  // Eye and radial distance (float): within one ulp of the stored value (radial: times the cosine <= 1).
  Worst eye, radial;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Truth& t = s.at(x, y);
      if (!t.hit) continue;
      const double z = -t.eye.z;
      std::optional<double> e = decodeEyeDepth(f, quantity(f, "Zeye"), x, y);
      std::optional<double> r = decodeEyeDepth(f, quantity(f, "Zradial"), x, y);
      eye.add(e ? std::abs(*e - z) : INFINITY, ulp(z), x, y);
      radial.add(r ? std::abs(*r - z) : INFINITY, ulp(glm::length(t.eye)) + 1e-12 * z, x, y);
    }
  EXPECT_WITHIN(eye, "A eye depth");
  EXPECT_WITHIN(radial, "A radial distance");
}

TEST(Import, HandMadeD3dZUpReversedGBufferDecodesToTheAnalyticValues) {
  const std::string dir = freshDir("import-fixture-b");
  const Scene s = makeScene();
  writeFixtureB(dir, s);
  Capture c = importAndLoad("--layout '" + dir + "/b.json'", dir + "/imported");
  const FrameSnapshot& f = c.frame;
  ASSERT_EQ(f.images.size(), 3u);
  EXPECT_TRUE(f.camera.reversedZ);
  // Half normals: each component rounded by at most half a half-float ulp below 1, 2^-12.
  expectNormals(f, s, quantity(f, "N"), std::ldexp(1.0, -12), "B world normals (xyz half)");
  expectHardwareDepth(f, s, quantity(f, "Zrev"), d3dReversedDepth, eyeDepthFromD3dReversedDepth, "B reversed D3D depth");
  expectStoredPositions(f, s, quantity(f, "P"), "B stored world positions (TIFF)");
}

// ---- malformed input: one line naming file, target and field; exit 2; nothing at -o --------------

struct Case {
  std::string name;
  std::function<void(json& layout, const std::string& dir)> spoil;
  std::vector<std::string> words;  // each must appear in the message
  std::string extraArgs;
};

void expectRefused(const std::string& dir, const std::string& args, const std::vector<std::string>& words, const std::string& what) {
  SCOPED_TRACE(what);
  const std::string out = dir + "/out-" + what;
  RunResult r = runGblens("import " + args + " -o '" + out + "'");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  // Progress lines ("  .. reading ...") come first; the mistake is one line of its own.
  std::string message = r.output;
  while (message.rfind("  .. ", 0) == 0) message.erase(0, message.find('\n') + 1);
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << "not one line:\n" << r.output;
  EXPECT_EQ(message.rfind("gblens import: ", 0), 0u) << r.output;
  for (const std::string& w : words) EXPECT_NE(r.output.find(w), std::string::npos) << "'" << w << "' not in: " << r.output;
  EXPECT_FALSE(fs::exists(out)) << out << " was written";
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".out-"), std::string::npos) << "left behind: " << e.path();
}

TEST(Import, MalformedInputGivesOneLineExitTwoAndWritesNothing) {
  const std::string dir = freshDir("import-malformed");
  const Scene s = makeScene();
  const json good = writeFixtureA(dir, s);
  // A raw dump one texel short, and an EXR of the wrong size.
  std::ifstream full(dir + "/normal_oct.bin", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(full)), {});
  std::ofstream(dir + "/short_oct.bin", std::ios::binary) << bytes.substr(0, bytes.size() - 4);
  const std::string layoutFile = "'" + dir + "/case.json'";
  const std::string t = "targets[";  // as the layout parser names a target: targets[i]: "name"
  std::vector<Case> cases = {
      {"missing-channel", [](json& l, auto&) { l["targets"][1]["source"]["channels"] = {"N.X", "N.Y", "N.W"}; },
       {"case.json", t + "1]: \"normal_world\"", "gbuffer.exr", "source.channels", "no channel \"N.W\""}},
      {"wrong-size", [](json& l, auto&) { l["size"] = {32, 24}; },
       {"case.json", t + "0]: \"eye_depth\"", "gbuffer.exr", "size 64x48, the layout says 32x24"}},
      {"short-raw", [](json& l, auto&) { l["targets"][4]["source"]["file"] = "short_oct.bin"; },
       {"case.json", t + "4]: \"normal_oct\"", "short_oct.bin", "holds 12284 bytes", "needs 12288"}},
      {"format-not-the-files", [](json& l, auto&) { l["targets"][3]["format"] = "rgb16_unorm"; },
       {"case.json", t + "3]: \"normal_png\"", "normal_view.png", "format: channel \"R\" is uint8", "rgb16_unorm"}},
      {"format-the-encoding-cannot-hold",
       [](json& l, auto&) {
         l["targets"][1]["quantities"][0]["encoding"] = "octahedral";
         l["targets"][1]["quantities"][0]["bits"] = 12;
       },
       {"case.json", t + "1]: \"normal_world\"", "quantities[0] \"Nworld\"", "bits", "8-bit unorm", "rgb32f"}},
      {"depth-in-integers",
       [](json& l, auto&) { l["targets"][5]["format"] = "r32_uint"; },
       {"case.json", t + "5]: \"hardware_depth\"", "encoding", "hardware depth cannot be held by the integer format r32_uint"}},
      {"singular-matrix", [](json& l, auto&) { l["camera"]["clip_from_view"] = json(std::vector<double>(16, 0.0)); },
       {"case.json", "camera: clip_from_view", "singular"}},
      {"unknown-encoding", [](json& l, auto&) { l["targets"][4]["quantities"][0]["encoding"] = "octahedron"; },
       {"case.json", t + "4]: \"normal_oct\"", "quantities[0] \"Noct\"", "encoding", "\"octahedron\" is not one of"}},
      {"missing-file", [](json& l, auto&) { l["targets"][6]["source"]["file"] = "nowhere.exr"; },
       {"case.json", t + "6]: \"radial_depth\"", "nowhere.exr", "source.file", "cannot read"}},
      {"missing-part", [](json& l, auto&) { l["targets"][6]["source"]["part"] = "linear"; },
       {"case.json", t + "6]: \"radial_depth\"", "depth.exr", "source.part", "no part named \"linear\""}},
      {"camera-needed", [](json& l, auto&) { l.erase("camera"); },
       {"case.json", t + "1]: \"normal_world\"", "\"Nworld\"", "camera"}},
  };
  for (Case& c : cases) {
    json layout = good;
    c.spoil(layout, dir);
    writeJson(dir + "/case.json", layout);
    expectRefused(dir, "--layout " + layoutFile + c.extraArgs, c.words, c.name);
  }
  // The layout itself, the command line's values, a singular camera from a sidecar.
  expectRefused(dir, "--layout '" + dir + "/none.json'", {"none.json", "cannot read the layout file"}, "no-layout");
  std::ofstream(dir + "/broken.json") << "{\"format\": \"gblens-layout\", ";
  expectRefused(dir, "--layout '" + dir + "/broken.json'", {"broken.json", "not valid JSON"}, "broken-layout");
  expectRefused(dir, "--layout builtin:nonesuch", {"builtin:nonesuch", "no such built-in layout", "builtin:gblens"}, "builtin");
  expectRefused(dir, "--layout builtin:gblens --param normal_format=oct-rg17", {"--param", "--normal-format oct-rg17", "oct-rg16"},
                "param-value");
  expectRefused(dir, "--layout builtin:gblens --param normal_fmt=oct-rg16", {"--param normal_fmt=oct-rg16", "NAME=VALUE"}, "param-name");
  writeJson(dir + "/case.json", good);
  writeJson(dir + "/flat.json", {{"view_from_world", std::vector<double>(16, 0.0)}, {"clip_from_view", json(good["camera"]["clip_from_view"])}});
  expectRefused(dir, "--layout " + layoutFile + " --camera '" + dir + "/flat.json'", {"flat.json", "view_from_world", "singular"},
                "sidecar-singular");
  expectRefused(dir, "'" + dir + "/gbuffer.exr' --layout " + layoutFile + " --event 3", {"--event", ".rdc"}, "event-without-rdc");
}

}  // namespace
}  // namespace gb
