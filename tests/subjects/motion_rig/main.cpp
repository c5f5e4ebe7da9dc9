// motion_rig: a CPU ray caster standing for "another renderer" that writes a G-buffer sequence with
// motion vectors, a lit colour and its history target (TAA's previous frame, reprojected by the
// true motion) (README.md). Shares no code or header with gblens.
//
//   motion_rig --out DIR --frames N [--width W --height H] [--bug MODE]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "rig.h"

namespace {

using namespace rig;

const char* const kModes[] = {"none",           "y_flipped",       "direction_flipped",       "half_scale",
                              "pixels_not_uv",  "one_frame_late",  "jitter_included",         "history_stale",
                              "history_not_reprojected", "history_current"};

int usage(const std::string& why) {
  std::fprintf(stderr, "motion_rig: %s\nusage: motion_rig --out DIR --frames N [--width W --height H] [--bug MODE]\n"
               "modes: none y_flipped direction_flipped half_scale pixels_not_uv one_frame_late jitter_included\n"
               "       history_stale history_not_reprojected history_current\n",
               why.c_str());
  return 2;
}

// Everything one frame holds, before any bug.
struct Frame {
  int width = 0, height = 0;
  std::vector<float> depth, normal, albedo, object, colour;  // normal, albedo, colour: 3 a texel
  std::vector<vec2> motion;    // pixels, x right, y down, to the previous frame, jitter excluded
  std::vector<vec2> jittered;  // the same from the jittered positions
  std::vector<float> mask;     // 0 sky, 1 static, 2 moving, 3 disoccluded
  std::vector<vec2> historyAt; // where the point was in the previous frame's stored (jittered) image
};

Frame render(int f, int w, int h) {
  Frame out;
  out.width = w, out.height = h;
  const size_t n = size_t(w) * h;
  out.depth.assign(n, 0.0f), out.normal.assign(3 * n, 0.0f), out.albedo.assign(3 * n, 0.0f);
  out.object.assign(n, 0.0f), out.motion.assign(n, vec2(0.0)), out.jittered.assign(n, vec2(0.0)), out.mask.assign(n, 0.0f);
  out.colour.assign(3 * n, 0.0f), out.historyAt.assign(n, vec2(NAN));
  const Scene scene(f), before(f - 1);
  const Camera cam = cameraAt(f, w, h), prev = cameraAt(f - 1, w, h);
  const mat4 prevFromNow = Scene::spinnerFromObject(f - 1) * glm::inverse(Scene::spinnerFromObject(f));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      // The pixel centre samples the jittered image: in unjittered coordinates it is centre - jitter.
      const vec2 centre(x + 0.5, y + 0.5), u = centre - cam.jitter;
      const Ray ray = cam.ray(u);
      const std::optional<Hit> hit = scene.trace(ray);
      vec4 now, then;  // world point (or direction) now, and where it was at f - 1
      if (!hit) {
        now = then = vec4(ray.direction, 0.0);  // the sky: a direction, moved by the camera's turning alone
      } else {
        now = vec4(hit->position, 1.0);
        then = hit->id == kMovingId ? prevFromNow * now : now;
        const vec4 v = cam.viewFromWorld * now;
        out.depth[i] = float(kNear / v.z);
        const vec3 lit = shade(*hit, f);
        for (int k = 0; k < 3; ++k) out.normal[3 * i + k] = float(hit->normal[k]), out.albedo[3 * i + k] = float(hit->albedo[k]);
        for (int k = 0; k < 3; ++k) out.colour[3 * i + k] = float(lit[k]);
        out.object[i] = float(hit->id);
      }
      const std::optional<vec2> p1 = cam.project(now), p0 = prev.project(then);
      if (!p1 || !p0) {  // behind the previous eye: no vector (never happens on this path)
        out.mask[i] = hit ? 3.0f : 0.0f;
        continue;
      }
      out.motion[i] = *p0 - *p1;
      out.historyAt[i] = *p0 + prev.jitter;  // the jittered image of f - 1 shows the point there
      out.jittered[i] = (*p0 + prev.jitter) - (*p1 + cam.jitter);
      if (!hit) continue;
      float m = hit->id == kMovingId ? 2.0f : 1.0f;
      // Visible at f - 1? On screen there, and the first thing a ray from the previous eye meets.
      if (p0->x < 0.0 || p0->y < 0.0 || p0->x >= w || p0->y >= h) {
        m = 3.0f;
      } else {
        const vec3 target = vec3(then), toward = target - prev.eye;
        const double dist = glm::length(toward);
        const std::optional<Hit> first = before.trace({prev.eye, toward / dist});
        if (first && first->t < dist - 1e-4) m = 3.0f;
      }
      out.mask[i] = m;
    }
  return out;
}

// The stored vector (EXR mv.u, mv.v) of `mode`, from the truth in pixels.
vec2 stored(const std::string& mode, vec2 px, vec2 jitteredPx, int w, int h) {
  const vec2 size(w, h);
  if (mode == "y_flipped") return vec2(px.x, -px.y) / size;
  if (mode == "direction_flipped") return -px / size;
  if (mode == "half_scale") return 0.5 * px / size;
  if (mode == "pixels_not_uv") return px;
  if (mode == "jitter_included") return jitteredPx / size;
  return px / size;  // none; one_frame_late stores the previous frame's "none" vectors (caller)
}

// The history of a texel: the previous frame's colour as stored (float32), sampled bilinearly at
// `at` (continuous pixel coordinates, texel centres at i + 0.5, clamped to the edge), as TAA reads it.
vec3 bilinear(const std::vector<float>& colour, int w, int h, vec2 at) {
  if (!std::isfinite(at.x) || !std::isfinite(at.y)) return vec3(0.0);
  const vec2 s = at - vec2(0.5);
  const double x0 = std::floor(s.x), y0 = std::floor(s.y), fx = s.x - x0, fy = s.y - y0;
  auto texel = [&](double x, double y) {
    const size_t i = size_t(std::clamp(int(y), 0, h - 1)) * w + size_t(std::clamp(int(x), 0, w - 1));
    return vec3(colour[3 * i], colour[3 * i + 1], colour[3 * i + 2]);
  };
  return (texel(x0, y0) * (1 - fx) + texel(x0 + 1, y0) * fx) * (1 - fy) + (texel(x0, y0 + 1) * (1 - fx) + texel(x0 + 1, y0 + 1) * fx) * fy;
}

// The history target a mode stores at frame f (`right`: the correct one, mode none's; frame 0: zeros).
vec3 storedHistory(const std::string& mode, int f, size_t i, const Frame& now, const Frame& previous,
                   const std::vector<vec3>& right, const std::vector<vec3>& previousRight) {
  if (f == 0) return vec3(0.0);
  if (mode == "history_stale") return previousRight[i];  // the previous frame's history: X of f - 2
  if (mode == "history_not_reprojected") return {previous.colour[3 * i], previous.colour[3 * i + 1], previous.colour[3 * i + 2]};
  if (mode == "history_current") return {now.colour[3 * i], now.colour[3 * i + 1], now.colour[3 * i + 2]};
  return right[i];
}

bool writeExr(const std::string& path, int w, int h, const std::vector<std::string>& names,
              const std::vector<OIIO::TypeDesc>& formats, const std::vector<float>& interleaved) {
  OIIO::ImageSpec spec(w, h, int(names.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.channelformats = formats;
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  spec.attribute("DateTime", "2026:01:01 00:00:00");  // fixed: the same bytes on every run
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, interleaved.data()) || !out->close()) {
    std::fprintf(stderr, "motion_rig: %s: %s\n", path.c_str(), out ? out->geterror().c_str() : OIIO::geterror().c_str());
    return false;
  }
  return true;
}

std::string numbered(const std::string& dir, const char* stem, int f, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%04d.%s", stem, f, ext);
  return (std::filesystem::path(dir) / buf).string();
}

std::string number(double v) {
  if (v == 0.0) return "0.0";  // no "-0"
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

// Row-major (the matrix as written on paper, column vectors), four numbers a line.
std::string matrixText(const mat4& m) {
  std::string s = "[\n";
  for (int r = 0; r < 4; ++r) {
    s += "    ";
    for (int c = 0; c < 4; ++c) s += number(m[c][r]) + (c < 3 ? ", " : r < 3 ? "," : "");
    s += "\n";
  }
  return s + "  ]";
}

bool writeCamera(const std::string& path, const Camera& c, int f) {
  std::ostringstream s;
  s << "{\n"
    << "  \"matrix_order\": \"row_major\",\n"
    << "  \"convention\": \"d3d\",\n"
    << "  \"view_handedness\": \"left\",\n"
    << "  \"up\": \"z\",\n"
    << "  \"image_origin\": \"top\",\n"
    << "  \"size\": [" << c.width << ", " << c.height << "],\n"
    << "  \"view_from_world\": " << matrixText(c.viewFromWorld) << ",\n"
    << "  \"clip_from_view\": " << matrixText(c.clipFromView) << ",\n"
    << "  \"jitter\": [" << number(c.jitter.x) << ", " << number(c.jitter.y) << "],\n"
    << "  \"time\": " << number(f / kFramesPerSecond) << "\n"
    << "}\n";
  std::ofstream out(path, std::ios::binary);
  out << s.str();
  return bool(out.flush());
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir, mode = "none";
  int frames = -1, w = 160, h = 96;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (a + 1 >= argc) return usage(arg + ": needs a value");
    const std::string v = argv[++a];
    auto integer = [&](int& out, int lo, int hi) {
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end || n < lo || n > hi) return false;
      out = int(n);
      return true;
    };
    if (arg == "--out") dir = v;
    else if (arg == "--frames") { if (!integer(frames, 1, 10000)) return usage("--frames: expected 1..10000, got " + v); }
    else if (arg == "--width") { if (!integer(w, 8, 4096)) return usage("--width: expected 8..4096, got " + v); }
    else if (arg == "--height") { if (!integer(h, 8, 4096)) return usage("--height: expected 8..4096, got " + v); }
    else if (arg == "--bug") mode = v;
    else return usage("unknown argument " + arg);
  }
  if (dir.empty()) return usage("--out is required");
  if (frames < 0) return usage("--frames is required");
  bool known = false;
  for (const char* m : kModes) known |= mode == m;
  if (!known) return usage("--bug: unknown mode " + mode);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    std::fprintf(stderr, "motion_rig: %s: %s\n", dir.c_str(), ec.message().c_str());
    return 1;
  }

  using OIIO::TypeDesc;
  const std::vector<std::string> names = {"Z",      "N.x",  "N.y",  "N.z",     "albedo.R", "albedo.G", "albedo.B", "object",
                                          "mv.u",   "mv.v", "color.R", "color.G", "color.B", "hist.R", "hist.G", "hist.B"};
  const std::vector<TypeDesc> formats = {TypeDesc::FLOAT, TypeDesc::HALF,  TypeDesc::HALF,  TypeDesc::HALF,
                                         TypeDesc::HALF,  TypeDesc::HALF,  TypeDesc::HALF,  TypeDesc::FLOAT,
                                         TypeDesc::FLOAT, TypeDesc::FLOAT, TypeDesc::FLOAT, TypeDesc::FLOAT,
                                         TypeDesc::FLOAT, TypeDesc::HALF,  TypeDesc::HALF,  TypeDesc::HALF};
  Frame previous;
  std::vector<vec3> previousRight(size_t(w) * h, vec3(0.0));  // the correct history of the previous frame
  for (int f = 0; f < frames; ++f) {
    const Frame fr = render(f, w, h);
    const size_t n = size_t(w) * h;
    std::vector<float> px(n * names.size()), truth(n * 3);
    std::vector<vec3> right(n, vec3(0.0));
    if (f > 0)
      for (size_t i = 0; i < n; ++i) right[i] = bilinear(previous.colour, w, h, fr.historyAt[i]);
    for (size_t i = 0; i < n; ++i) {
      vec2 mv(0.0);
      if (mode == "one_frame_late") mv = f == 0 ? vec2(0.0) : previous.motion[i] / vec2(w, h);
      else mv = stored(mode, fr.motion[i], fr.jittered[i], w, h);
      float* t = &px[i * names.size()];
      t[0] = fr.depth[i];
      for (int k = 0; k < 3; ++k) t[1 + k] = fr.normal[3 * i + k], t[4 + k] = fr.albedo[3 * i + k];
      t[7] = fr.object[i];
      t[8] = float(mv.x), t[9] = float(mv.y);
      const vec3 hist = storedHistory(mode, f, i, fr, previous, right, previousRight);
      for (int k = 0; k < 3; ++k) t[10 + k] = fr.colour[3 * i + k], t[13 + k] = float(hist[k]);
      truth[3 * i] = float(fr.motion[i].x), truth[3 * i + 1] = float(fr.motion[i].y), truth[3 * i + 2] = fr.mask[i];
    }
    if (!writeExr(numbered(dir, "rig", f, "exr"), w, h, names, formats, px) ||
        !writeExr(numbered(dir, "truth_mv", f, "exr"), w, h, {"mv.x", "mv.y", "mask"},
                  {TypeDesc::FLOAT, TypeDesc::FLOAT, TypeDesc::FLOAT}, truth))
      return 1;
    if (!writeCamera(numbered(dir, "camera", f, "json"), cameraAt(f, w, h), f)) {
      std::fprintf(stderr, "motion_rig: cannot write %s\n", numbered(dir, "camera", f, "json").c_str());
      return 1;
    }
    previous = fr;
    previousRight = right;
  }
  std::printf("motion_rig %s: wrote %d frames %dx%d to %s\n", mode.c_str(), frames, w, h, dir.c_str());
  return 0;
}
