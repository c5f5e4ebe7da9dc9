// gblens on "another renderer": tests/subjects/foreign_deferred, a Vulkan deferred app written for
// these tests with conventions gblens does not use (Y-down world, view-space rgba32f positions with
// eye depth / far in w, xyz_unorm normals, an r8 occlusion pass, unnamed textures, the projection
// before the view matrix in its uniform buffer, an orthographic variant). Its RenderDoc captures
// (the foreign_captures fixture) are imported with its hand-written layout.json and checked against
// the app's own read-back of the same frame (--dump): every stored texel bit for bit, and positions
// rebuilt from its depth against its stored positions within a derived bound; the manifest's
// provenance; what the viewer and probe offer for it (only the layout's quantities).
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "renderer/core/decode.h"
#include "tests/support/capture_util.h"
#include "views/analysis/view_table.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kLayout = FOREIGN_DEFERRED_DIR + "/layout.json";
const std::string kApp = FOREIGN_DEFERRED_BINARY;
const std::string kOut = GBLENS_BUILD_DIR + "/foreign";

struct Variant {
  const char* name;  // for messages
  std::string rdc, dump;
};
const Variant kPerspective{"perspective", kOut + "/foreign.rdc", kOut + "/dump"};
const Variant kOrthographic{"orthographic", kOut + "/foreign_ortho.rdc", kOut + "/dump_ortho"};

// The app's own read-back (its README: camera.json, one raw file per target, rows top first).
struct AppDump {
  json camera;
  uint32_t width = 0, height = 0;
  std::map<std::string, std::string> bytes;  // target name -> the file's bytes
  glm::vec4 position(uint32_t x, uint32_t y) const {
    glm::vec4 p;
    std::memcpy(&p, bytes.at("position").data() + (size_t(y) * width + x) * sizeof(p), sizeof(p));
    return p;
  }
};

AppDump loadDump(const std::string& dir) {
  AppDump d;
  std::ifstream in(dir + "/camera.json");
  EXPECT_TRUE(in) << dir << "/camera.json is missing: the foreign_captures fixture did not run (ctest -R Foreign runs it)";
  if (!in) return d;
  d.camera = json::parse(in);
  d.width = d.camera["width"];
  d.height = d.camera["height"];
  for (const json& t : d.camera["targets"]) d.bytes[t["name"]] = readText(dir + "/" + t["file"].get<std::string>());
  return d;
}

struct Imported {
  bool ok = false;
  Capture capture;
};

// `gblens import RDC --layout layout.json`, the layout as written (the G-buffer targets are read
// after render pass 1, the pass that last writes them; the camera at the first use of the uniform
// buffer).
Imported importCapture(const Variant& v, const std::string& dir) {
  Imported r;
  const std::string out = dir + "/imported";
  RunResult run = runGblens("import '" + v.rdc + "' --layout '" + kLayout + "' -o '" + out + "'");
  if (run.exitCode != 0) {
    ADD_FAILURE() << "gblens import of the " << v.name << " capture failed:\n" << run.output;
    return r;
  }
  std::string error;
  r.ok = loadCapture(out, r.capture, error);
  EXPECT_TRUE(r.ok) << error;
  return r;
}

// Every target of the layout, as imported, byte for byte against the app's read-back.
void expectTexelsEqual(const Capture& c, const AppDump& d, const std::string& variant) {
  ASSERT_EQ(d.bytes.size(), 7u);
  for (const auto& [name, bytes] : d.bytes) {
    SCOPED_TRACE(variant + " target " + name);
    const int i = c.frame.indexOf(name);
    ASSERT_GE(i, 0) << "the layout has no target " << name;
    const CpuImage& img = c.frame.images[size_t(i)].image;
    ASSERT_EQ(img.width, d.width);
    ASSERT_EQ(img.height, d.height);
    ASSERT_EQ(img.data.size(), bytes.size()) << "stored with another texel size";
    const size_t texel = bytes.size() / (size_t(d.width) * d.height);
    size_t differing = 0, first = 0;
    for (size_t k = 0; k < bytes.size(); k += texel)
      if (std::memcmp(img.data.data() + k, bytes.data() + k, texel) != 0 && differing++ == 0) first = k / texel;
    EXPECT_EQ(differing, 0u) << "texels differ, the first at (" << first % d.width << ", " << first / d.width << ")";
  }
}

// The bound on |rebuilt - stored| at a surface pixel (fp32 storage, lavapipe or any Vulkan rasteriser):
//  - the rasteriser snaps vertices to 2^-s pixel (s: subPixelPrecisionBits, in the app's camera.json) and
//    may interpolate from the snapped triangle, so the point a pixel stores may lie up to sqrt(2) 2^-(s+1)
//    pixel beside the pixel centre gblens unprojects at the same depth: that many pixel widths at its depth;
//  - hardware depth only: the stored D32 value is the rasteriser's fp32 evaluation of the depth plane,
//    off the depth of the stored position by Kd = 32 units of 2^-24 (measured on lavapipe: 3.5 with this
//    perspective camera, 17 with the orthographic one, whose ground triangles reach far off screen), moved
//    into the point by |de/dd| (perspective e^2 (f - n) / (n f), times |p| / e for the whole point;
//    orthographic f - n);
//  - the stored position is itself an fp32 interpolation: 16 ulps (2^-24) of |p|.
// Linear depth (w * far) adds no depth term: w = eye * 2^-5 is exact. A wrong matrix or offset is metres
// off; a half-pixel shift is about 30 times the bound at 10 m.
double positionBound(const json& cam, const glm::dvec3& p, bool hardwareDepth) {
  const double u = std::ldexp(1.0, -24), n = cam["near"], f = cam["far"];
  const double e = -p.z, length = glm::length(p);
  const bool ortho = cam["projection"] == "orthographic";
  const double p11 = std::abs(cam["clip_from_view"][5].get<double>());
  const double pixel = 2.0 / (p11 * cam["height"].get<double>()) * (ortho ? 1.0 : e);
  const double beside = pixel * std::sqrt(2.0) * std::ldexp(1.0, -(cam["sub_pixel_precision_bits"].get<int>() + 1));
  const double dedd = ortho ? f - n : e * e * (f - n) / (n * f) * length / e;
  return beside + (hardwareDepth ? dedd * 32.0 * u : 0.0) + 16.0 * u * length;
}

// Positions gblens rebuilds from one depth quantity against the stored ones, at every pixel; the
// surface (the app's w < 1) must be where gblens finds one.
void expectPositions(const Capture& c, const AppDump& d, const std::string& depthName, const std::string& variant) {
  const Quantity* depth = c.frame.layout.findByName(depthName);
  ASSERT_NE(depth, nullptr) << depthName;
  const bool hardware = depth->depth == DepthEncoding::Hardware;
  size_t surfaces = 0, wrongSurface = 0, missing = 0, over = 0;
  double worst = 0.0, worstError = 0.0;
  glm::uvec2 worstAt{0};
  for (uint32_t y = 0; y < d.height; ++y)
    for (uint32_t x = 0; x < d.width; ++x) {
      const glm::vec4 stored = d.position(x, y);
      const bool surface = stored.w < 1.0f;
      wrongSurface += hasSurface(c.frame, x, y) != surface;
      if (!surface) continue;
      ++surfaces;
      const std::optional<glm::dvec3> rebuilt = decodePosition(c.frame, *depth, x, y);
      if (!rebuilt) {
        ++missing;
        continue;
      }
      const glm::dvec3 p(stored);
      const double error = glm::length(*rebuilt - p), ratio = error / positionBound(d.camera, p, hardware);
      over += ratio > 1.0;
      if (ratio > worst) {
        worst = ratio;
        worstError = error;
        worstAt = {x, y};
      }
    }
  std::ostringstream s;
  s << variant << ", " << depthName << ": " << surfaces << " surface pixels, worst |rebuilt - stored| = " << worstError
    << " at (" << worstAt.x << ", " << worstAt.y << "), " << worst << " of the bound";
  std::cout << s.str() << "\n";
  EXPECT_GT(surfaces, size_t(d.width) * d.height / 4) << s.str();
  EXPECT_EQ(wrongSurface, 0u) << "pixels where gblens and the app disagree on a surface; " << s.str();
  EXPECT_EQ(missing, 0u) << "surface pixels without a rebuilt position; " << s.str();
  EXPECT_EQ(over, 0u) << "pixels beyond the bound; " << s.str();
}

glm::dmat4 appMatrix(const json& cam, const char* name) {
  glm::dmat4 m;
  for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = cam[name][i].get<double>();  // column-major, as stored
  return m;
}

// The projection gblens read from the uniform buffer (offset 0) is the app's, float for float.
void expectProjection(const Capture& c, const AppDump& d) {
  const glm::dmat4 app = appMatrix(d.camera, "clip_from_view");
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      EXPECT_EQ(c.frame.camera.clipFromEye[col][row], app[col][row]) << "clip_from_view[" << col << "][" << row << "]";
}

void importAndCheck(const Variant& v, const std::string& dir) {
  const AppDump d = loadDump(v.dump);
  ASSERT_FALSE(d.bytes.empty());
  const Imported imp = importCapture(v, dir);
  ASSERT_TRUE(imp.ok);
  expectTexelsEqual(imp.capture, d, v.name);
  expectProjection(imp.capture, d);
  expectPositions(imp.capture, d, "Depth", v.name);
}

TEST(Foreign, PerspectiveCaptureImportsEveryTexelAndPositionsFromHardwareDepth) {
  importAndCheck(kPerspective, freshDir("foreign-perspective"));
}

TEST(Foreign, OrthographicCaptureImportsEveryTexelAndPositionsFromHardwareDepth) {
  importAndCheck(kOrthographic, freshDir("foreign-orthographic"));
}

// Positions from the linear depth in w (eye depth = w * 32, exact: w = eye * 2^-5 is exact in fp32;
// the layout says "scale": 32); for the orthographic camera x and y do not grow with depth.
void linearDepth(const Variant& v, const std::string& dir) {
  const AppDump d = loadDump(v.dump);
  ASSERT_FALSE(d.bytes.empty());
  const Imported imp = importCapture(v, dir);
  ASSERT_TRUE(imp.ok);
  expectPositions(imp.capture, d, "LinearDepth", v.name);
}

// RenderDoc writes one .rdc per captured frame (APP_frameN.rdc): `import 'APP_frame#.rdc' --frames A..B`
// reads them as one sequence (docs/temporal.md). Frame 1 is the perspective capture and frame 2 the
// orthographic one (links named as RenderDoc names frames): each frame's texels are the app's dump.
TEST(Foreign, SeveralCapturesImportAsOneSequenceFrameForFrame) {
  const std::string dir = freshDir("foreign-sequence");
  std::filesystem::create_symlink(kPerspective.rdc, dir + "/app_frame1.rdc");
  std::filesystem::create_symlink(kOrthographic.rdc, dir + "/app_frame2.rdc");
  RunResult r = runGblens("import '" + dir + "/app_frame#.rdc' --layout '" + kLayout + "' --frames 1..2 -o '" + dir + "/seq'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const auto& [n, v] : {std::pair{1, kPerspective}, std::pair{2, kOrthographic}}) {
    Capture c;
    std::string error;
    ASSERT_TRUE(loadCapture(dir + "/seq@" + std::to_string(n), c, error)) << error;
    expectTexelsEqual(c, loadDump(v.dump), v.name);
  }
  r = runGblens("import '" + dir + "/app_frame#.rdc' --layout '" + kLayout + "' --frames 1..3 -o '" + dir + "/short'");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("frame 3"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/short"));
}

TEST(Foreign, PerspectivePositionsFromLinearDepth) { linearDepth(kPerspective, freshDir("foreign-linear")); }
TEST(Foreign, OrthographicPositionsFromLinearDepth) { linearDepth(kOrthographic, freshDir("foreign-linear-ortho")); }

// What only the layout's camera can show: the world's up direction seen from the eye is the app's (its
// world up is -Y, gblens's +Y).
TEST(Foreign, LayoutIsReadAsWrittenAndTheWorldIsYDown) {
  const AppDump d = loadDump(kPerspective.dump);
  ASSERT_FALSE(d.bytes.empty());
  const std::string dir = freshDir("foreign-layout");
  RunResult r = runGblens("import '" + kPerspective.rdc + "' --layout '" + kLayout + "' -o '" + dir + "/out'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/out", c, error)) << error;
  expectProjection(c, d);
  // The up direction in eye space: the app's view matrix applied to its up (0, -1, 0), and gblens's
  // eye-from-world applied to its own up (0, 1, 0). Within float rounding of the matrices.
  const glm::dvec3 appUp = glm::dvec3(appMatrix(d.camera, "view_from_world") * glm::dvec4(0, -1, 0, 0));
  const glm::dvec3 gblensUp = glm::dvec3(c.frame.camera.eyeFromWorld * glm::dvec4(0, 1, 0, 0));
  EXPECT_LT(glm::length(appUp - gblensUp), 1e-6) << "app (" << appUp.x << ", " << appUp.y << ", " << appUp.z
                                                  << "), gblens (" << gblensUp.x << ", " << gblensUp.y << ", " << gblensUp.z << ")";
}

// What gblens offers for the imported frame is the layout's, nothing of gblens's own: a view per
// quantity the layout declares (position and occlusion among them; no shadow, specular or stencil
// view), and a probe whose quantities are exactly the layout's, with the stored texel as the app
// wrote it (its own dump).
TEST(Foreign, ViewsAndProbeShowOnlyTheLayoutsQuantities) {
  const AppDump d = loadDump(kPerspective.dump);
  ASSERT_FALSE(d.bytes.empty());
  const Imported imp = importCapture(kPerspective, freshDir("foreign-views"));
  ASSERT_TRUE(imp.ok);
  const json layout = json::parse(std::ifstream(kLayout));
  std::vector<std::string> declared, kinds;
  for (const json& t : layout["targets"])
    for (const json& q : t["quantities"]) declared.push_back(q["name"]), kinds.push_back(q["quantity"]);
  std::sort(declared.begin(), declared.end());
  std::vector<std::string> views;
  for (const ViewDef& v : layoutViews(imp.capture.frame.layout)) views.push_back(v.name);
  std::sort(views.begin(), views.end());
  EXPECT_EQ(views, declared);
  for (const char* kind : {"position", "occlusion"})
    EXPECT_NE(std::find(kinds.begin(), kinds.end(), kind), kinds.end()) << kind << " is not in the layout";
  for (const char* gblensOnly : {"Shadow", "Specular", "Stencil", "ShadowMap"})
    EXPECT_EQ(std::find(views.begin(), views.end(), gblensOnly), views.end()) << gblensOnly;

  // A pixel the occlusion pass darkened (first one under 250 from the centre row).
  const std::string& ao = d.bytes.at("occlusion");
  uint32_t px = d.width / 2, py = d.height / 2;
  for (uint32_t x = 0; x < d.width; ++x)
    if (uint8_t(ao[size_t(py) * d.width + x]) < 250 && d.position(x, py).w < 1.0f) {
      px = x;
      break;
    }
  RunResult r = runGblens("probe '" + imp.capture.dir + "' " + std::to_string(px) + " " + std::to_string(py) + " --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json dossier = json::parse(r.output.substr(r.output.find('{')));
  std::vector<std::string> probed;
  std::map<std::string, json> byName;
  for (const json& q : dossier["quantities"]) probed.push_back(q["name"]), byName[q["name"]] = q;
  std::sort(probed.begin(), probed.end());
  EXPECT_EQ(probed, declared);
  // One shape for every layout (docs/schemas/probe.schema.json): gblens's own sections null here.
  for (const char* gblensOnly : {"shadow_map", "hdr", "final"})
    EXPECT_TRUE(dossier.contains(gblensOnly) && dossier[gblensOnly].is_null()) << gblensOnly << " in a foreign frame's dossier";
  EXPECT_FALSE(dossier.contains("lights"));
  // Occlusion: r8_unorm, the app's byte / 255; the stored position and the linear depth as written.
  const uint8_t code = uint8_t(ao[size_t(py) * d.width + px]);
  EXPECT_NEAR(byName["AO"]["values"][0].get<double>(), code / 255.0, 1e-9) << byName["AO"].dump();
  const glm::vec4 p = d.position(px, py);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(byName["P"]["values"][k].get<double>(), double(p[k])) << k;
  EXPECT_DOUBLE_EQ(byName["LinearDepth"]["values"][0].get<double>(), double(p.w) * 32.0);
}

// Provenance: the manifest names the device the application recorded on (as the app itself reports
// it) and the replay's; compare warns when two imports were replayed on different drivers.
TEST(Foreign, TheManifestSaysWhereTheFrameWasRecordedAndReplayed) {
  const AppDump d = loadDump(kPerspective.dump);
  ASSERT_FALSE(d.bytes.empty());
  const std::string dir = freshDir("foreign-provenance");
  RunResult r = runGblens("import '" + kPerspective.rdc + "' --layout '" + kLayout + "' -o '" + dir + "/a'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/a", c, error)) << error;
  ASSERT_TRUE(c.manifest.contains("source")) << c.manifest.dump(2);
  const json& source = c.manifest["source"];
  EXPECT_EQ(source.value("tool", ""), "RenderDoc");
  EXPECT_EQ(source["recorded"].value("api", ""), "Vulkan");
  EXPECT_EQ(source["recorded"].value("device", ""), d.camera.at("gpu").get<std::string>());
  EXPECT_FALSE(source["replay"].value("device", "").empty());
  EXPECT_FALSE(c.manifest.contains("options")) << "gblens render options written for a foreign frame";

  // The same frame "replayed elsewhere": the warning names both devices; the same replay: none.
  fs::copy(dir + "/a", dir + "/b", fs::copy_options::recursive);
  json m = json::parse(std::ifstream(dir + "/b/manifest.json"));
  m["source"]["replay"]["device"] = "Another GPU (another driver 1.0)";
  std::ofstream(dir + "/b/manifest.json") << m.dump(2) << "\n";
  RunResult same = runGblens("compare '" + dir + "/a' '" + dir + "/a'");
  EXPECT_EQ(same.output.find("replay drivers"), std::string::npos) << same.output;
  RunResult other = runGblens("compare '" + dir + "/a' '" + dir + "/b'");
  EXPECT_EQ(other.exitCode, 0) << other.output;
  EXPECT_NE(other.output.find("gblens compare: warning: "), std::string::npos) << other.output;
  EXPECT_NE(other.output.find("Another GPU (another driver 1.0)"), std::string::npos) << other.output;
  EXPECT_NE(other.output.find(source["replay"].value("device", "?")), std::string::npos) << other.output;
}


// The subject itself, independently of gblens: the same pixels every run (and under RenderDoc: the
// fixture's dump equals a plain run's), frames that differ, no validation message, and the conventions
// its README states, read from its own dump.
void expectSameFiles(const std::string& a, const std::string& b) {
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(a)) {
    ++files;
    EXPECT_TRUE(readText(e.path().string()) == readText(b + "/" + e.path().filename().string()))
        << e.path().filename() << " differs between " << a << " and " << b;
  }
  EXPECT_EQ(files, 9u) << a;
}

void expectDocumentedConventions(const std::string& dir, bool ortho) {
  const AppDump d = loadDump(dir);
  ASSERT_FALSE(d.bytes.empty());
  const std::string& depth = d.bytes.at("depth");
  const std::string& normal = d.bytes.at("normal");
  const std::string& occlusion = d.bytes.at("occlusion");
  size_t surfaces = 0, bad = 0;
  for (uint32_t y = 0; y < d.height; ++y)
    for (uint32_t x = 0; x < d.width; ++x) {
      const size_t i = size_t(y) * d.width + x;
      const glm::vec4 p = d.position(x, y);
      float z;
      std::memcpy(&z, depth.data() + 4 * i, 4);
      const bool surface = p.w < 1.0f;
      surfaces += surface;
      glm::vec3 n;
      for (int c = 0; c < 3; ++c) n[c] = float(uint8_t(normal[4 * i + c])) / 255.0f * 2.0f - 1.0f;
      if (surface)  // w = eye depth * (1 / 32) exactly; D32 depth below the far plane's 1; a unit normal (8 bits)
        bad += !(p.w == -p.z * 0.03125f && z < 1.0f && std::abs(glm::length(n) - 1.0f) < 0.01f);
      else  // the clear values: position (0, 0, 0, 1), depth 1, normal 0, occlusion 1
        bad += !(p == glm::vec4(0, 0, 0, 1) && z == 1.0f && n == glm::vec3(-1.0f) && uint8_t(occlusion[i]) == 255);
    }
  EXPECT_EQ(bad, 0u) << dir;
  EXPECT_GT(surfaces, size_t(d.width) * d.height / 4) << dir;
  // The uniform buffer: the projection at offset 0, the view matrix at 64, as camera.json says.
  const std::string ubo = readText(dir + "/uniforms.bin");
  ASSERT_EQ(ubo.size(), 464u);
  for (int i = 0; i < 16; ++i) {
    float proj, view;
    std::memcpy(&proj, ubo.data() + 4 * i, 4);
    std::memcpy(&view, ubo.data() + 64 + 4 * i, 4);
    EXPECT_EQ(proj, d.camera["clip_from_view"][i].get<float>()) << i;
    EXPECT_EQ(view, d.camera["view_from_world"][i].get<float>()) << i;
  }
  // Y-down world: the world's up (0, -1, 0) points up the picture (view +Y); orthographic: w = 1.
  const glm::dmat4 view = appMatrix(d.camera, "view_from_world"), proj = appMatrix(d.camera, "clip_from_view");
  EXPECT_GT((view * glm::dvec4(0, -1, 0, 0)).y, 0.9);
  EXPECT_EQ(proj[3][3], ortho ? 1.0 : 0.0);
  EXPECT_EQ(proj[2][3], ortho ? 0.0 : -1.0);
}

TEST(Foreign, AppIsDeterministicValidatedAndAsDocumented) {
  const std::string dir = freshDir("foreign-app");
  auto run = [&](const std::string& args, const std::string& out) {
    RunResult r = runShell("GBLENS_VALIDATE=1 '" + kApp + "' " + args + " --dump '" + dir + "/" + out + "'");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
  };
  run("", "a");
  run("--frames 3", "b");
  run("--ortho", "ortho");
  run("--frames 2", "frame1");
  expectSameFiles(dir + "/a", dir + "/b");
  expectSameFiles(dir + "/a", kPerspective.dump);   // rendered under RenderDoc by the fixture
  expectSameFiles(dir + "/ortho", kOrthographic.dump);
  EXPECT_FALSE(readText(dir + "/a/position.bin") == readText(dir + "/frame1/position.bin")) << "frames 1 and 2 are alike";
  expectDocumentedConventions(dir + "/a", false);
  expectDocumentedConventions(dir + "/ortho", true);

  RunResult bad = runShell("'" + kApp + "' --size 0x5 --dump '" + dir + "/bad'");
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("--size 0x5: expected WxH"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir + "/bad"));
}

}  // namespace
}  // namespace gb
