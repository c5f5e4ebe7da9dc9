// The import tests' hand-made G-buffers (see import_fixtures.h): geometry by ray casting in double,
// files written with OpenImageIO and plain streams, layouts as JSON.
#include "tests/cli/import_fixtures.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace gb::fixtures {

using json = nlohmann::json;

namespace {

// The nearest hit of the ray o + t d (t > 0) with the sphere (centre (0, 0.5, 0), radius 0.5) and the
// floor square y = 0, |x|, |z| <= 6.
Truth cast(const glm::dvec3& o, const glm::dvec3& d) {
  Truth h;
  double best = std::numeric_limits<double>::infinity();
  const glm::dvec3 c(0.0, 0.5, 0.0), oc = o - c;
  const double a = glm::dot(d, d), b = glm::dot(oc, d), disc = b * b - a * (glm::dot(oc, oc) - 0.25);
  if (disc >= 0.0) {
    const double t = (-b - std::sqrt(disc)) / a;
    if (t > 0.0) best = t, h.normalWorld = (o + t * d - c) / 0.5;
  }
  if (d.y < 0.0) {
    const double t = -o.y / d.y;
    const glm::dvec3 p = o + t * d;
    if (t < best && std::abs(p.x) <= 6.0 && std::abs(p.z) <= 6.0) best = t, h.normalWorld = glm::dvec3(0, 1, 0);
  }
  if (std::isinf(best)) return h;
  h.hit = true;
  h.world = o + best * d;
  return h;
}

json columnMajor(const glm::dmat4& m) {
  json a = json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(m[c][r]);
  return a;
}

json rowMajor(const glm::dmat4& m) {
  json a = json::array();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) a.push_back(m[c][r]);
  return a;
}

// One image file (or one part of a multi-part EXR): float values, `n` channels, stored as `type`.
struct Part {
  std::string name;  // EXR part name ("" : single part)
  std::vector<std::string> channels;
  OIIO::TypeDesc type = OIIO::TypeDesc::FLOAT;
  std::vector<float> values;  // kW * kH * channels, rows as they go into the file
};

void writeImage(const std::string& path, const std::vector<Part>& parts) {
  std::vector<OIIO::ImageSpec> specs;
  for (const Part& p : parts) {
    OIIO::ImageSpec spec(int(kW), int(kH), int(p.channels.size()), p.type);
    spec.channelnames = p.channels;
    spec.alpha_channel = -1;
    if (!p.name.empty()) spec.attribute("oiio:subimagename", p.name);
    specs.push_back(spec);
  }
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": " + OIIO::geterror());
  bool ok = parts.size() == 1 ? out->open(path, specs[0]) : out->open(path, int(specs.size()), specs.data());
  for (size_t i = 0; ok && i < parts.size(); ++i) {
    if (i > 0) ok = out->open(path, specs[i], OIIO::ImageOutput::AppendSubimage);
    ok = ok && out->write_image(OIIO::TypeDesc::FLOAT, parts[i].values.data());
  }
  if (!ok || !out->close()) throw std::runtime_error(path + ": " + out->geterror());
}

template <class T>
void writeRaw(const std::string& path, const std::vector<T>& values) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(T)));
  if (!f) throw std::runtime_error(path + ": cannot write");
}

// The file row holding picture row y.
uint32_t fileRow(uint32_t y, bool bottomFirst) { return bottomFirst ? kH - 1 - y : y; }

}  // namespace

glm::dvec3 zUp(const glm::dvec3& v) { return {v.x, -v.z, v.y}; }

glm::dvec2 octahedral(glm::dvec3 n) {
  n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (n.z >= 0.0) return {n.x, n.y};
  return {(1.0 - std::abs(n.y)) * (n.x >= 0.0 ? 1.0 : -1.0), (1.0 - std::abs(n.x)) * (n.y >= 0.0 ? 1.0 : -1.0)};
}

double glWindowDepth(const Scene& s, const glm::dvec3& eye) {
  const glm::dvec4 c = s.glProjection * glm::dvec4(eye, 1.0);
  return 0.5 * c.z / c.w + 0.5;
}

double eyeDepthFromGlWindowDepth(const Scene& s, double d) {
  // clip.z = P22 z + P32, clip.w = -z: ndc = -(P22 z + P32) / z, so -z = P32 / (ndc + P22).
  const glm::dmat4& p = s.glProjection;
  return p[3][2] / ((2.0 * d - 1.0) + p[2][2]);
}

double d3dReversedDepth(const Scene& s, const glm::dvec3& eye) {
  const glm::dvec4 c = s.d3dReversed * glm::dvec4(eye.x, eye.y, -eye.z, 1.0);  // left-handed view: z forward
  return c.z / c.w;
}

double eyeDepthFromD3dReversedDepth(const Scene& s, double d) {
  // clip.z = P22 z + P32, clip.w = z: d = P22 + P32 / z.
  const glm::dmat4& p = s.d3dReversed;
  return p[3][2] / (d - p[2][2]);
}

Scene makeScene() {
  Scene s;
  s.view = glm::lookAtRH(glm::dvec3(0.6, 1.7, 3.2), glm::dvec3(0.0, 0.4, 0.0), glm::dvec3(0.0, 1.0, 0.0));
  s.glProjection = glm::perspectiveRH_NO(s.fovy, s.aspect, s.znear, s.zfar);
  s.d3dReversed = glm::perspectiveLH_ZO(s.fovy, s.aspect, s.zfar, s.znear);  // near and far swapped: reversed
  const glm::dmat4 yUpFromZUp(glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 0, -1, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 0, 1));
  s.viewLeftZUp = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 1.0, -1.0)) * s.view * yUpFromZUp;
  const glm::dmat4 worldFromView = glm::inverse(s.view);
  const glm::dvec3 origin(worldFromView[3]);
  const double t = std::tan(s.fovy / 2.0);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const double nx = (x + 0.5) / kW * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / kH * 2.0;
      Truth h = cast(origin, glm::dmat3(worldFromView) * glm::dvec3(nx * t * s.aspect, ny * t, -1.0));
      if (h.hit) {
        h.eye = glm::dvec3(s.view * glm::dvec4(h.world, 1.0));
        h.normalEye = glm::dmat3(s.view) * h.normalWorld;
      }
      s.pixels.push_back(h);
    }
  return s;
}

void writeJson(const std::string& path, const json& j) {
  std::ofstream f(path);
  f << j.dump(2) << "\n";
  if (!f) throw std::runtime_error(path + ": cannot write");
}

json writeFixtureA(const std::string& dir, const Scene& s) {
  const size_t n = size_t(kW) * kH;
  Part normals{"", {"N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "Z"}, OIIO::TypeDesc::FLOAT, std::vector<float>(n * 7, 0.0f)};
  Part hardware{"hardware", {"Z"}, OIIO::TypeDesc::FLOAT, std::vector<float>(n, 1.0f)};
  Part radial{"radial", {"Z"}, OIIO::TypeDesc::FLOAT, std::vector<float>(n, 0.0f)};
  Part png{"", {"R", "G", "B"}, OIIO::TypeDesc::UINT8, std::vector<float>(n * 3, 0.0f)};
  std::vector<int16_t> oct(n * 2, 0);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Truth& h = s.at(x, y);
      if (!h.hit) continue;
      const size_t i = size_t(fileRow(y, true)) * kW + x;  // GL read-back: bottom row first
      for (int k = 0; k < 3; ++k) {
        normals.values[i * 7 + size_t(k)] = float(h.normalWorld[k]);
        normals.values[i * 7 + 3 + size_t(k)] = float(h.world[k]);
        // 8-bit unorm: the file holds round(v * 255); OIIO writes float data / 255 back exactly.
        png.values[i * 3 + size_t(k)] = float(std::round((h.normalEye[k] * 0.5 + 0.5) * 255.0) / 255.0);
      }
      normals.values[i * 7 + 6] = float(-h.eye.z);
      hardware.values[i] = float(glWindowDepth(s, h.eye));
      radial.values[i] = float(glm::length(h.eye));
      const glm::dvec2 o = octahedral(h.normalEye);
      for (int k = 0; k < 2; ++k) oct[i * 2 + size_t(k)] = int16_t(std::lround(std::clamp(o[k], -1.0, 1.0) * 32767.0));
    }
  writeImage(dir + "/gbuffer.exr", {normals});
  writeImage(dir + "/depth.exr", {hardware, radial});
  writeImage(dir + "/normal_view.png", {png});
  writeRaw(dir + "/normal_oct.bin", oct);

  auto target = [](const char* name, const char* format, json source, json quantity) {
    return json{{"name", name}, {"format", format}, {"source", source}, {"quantities", json::array({quantity})}};
  };
  json layout = {
      {"format", "gblens-layout"}, {"version", 1}, {"name", "fixture A: OpenGL conventions"}, {"size", {kW, kH}},
      {"targets",
       {target("eye_depth", "r32f", {{"file", "gbuffer.exr"}, {"channels", {"Z"}}},
               {{"quantity", "depth"}, {"name", "Zeye"}, {"channels", {0}}, {"encoding", "eye"}, {"background", 0}}),
        target("normal_world", "rgb32f", {{"file", "gbuffer.exr"}, {"channels", {"N.X", "N.Y", "N.Z"}}},
               {{"quantity", "normal"}, {"name", "Nworld"}, {"channels", {0, 1, 2}}, {"encoding", "xyz"}, {"space", "world"}}),
        target("position", "rgb32f", {{"file", "gbuffer.exr"}, {"channels", {"P.X", "P.Y", "P.Z"}}},
               {{"quantity", "position"}, {"name", "P"}, {"channels", {0, 1, 2}}, {"space", "world"}}),
        target("normal_png", "rgb8_unorm", {{"file", "normal_view.png"}},
               {{"quantity", "normal"}, {"name", "Nunorm"}, {"channels", {0, 1, 2}}, {"encoding", "xyz_unorm"}}),
        target("normal_oct", "rg16_snorm", {{"file", "normal_oct.bin"}, {"raw", true}},
               {{"quantity", "normal"}, {"name", "Noct"}, {"channels", {0, 1}}, {"encoding", "octahedral"}}),
        target("hardware_depth", "r32f", {{"file", "depth.exr"}, {"part", "hardware"}, {"channels", {"Z"}}},
               {{"quantity", "depth"}, {"name", "Zhw"}, {"channels", {0}}, {"encoding", "hardware"}}),
        target("radial_depth", "r32f", {{"file", "depth.exr"}, {"part", "radial"}, {"channels", {"Z"}}},
               {{"quantity", "depth"}, {"name", "Zradial"}, {"channels", {0}}, {"encoding", "radial"}, {"background", 0}})}},
      {"camera",
       {{"view_from_world", columnMajor(s.view)}, {"clip_from_view", columnMajor(s.glProjection)},
        {"matrix_order", "column_major"}, {"convention", "gl"}, {"image_origin", "bottom"}}}};
  writeJson(dir + "/a.json", layout);
  return layout;
}

json writeFixtureB(const std::string& dir, const Scene& s) {
  const size_t n = size_t(kW) * kH;
  std::vector<float> depth(n, 0.0f);
  Part normals{"", {"R", "G", "B"}, OIIO::TypeDesc::HALF, std::vector<float>(n * 3, 0.0f)};
  Part positions{"", {"R", "G", "B"}, OIIO::TypeDesc::FLOAT, std::vector<float>(n * 3, 0.0f)};
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const Truth& h = s.at(x, y);
      if (!h.hit) continue;
      const size_t i = size_t(y) * kW + x;
      depth[i] = float(d3dReversedDepth(s, h.eye));
      const glm::dvec3 nz = zUp(h.normalWorld), pz = zUp(h.world);
      for (int k = 0; k < 3; ++k) {
        normals.values[i * 3 + size_t(k)] = float(nz[k]);
        positions.values[i * 3 + size_t(k)] = float(pz[k]);
      }
    }
  writeRaw(dir + "/depth_reversed.bin", depth);
  writeImage(dir + "/normal_half.exr", {normals});
  writeImage(dir + "/position.tif", {positions});
  writeJson(dir + "/camera_b.json", {{"view_from_world", rowMajor(s.viewLeftZUp)}, {"clip_from_view", rowMajor(s.d3dReversed)},
                                     {"matrix_order", "row_major"}, {"convention", "d3d"}, {"view_handedness", "left"},
                                     {"up", "z"}});
  json layout = {
      {"format", "gblens-layout"}, {"version", 1}, {"name", "fixture B: D3D, left-handed view, Z up, reversed depth"},
      {"targets",
       {{{"name", "depth"}, {"format", "d32f"}, {"size", {kW, kH}}, {"source", {{"file", "depth_reversed.bin"}, {"raw", true}}},
         {"quantities", {{{"quantity", "depth"}, {"name", "Zrev"}, {"channels", {0}}, {"encoding", "hardware"}}}}},
        {{"name", "normal"}, {"format", "rgb16f"}, {"source", {{"file", "normal_half.exr"}, {"channels", {"R", "G", "B"}}}},
         {"quantities", {{{"quantity", "normal"}, {"name", "N"}, {"channels", {0, 1, 2}}, {"space", "world"}}}}},
        {{"name", "position"}, {"format", "rgb32f"}, {"source", {{"file", "position.tif"}}},
         {"quantities", {{{"quantity", "position"}, {"name", "P"}, {"channels", {0, 1, 2}}, {"space", "world"}}}}}}},
      {"camera", {{"sidecar", "camera_b.json"}}}};
  writeJson(dir + "/b.json", layout);
  return layout;
}

json writeFixtureC(const std::string& dir, bool plant) {
  constexpr uint32_t w = 16, h = 8;
  std::vector<float> gbuf(w * h * 4), normal(w * h * 3), depth(w * h, 2.0f);
  for (uint32_t i = 0; i < w * h; ++i) {
    gbuf[i * 4 + 0] = 0.5f, gbuf[i * 4 + 1] = 0.4f, gbuf[i * 4 + 2] = 0.3f, gbuf[i * 4 + 3] = 0.3f;
    normal[i * 3 + 0] = 0.0f, normal[i * 3 + 1] = 0.6f, normal[i * 3 + 2] = 0.8f;
  }
  auto at = [&](uint32_t x, uint32_t y) { return size_t(y) * w + x; };
  if (plant) {
    gbuf[at(3, 1) * 4 + 1] = std::numeric_limits<float>::quiet_NaN();      // albedo G: NaN
    normal[at(5, 2) * 3 + 1] = std::numeric_limits<float>::infinity();     // normal Y: +Inf
    depth[at(7, 3)] = -std::numeric_limits<float>::infinity();             // depth: -Inf
    gbuf[at(9, 4) * 4 + 3] = 1e-40f;                                       // roughness: a float denormal
    gbuf[at(2, 5) * 4 + 0] = 1.5f;                                         // albedo R: above 1
    normal[at(11, 6) * 3 + 1] = 0.3f, normal[at(11, 6) * 3 + 2] = 0.4f;    // normal of length 0.5
    depth[at(13, 7)] = -1.0f;                                              // negative eye depth
  }
  auto write = [&](const std::string& file, std::vector<std::string> channels, OIIO::TypeDesc type, const std::vector<float>& v) {
    OIIO::ImageSpec spec(int(w), int(h), int(channels.size()), type);
    spec.channelnames = channels;
    auto out = OIIO::ImageOutput::create(dir + "/" + file);
    if (!out || !out->open(dir + "/" + file, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, v.data()) || !out->close())
      throw std::runtime_error(file + ": cannot write");
  };
  write("gbuf.exr", {"R", "G", "B", "A"}, OIIO::TypeDesc::FLOAT, gbuf);
  write("normal.exr", {"R", "G", "B"}, OIIO::TypeDesc::HALF, normal);
  write("depth.exr", {"Z"}, OIIO::TypeDesc::FLOAT, depth);
  json layout = {
      {"format", "gblens-layout"}, {"version", 1}, {"name", "fixture C: for gblens check"},
      {"targets",
       {{{"name", "gbuf"}, {"format", "rgba32f"}, {"source", {{"file", "gbuf.exr"}, {"channels", {"R", "G", "B", "A"}}}},
         {"quantities", {{{"quantity", "albedo"}, {"name", "Albedo"}, {"channels", {0, 1, 2}}},
                         {{"quantity", "roughness"}, {"name", "Roughness"}, {"channels", {3}}}}}},
        {{"name", "normal"}, {"format", "rgb16f"}, {"source", {{"file", "normal.exr"}, {"channels", {"R", "G", "B"}}}},
         {"quantities", {{{"quantity", "normal"}, {"name", "N"}, {"channels", {0, 1, 2}}}}}},
        {{"name", "depth"}, {"format", "r32f"}, {"source", {{"file", "depth.exr"}, {"channels", {"Z"}}}},
         {"quantities", {{{"quantity", "depth"}, {"name", "Z"}, {"channels", {0}}, {"encoding", "eye"}, {"background", 0}}}}}}}};
  writeJson(dir + "/c.json", layout);
  return layout;
}

}  // namespace gb::fixtures
