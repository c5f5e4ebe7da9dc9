// What a caller asks of one frame (read-backs, hand-offs) and what the frame cost and did: per-pass
// GPU time or the reason a pass was skipped, light counts and culling statistics (--stats, bench
// rows, capture manifests).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/core/targets.h"

namespace gb {

struct FrameRequest {
  std::vector<Target> readback;     // copied to the CPU after the frame (Renderer::readback)
  std::vector<Target> sampleAfter;  // left readable by fragment shaders (the viewer samples them)
  bool cullingStats = false;        // ideal pairs + pipeline statistics (needs options.coverage)
};

struct PassStat {
  std::string name;
  bool skipped = false;
  std::string reason;
  double ms = 0.0;  // GPU time (-1 for a pass that ran until its frame in flight is retired)
  // GPU time from the end of the pass that ran before it to its start: its barriers and what else
  // the queue did there (0 for the frame's first pass).
  double beforeMs = 0.0;
};

struct CullingStats {
  bool valid = false;
  uint64_t invocations = 0;          // sum of coverage_masked: point-light fragment shader runs
  uint64_t idealPairs = 0;           // (pixel, light) pairs whose surface point is inside the radius
  uint64_t pipelineInvocations = 0;  // pipeline-statistics count for the point-light pass
  double workOverIdeal = 0.0;        // invocations / idealPairs
};

// Clustered shading's counts (method clustered): occupied clusters, light-list entries, and the
// clusters or tiles that found no room (shaded exactly from their bin; the next frame has room).
struct ClusterStats {
  bool valid = false;
  uint32_t clusters = 0, listEntries = 0, listOverflows = 0, tilesWithoutRoom = 0;
};

struct FrameStats {
  // The lighting method that ran (never "auto") and why: "auto: clustered on a GPU (...)".
  std::string method, methodReason;
  // How the G-buffer was filled ("raster" or "visibility", never "auto", --gbuffer) and why:
  // "auto: visibility on a GPU (...)".
  std::string gbuffer, gbufferReason;
  // Where the lights were set up ("cpu" or "gpu", --light-setup) and why.
  std::string lightSetup, lightSetupReason;
  // Whether the visibility pass ran on the side queue beside the previous frame (GBLENS_OVERLAP,
  // renderer/frame/side_queue.h) and why.
  bool overlap = false;
  std::string overlapReason;
  // Method clustered: where its lights were assigned ("gpu": occupied clusters, "cpu": the cluster
  // grid, --cluster-assign) and why; empty for the other methods.
  std::string clusterAssign, clusterAssignReason;
  // CPU wall time of the frame: record + submit + wait. A frame in flight (submitFrame): from its
  // start until it was seen finished, a latency (its throughput is a burst's: FrameBurst).
  double frameMs = 0.0;
  double gpuMs = 0.0;    // first to last GPU timestamp (-1 until a frame in flight is retired)
  // The GPU clock (ms) when the frame's last pass ended (-1: no timestamps). Comparable between the
  // frames of one burst: each ends on the same queue (the compute one where the frames overlap).
  double gpuEndMs = -1.0;
  // CPU time of the frame before submission: per-frame work (camera, draws, light classification,
  // frame data), building the frame graph and recording it.
  double cpuMs = 0.0;
  double recordMs = 0.0;  // of which recording the graph (render passes, barriers, commands)
  // Render-pass groups compiled this frame (0 when every group kept last frame's shape) and reused.
  uint32_t groupsCompiled = 0, groupsReused = 0;
  std::vector<PassStat> passes;
  CullingStats culling;
  ClusterStats clusters;
  uint32_t lights = 0, lightsVisible = 0, lightsInside = 0, lightsCulled = 0;
  uint32_t stencilLayers = 0;  // screen-disjoint layers of the stencil class (FrameLights::layerStarts)
  uint32_t lightsCulledFrustum = 0, lightsCulledEmpty = 0, lightsCulledSubpixel = 0;  // lightsCulled split
  int64_t skyPixels = -1;  // sky pixels the skybox drew (occlusion query; -1: skybox not drawn)
};

// A burst of frames in flight (renderBurst, renderer.h): the first is submitted and waited for
// (not counted), the others back to back; msPerFrame is the wall time from the start of the second
// to the end of the last, per counted frame: the throughput, with the pipeline's fill (one frame's
// CPU or GPU time, the smaller) spread over the counted frames.
struct FrameBurst {
  FrameStats first;                // the first frame (waited for, not counted)
  std::vector<FrameStats> frames;  // the counted frames, oldest first
  double msPerFrame = 0.0;
  int inFlight = 0;  // frames submitted at once at most (the renderer's frame slots)
  // Each counted frame's wall time: from one frame's submission call returning to the next one's
  // (the last: to the burst's end). In flight, a frame waits there for its slot, so a frame that
  // stalls (an attached layer's connect) shows as one long interval where the mean would hide it.
  std::vector<double> intervalMs;
  // The steady state without the fill: the GPU clock between the first and the last counted
  // frame's end / (counted frames - 1) (-1: no timestamps or fewer than 2 counted frames). Where a
  // frame's latency exceeds the interval between frames (the frames overlap: one frame's visibility
  // pass runs before its compute part, beside the frame before), msPerFrame carries the excess
  // over burst - 1 frames; this does not.
  double steadyMs = -1.0;
};

}  // namespace gb
