// The camera of an import (see import.h): where its matrices come from (the layout, a sidecar
// beside the imported files, a RenderDoc uniform buffer) and their conversion to gblens's convention,
// perspective or orthographic.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "renderer/core/json_read.h"
#include "renderer/core/layout_json.h"
#include "renderer/core/camera.h"
#include "views/import/import_internal.h"

namespace gb {

namespace fs = std::filesystem;

glm::dmat4 matrixFromFloats(const std::vector<uint8_t>& bytes, uint64_t offset, bool rowMajor) {
  glm::dmat4 m(1.0);
  for (int i = 0; i < 16; ++i) {
    float v;
    std::memcpy(&v, bytes.data() + offset + size_t(i) * 4, 4);
    if (rowMajor)
      m[i % 4][i / 4] = v;
    else
      m[i / 4][i % 4] = v;
  }
  return m;
}

namespace {


// The camera's size, when it gives one, against the images' (the projection's aspect is for it).
bool checkCameraSize(const LayoutCamera& c, const std::string& from, uint32_t w, uint32_t h, std::string& error) {
  if (!c.width || (c.width == w && c.height == h)) return true;
  error = from + ": camera: size: the matrices are for " + std::to_string(c.width) + "x" + std::to_string(c.height) +
          ", the images are " + std::to_string(w) + "x" + std::to_string(h);
  return false;
}

// Where a relative sidecar may be: beside the imported images (or the RenderDoc capture), nowhere
// else (not beside the layout, not the current folder: a stale camera.json there would be taken).
std::vector<std::string> sidecarCandidates(const ImportInput& in, const std::string& sidecar) {
  std::vector<std::string> places;
  std::vector<std::string> inputs = in.files;
  if (!in.capture.empty()) inputs.push_back(in.capture);
  for (const LayoutTarget& t : in.layout.targets)
    if (t.source.kind == TargetSource::Kind::File || t.source.kind == TargetSource::Kind::Raw)
      if (std::string path = sourcePath(in, t); !path.empty()) inputs.push_back(path);
  for (const std::string& input : inputs) {
    const std::string place = (fs::path(input).parent_path() / sidecar).lexically_normal().string();
    if (std::find(places.begin(), places.end(), place) == places.end()) places.push_back(place);
  }
  return places;
}

bool findSidecar(const ImportInput& in, const std::string& where, std::string& sidecar, std::string& error) {
  if (fs::path(sidecar).is_absolute()) return sourceAllowed(in, sidecar, where, "sidecar", error);
  const std::vector<std::string> places = sidecarCandidates(in, sidecar);
  std::error_code ec;
  for (const std::string& place : places)
    if (fs::is_regular_file(place, ec)) {
      sidecar = place;
      return sourceAllowed(in, sidecar, where, "sidecar", error);
    }
  std::string looked;
  for (const std::string& place : places) looked += (looked.empty() ? "" : ", ") + place;
  error = where + ": sidecar \"" + sidecar + "\": not found beside the imported files (" +
          (looked.empty() ? std::string("no file to look beside") : "looked for " + looked) +
          "); give it with --camera FILE";
  return false;
}

}  // namespace

bool resolveCamera(const ImportInput& in, LayoutCamera& c, uint32_t w, uint32_t h, std::string& error) {
  const std::string file = in.layout.file.empty() ? std::string("layout") : in.layout.file;
  const std::string where = file + ": camera";
  // camera.live names a running application's binding: only attach (which hands its bytes over as a
  // capture buffer's) has them; every other import refuses it rather than use no matrices.
  if (c.live && in.liveTexels.empty()) {
    error = importCameraRefusal(in.layout);
    return false;
  }
  std::string sidecar = !in.cameraFile.empty() ? in.cameraFile : c.sidecar;
  if (!sidecar.empty()) {
    if (in.cameraFile.empty() && !findSidecar(in, where, sidecar, error)) return false;
    // The layout's conventions, the sidecar's matrices (and whatever conventions it gives).
    nlohmann::json j = layoutCameraJson(c), side;
    for (const char* key : {"sidecar", "renderdoc", "view_from_world", "clip_from_view", "world_handedness", "projection"})
      j.erase(key);
    std::string why;
    if (!readJsonFile(sidecar, side, why)) {
      error = where + ": sidecar: " + why;
      return false;
    }
    if (!side.is_object()) {
      error = where + ": sidecar: " + sidecar + ": expected a JSON object";
      return false;
    }
    // A sidecar holds the matrices: one naming another sidecar or a buffer would leave none.
    for (const char* key : {"sidecar", "renderdoc"})
      if (side.contains(key)) {
        error = sidecar + ": camera: " + key + ": a sidecar gives the matrices itself (view_from_world or world_from_view, "
                "and clip_from_view)";
        return false;
      }
    for (auto& [k, v] : side.items()) j[k] = v;
    if (!parseLayoutCamera(j, sidecar, c, error) || !checkCameraSize(c, sidecar, w, h, error)) return false;
    c.from = (in.cameraFile.empty() ? "sidecar " : "--camera ") + fs::absolute(sidecar).lexically_normal().string();
    return true;
  }
  if (c.renderdoc) {
    const LayoutCamera::BufferMatrix& b = *c.renderdoc;
    const std::vector<uint8_t>& bytes = in.renderdocCameraBuffer;
    if (bytes.empty()) {
      error = where + ": renderdoc: the matrices are in buffer \"" + b.buffer +
              "\" of a RenderDoc capture; import the .rdc, or give the camera with --camera";
      return false;
    }
    if (bytes.size() < std::max(b.viewOffset, b.clipOffset) + 64) {
      error = where + ": renderdoc: buffer \"" + b.buffer + "\" holds " + std::to_string(bytes.size()) +
              " bytes, the matrices need " + std::to_string(std::max(b.viewOffset, b.clipOffset) + 64);
      return false;
    }
    glm::dmat4 view = matrixFromFloats(bytes, b.viewOffset, b.rowMajor);
    c.clipFromView = matrixFromFloats(bytes, b.clipOffset, b.rowMajor);
    if (b.combined) {
      const glm::dmat4 clipFromWorld = c.clipFromView;
      if (!splitClipFromWorld(clipFromWorld, c.convention != LayoutCamera::Convention::Vulkan, c.viewFromWorld,
                              c.clipFromView)) {
        error = where + ": renderdoc: clip_from_world read from \"" + b.buffer + "\" at byte " +
                std::to_string(b.clipOffset) + " is no perspective projection";
        return false;
      }
      c.leftHanded = false;
      c.from = "buffer \"" + b.buffer + "\"" + in.renderdocCameraBufferAt + ": clip_from_world at byte " +
               std::to_string(b.clipOffset) + (b.rowMajor ? ", row-major" : ", column-major") + ", split into view and projection";
      return checkCameraSize(c, file, w, h, error);
    }
    for (auto [m, name] : {std::pair{&view, "view matrix"}, {&c.clipFromView, "clip_from_view"}})
      if (!(std::abs(glm::determinant(*m)) > 1e-30)) {
        error = where + ": renderdoc: " + name + " read from \"" + b.buffer + "\" is singular";
        return false;
      }
    c.viewFromWorld = b.worldFromView ? glm::inverse(view) : view;
    c.from = "buffer \"" + b.buffer + "\"" + in.renderdocCameraBufferAt + ": " +
             (b.worldFromView ? "world_from_view" : "view_from_world") + " at byte " + std::to_string(b.viewOffset) +
             ", clip_from_view at byte " + std::to_string(b.clipOffset) + (b.rowMajor ? ", row-major" : ", column-major");
  } else {
    c.from = "the layout's matrices (" + file + ")";
  }
  return checkCameraSize(c, file, w, h, error);
}

namespace {

// The projection's near and far eye depths and whether depth runs reversed (1 at the near plane).
void depthRange(Camera& out) {
  const glm::dmat4& p = out.clipFromEye;
  if (orthographic(out)) {  // depth = p22 z + p32 (w = 1): linear in the eye depth -z
    out.reversedZ = p[2][2] > 0.0;
    auto depthAt = [&](double target) { return (p[3][2] - target) / p[2][2]; };
    out.znear = depthAt(out.reversedZ ? 1.0 : 0.0);
    out.zfar = depthAt(out.reversedZ ? 0.0 : 1.0);
    return;
  }
  // Where the far plane lands: 0 for reversed Z (a perspective's depth at infinity is -p22 / p23 ...).
  const double farDepth = hardwareDepth(out, {0.0, 0.0, -1e12});
  out.reversedZ = farDepth < 0.5;
  auto depthAt = [&](double target) {  // eye depth where the hardware depth is `target` (bisection)
    double lo = 1e-9, hi = 1e12;
    for (int i = 0; i < 200; ++i) {
      double mid = std::sqrt(lo * hi);
      (hardwareDepth(out, {0.0, 0.0, -mid}) < target) != out.reversedZ ? lo = mid : hi = mid;
    }
    return lo;
  };
  out.znear = depthAt(out.reversedZ ? 1.0 : 0.0);
  out.zfar = depthAt(out.reversedZ ? 0.0 : 1.0);
}

}  // namespace

bool importCamera(const LayoutCamera& given, uint32_t width, uint32_t height, Camera& out, std::string& error) {
  LayoutCamera c = given;
  if (!settleWorldHandedness(c, error)) return false;
  // gblens eye space = S * source view space (S flips Z for a left-handed view); gblens world =
  // R * source world (R turns the up axis to Y, and mirrors a left-handed world). Clip space:
  // Vulkan's, y down, depth 0..1.
  glm::dmat4 S(1.0), R(1.0), C(1.0);
  if (c.leftHanded) S[2][2] = -1.0;
  R = glm::dmat4(worldFromLayoutWorld(c));
  if (c.convention != LayoutCamera::Convention::Vulkan) C[1][1] = -1.0;  // NDC y up -> down (rows are top first)
  if (c.convention == LayoutCamera::Convention::Gl) {  // z' = (z + w) / 2
    C[2][2] = 0.5;
    C[3][2] = 0.5;
  }
  out = Camera{};
  out.width = width;
  out.height = height;
  out.eyeFromWorld = S * c.viewFromWorld * glm::inverse(R);
  out.worldFromEye = glm::inverse(out.eyeFromWorld);
  out.clipFromEye = C * c.clipFromView * glm::inverse(S);
  const double det = glm::determinant(out.clipFromEye);
  if (!std::isfinite(det) || std::abs(det) < 1e-300) {
    error = "camera: clip_from_view: singular after conversion";
    return false;
  }
  // One scale for clip space (w = -z, or w = 1): the same image, and the formulas of camera.h hold.
  glm::dmat4& p = out.clipFromEye;
  if (p[3][3] == 0.0 && p[2][3] < 0.0 && p[2][3] != -1.0) p /= -p[2][3];
  if (p[2][3] == 0.0 && p[3][3] != 0.0 && p[3][3] != 1.0) p /= p[3][3];
  const Projection kind = projectionOf(p);
  if (kind == Projection::Other) {
    error = p[2][3] > 0.0 && p[3][3] == 0.0
                ? std::string("camera: clip_from_view: a perspective looking down ") + (c.leftHanded ? "-Z" : "+Z") +
                      " of the view: view_handedness is \"" + (c.leftHanded ? "right" : "left") + "\", not \"" +
                      (c.leftHanded ? "left" : "right") + "\""
                : "camera: clip_from_view: neither a perspective nor an orthographic projection (clip w mixes x, y "
                  "or z with a constant, or x and y are mixed); gblens cannot reconstruct positions through it";
    return false;
  }
  if (c.statedOrthographic && *c.statedOrthographic != (kind == Projection::Orthographic)) {
    error = std::string("camera: projection: \"") + (*c.statedOrthographic ? "orthographic" : "perspective") +
            "\", but clip_from_view is " + name(kind);
    return false;
  }
  out.eyeFromClip = glm::inverse(out.clipFromEye);
  out.clipFromWorld = out.clipFromEye * out.eyeFromWorld;
  for (const glm::dmat4* m : {&out.eyeFromWorld, &out.worldFromEye, &out.clipFromEye, &out.eyeFromClip, &out.clipFromWorld})
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite((*m)[i / 4][i % 4])) {
        error = "camera: the matrices are not finite after conversion (values too large or nearly singular)";
        return false;
      }
  out.yfov = kind == Projection::Orthographic ? 0.0 : 2.0 * std::atan(1.0 / std::abs(p[1][1]));
  out.aspect = std::abs(p[1][1] / p[0][0]);
  depthRange(out);
  return true;
}

}  // namespace gb
