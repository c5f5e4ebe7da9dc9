// Capture test helpers.
#include "tests/support/test_paths.h"
#include "tests/support/capture_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "renderer/core/camera.h"
#include "renderer/core/layout_json.h"

namespace gb {

std::string freshDir(const std::string& name) {
  namespace fs = std::filesystem;
  fs::path p = fs::temp_directory_path() / ("gblens-test-" + std::to_string(getpid())) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

RunResult runShell(const std::string& command) {
  RunResult r;
  std::FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  int status = pclose(p);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

RunResult runGblens(const std::string& args) { return runShell(std::string("'") + GBLENS_BINARY + "' " + args); }

RenderOptions smallCaptureOptions() {
  RenderOptions o;
  o.width = 96;
  o.height = 54;
  o.lights = 24;
  o.shadowMapSize = 128;
  o.coverage = true;
  o.primitiveId = true;                      // every target computed, so every target is captured
  o.position = PositionSource::Rgba32f;
  o.time = 1.5;
  return o;
}

void setTexel(CpuImage& img, uint32_t x, uint32_t y, uint32_t c, double v) {
  uint8_t* p = img.data.data() + (size_t(y) * img.width + x) * img.texelBytes() + c * pixelTypeSize(img.type);
  switch (img.type) {
    case PixelType::F16: {
      uint16_t h = floatToHalf(float(v));
      std::memcpy(p, &h, 2);
      break;
    }
    case PixelType::F32: {
      float f = float(v);
      std::memcpy(p, &f, 4);
      break;
    }
    case PixelType::U8: *p = uint8_t(v); break;
    case PixelType::U32: {
      uint32_t u = uint32_t(v);
      std::memcpy(p, &u, 4);
      break;
    }
    default: std::abort();  // not used by the synthetic frames
  }
}

FrameSnapshot syntheticFrame(uint32_t w, uint32_t h) {
  FrameSnapshot f;
  f.options.width = w;
  f.options.height = h;
  f.options.coverage = true;
  f.options.normalFormat = NormalFormat::Rgba16f;  // N = (0, 0, 1) stored as is
  f.options.accumFormat = AccumFormat::Rgba16f;
  CameraDesc cam;
  cam.worldFromEye = lookAt({0, 2, 5}, {0, 0, 0});
  f.camera = makeCamera(cam, w, h, false);
  f.setLayout(nativeLayout(f.options));
  for (Target t : {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth, Target::DepthStencil, Target::Hdr,
                   Target::Final, Target::CoverageMasked}) {
    TargetImage& ti = f.target(t);
    describeReadback(t, f.options, ti.image);
    ti.image.width = ti.targetWidth = w;
    ti.image.height = ti.targetHeight = h;
    ti.image.data.assign(size_t(w) * h * ti.image.texelBytes(), 0);
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        double u = (x + 0.5) / w, v = (y + 0.5) / h;
        for (uint32_t c = 0; c < ti.image.channelCount(); ++c) {
          double value = 0.0;
          switch (t) {
            case Target::AlbedoSpecular:
            case Target::Final: value = std::floor(255.0 * (c == 3 ? 1.0 : c == 0 ? u : c == 1 ? v : 0.5)); break;
            case Target::NormalShadow: value = c == 2 || c == 3 ? 1.0 : 0.0; break;
            case Target::Depth: value = 2.0 + 3.0 * u; break;
            case Target::DepthStencil: value = c == 0 ? 0.9 + 0.05 * v : 128.0; break;
            case Target::Hdr: value = c == 3 ? 1.0 : 0.25 + u + c * v; break;
            default: value = double((x + y) % 4); break;
          }
          setTexel(ti.image, x, y, c, value);
        }
      }
    f.setAbsence(t, Absent::No);
  }
  return f;
}

// The plane's colour at world (x, y): a checkerboard, red and blue by square, green by height.
static glm::dvec3 planeColour(double x, double y) {
  const bool odd = (int64_t(std::floor(x / 0.25)) + int64_t(std::floor(y / 0.25))) & 1;
  return odd ? glm::dvec3(0.8, 0.5, 0.15) : glm::dvec3(0.1, 0.3 + 0.1 * std::clamp(y, -2.0, 2.0), 0.7);
}

FrameSnapshot planeFrame(uint32_t w, uint32_t h, double cameraX, double brightness) {
  FrameSnapshot f = syntheticFrame(w, h);
  CameraDesc cam;
  cam.worldFromEye = lookAt({cameraX, 0, kPlaneDepth}, {cameraX, 0, 0});
  f.camera = makeCamera(cam, w, h, false);
  auto srgb = [](double v) { return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; };
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const glm::dvec3 eye = eyeFromEyeDepth(f.camera, x, y, kPlaneDepth);
      const glm::dvec3 world = glm::dvec3(f.camera.worldFromEye * glm::dvec4(eye, 1.0));
      const glm::dvec3 c = glm::clamp(planeColour(world.x, world.y) * brightness, 0.0, 1.0);
      for (uint32_t k = 0; k < 3; ++k) {
        setTexel(f.target(Target::AlbedoSpecular).image, x, y, k, std::round(255.0 * c[k]));
        setTexel(f.target(Target::Final).image, x, y, k, std::round(255.0 * srgb(c[k])));
        setTexel(f.target(Target::Hdr).image, x, y, k, c[k]);
      }
      setTexel(f.target(Target::Depth).image, x, y, 0, kPlaneDepth);
      setTexel(f.target(Target::DepthStencil).image, x, y, 0, hardwareDepth(f.camera, eye));
    }
  return f;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace gb
