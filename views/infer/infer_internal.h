// The drafting's working state (infer.h), shared by its stages: depth targets and the surfaces,
// positions, the camera, linear depths, normals, colours, the rest. Each stage claims the channels
// it decides; what is left is drafted as stored values.
#pragma once
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "views/infer/guess.h"
#include "views/infer/infer.h"
#include "renderer/core/pinhole.h"

namespace gb::infer {

// A camera the frame's geometry can be rebuilt through.
struct FoundCam {
  bool present = false;
  LayoutCamera layout;   // as the draft states it (conventions, matrices)
  Camera camera;         // in gblens's convention (import's conversion)
  nlohmann::json block;  // the draft's "camera" block
  bool checked = false;  // the stored positions confirmed it
  std::string from;      // for people
};

// Where the surfaces' distances are: the hardware depth (through the camera) or a linear depth channel.
struct DepthSource {
  size_t target = 0;
  uint32_t channel = 0;
  DepthEncoding encoding = DepthEncoding::Hardware;
  double scale = 1.0;
  std::optional<double> background;
};

struct Positions {
  int target = -1;
  std::vector<uint32_t> channels;
  Space space = Space::World;
  PinholeFit fit;
};

// Reference normals in one of the layout's spaces (view: the layout's view convention; world: its
// world axes), with where they came from.
struct SpaceRef {
  Space space = Space::View;
  ReferenceNormals normals;
};

struct State {
  const InferInput& in;
  uint32_t width = 0, height = 0;
  SurfaceMask surface;
  std::vector<std::vector<bool>> claimed;  // per target, per channel
  std::vector<nlohmann::json> quantities;  // per target: a JSON list
  std::set<std::string> names;
  std::vector<std::string> summary;
  std::optional<DepthSource> hardware;     // the G-buffer's hardware depth
  std::optional<DepthSource> linear;       // a linear depth channel, once decided
  Positions positions;
  FoundCam cam;
  std::vector<glm::uvec2> pixels;          // where evidence is measured (surface pixels)
  // What the evidence could test (a name is taken only for what it could not): normals (a reference
  // surface existed), the targets whose xyz was fitted as positions, whose colour was tested.
  bool normalsTested = false, distancesKnown = false;
  std::set<size_t> positionTested, colourTested;

  explicit State(const InferInput& i) : in(i) {}
  const CpuImage* image(size_t t) const { return in.targets[t].texels; }
  bool isFree(size_t t, const std::vector<uint32_t>& channels) const;
  // Drafts a quantity (name unique, from `name` or the kind) and claims its channels.
  void add(size_t t, QuantityKind kind, const std::vector<uint32_t>& channels, nlohmann::json fields, const Guess& g,
           const std::string& name = "");
};

// The stages, in order (each file's purpose comment says how it decides).
void decideDepthTargets(State& s);   // infer_geometry.cpp
void decideSurface(State& s);
void decidePositions(State& s);
void decideCamera(State& s);         // infer_camera.cpp
void decideNormalsAndDepths(State& s);  // infer_normals.cpp (linear depths: infer_depth.cpp)
void decideColours(State& s);        // infer_colour.cpp

// Eye-space points (gblens's eye: -Z forward) of the surfaces through `camera` from a depth source.
PointField eyePoints(const State& s, const DepthSource& d, const Camera& camera);
// Vectors between gblens's eye space and the layout's spaces under a camera.
glm::dvec3 layoutFromEye(const LayoutCamera& lc, const Camera& c, Space space, const glm::dvec3& v);
// The reference normals a camera and a depth give, in the layout's view and world spaces.
std::vector<SpaceRef> referencesFromDepth(const State& s, const DepthSource& d, const LayoutCamera& lc, const Camera& c,
                                          const std::string& from);
// Linear depths (infer_depth.cpp): each float channel left compared with the eye distances the
// camera and hardware depth (or the stored positions) give.
void decideLinearDepths(State& s);
// A linear depth candidate's channels: single float (or 16-bit unorm) channels nothing claimed.
std::vector<std::pair<size_t, uint32_t>> linearDepthCandidates(const State& s);
// Without a distance to compare with: a camera from the buffers and a linear depth channel decided
// together by the normals of the surface they rebuild (infer_depth.cpp).
void decideJointly(State& s);
// The best median angle (degrees) any normal candidate makes with `refs` (infer_normals.cpp).
double bestNormalMedian(const State& s, const std::vector<SpaceRef>& refs);
// A stored value as a number.
double stored(const State& s, size_t target, uint32_t channel, uint32_t x, uint32_t y);

}  // namespace gb::infer
