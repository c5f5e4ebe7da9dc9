// Attaching to a running Vulkan application (`gblens attach`, docs/attach.md): start it with the
// gblens layer (app/layer), tell the layer what a layout names, and receive its frames one at a
// time, each decoded exactly as `gblens import` builds a FrameSnapshot (import.h: a live source is
// one more source kind). No Vulkan here: the layer and this side share only live_wire.h.
#pragma once
#include <sys/types.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "renderer/core/layout.h"
#include "renderer/core/options.h"
#include "renderer/core/snapshot.h"
#include "views/import/import.h"
#include "views/import/renderdoc_replay.h"
#include "views/live/frame_history.h"

namespace gb {

struct LiveOptions {
  std::string layout;                    // a layout file or builtin:NAME ("" : none, with suggest)
  nlohmann::json layoutJson;             // or the layout itself (a draft; null: `layout`)
  RenderOptions options;                 // what a parameterised layout is resolved with (import's --param)
  std::vector<std::string> given;        // the options of those the user gave (the rest are defaults)
  std::vector<std::string> argv;         // the application and its arguments
  uint32_t every = 1;                    // stream the application's frames 0, N, 2N, ...
  int64_t captureFrame = -1;             // stream only the application's frame of this number (0: its first; -1: all)
  // With captureFrame: the frames captureFrame..captureLast, every one (the layer's submissions wait
  // for each frame to be read instead of skipping one); -1: captureFrame alone.
  int64_t captureLast = -1;
  // Keep the last `history` frames decoded (LiveSession::history; 0: none): at most that many frames'
  // bytes besides the one returned.
  size_t history = 0;
  bool suggest = false;                  // the layer reports one frame's render passes and attachments
  // A stream (the viewer, --frames, the bench): the layer's thread makes the ring when the first
  // frames need it, and those frames go without copies, so the application never waits for it.
  // Off: the first frame due is copied, the ring made in the application's thread (a capture, a draft).
  bool ringOffThread = false;
  // Paced (the viewer): the layer copies one frame, then the next only after ready(), so that the
  // application pays for no frame the receiver would not use (a frame that does not decode asks for
  // the next itself). Off: every frame the receiver can take (--frames, the bench, --history).
  bool paced = false;
  uint32_t giveUpFrames = 120;           // frames with render passes and no target before the layer says so
  // bound_buffers: in each streamed frame the layer also copies, at the end of this render pass (its
  // ordinal in its command buffer; -1: none), every buffer range the descriptor sets bound at the
  // graphics bind point during it bind, and its push constants (LiveSession::boundBuffers).
  int boundBuffersPass = -1;
  uint64_t boundBuffersMaxBytes = 4u << 20;  // in all; the rest is left out (the layer says so)
  std::string layerDir;                  // the folder of VkLayer_gblens_live.json ("" : layerFolder())
  std::vector<std::string> environment;  // more NAME=VALUE for the application
  std::string log;                       // the application's stdout and stderr go here ("" : gblens's own)
};

struct LiveFrameInfo {
  uint64_t stream = 0;    // its number among the streamed frames (1, 2, ...)
  uint64_t appFrame = 0;  // the application's frame (0: its first)
  double latencyMs = 0.0; // from the end of that frame (present or submission) to poll() returning it
  uint64_t endNs = 0;     // when that frame ended (CLOCK_MONOTONIC, live_wire.h monotonicNs)
  // Per layout target: where it came from ("render pass 3 \"gbuffer\""), or why it is absent.
  std::vector<std::string> sources, absent;
};

struct LiveCounts {
  uint64_t received = 0;     // frames poll() returned
  uint64_t undecodable = 0;  // frames that came but did not decode (the reports say why)
  uint64_t overwritten = 0;  // frames read in place that the application's GPU wrote again meanwhile
  uint64_t dropped = 0;      // frames the layer dropped because this side was still busy (or the ring moved)
  uint64_t notAsked = 0;     // LiveOptions::paced: frames this side had not asked for (the layer copied none of most)
  uint64_t appFrames = 0;    // frames the application had ended at the last frame received
  double meanLatencyMs = 0.0, maxLatencyMs = 0.0;
  double meanDecodeMs = 0.0;  // this side's time to turn a frame into a FrameSnapshot
  // From the end of the application's frame to its copies being done (the layer saw its fence):
  // the GPU's own latency, without the transfer to this side and the decoding.
  double meanReadyMs = 0.0;
  nlohmann::json layer;      // the layer's own figures with the last frame (docs/attach.md)
};

class LiveSession {
 public:
  LiveSession() = default;
  ~LiveSession();  // detaches; the application runs on
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  // Starts the application under the layer. False, with nothing started, on a layout mistake (one
  // line naming the file, the target and the field) or when the layer is not built.
  bool start(const LiveOptions& o, std::string& error);
  // The next streamed frame if one has come (never waits): decoded into `out`, true.
  bool poll(FrameSnapshot& out, LiveFrameInfo* info = nullptr);
  // Waits up to `seconds` for one (less when the application ends first, or `wakeFd` becomes readable).
  bool wait(FrameSnapshot& out, double seconds, LiveFrameInfo* info = nullptr, int wakeFd = -1);
  // Decodes the frames to come with another layout that streams the same attachments (a refined
  // draft: targets renamed, other quantities): same targets in the same order, each with the same
  // storage format and live source. False, with the target named, otherwise.
  bool setLayout(const nlohmann::json& layout, std::string& error);
  // A frame poll() / wait() returned that is no longer needed: its buffers hold the next frames'
  // texels (TexelPool, import.h), one frame's worth kept (the memory the frame held).
  void recycle(FrameSnapshot&& frame);
  // LiveOptions::paced: the layer may copy the next frame, or the next two (a stream slower than its
  // viewer: one on its way while the other is shown), beyond those it sent.
  void ready(unsigned frames = 1);

  const LiveCounts& counts() const { return counts_; }
  // What the layer and the decoding said for people since the last call, each once: a target the
  // application never draws, a format the layout does not match, a frame that did not decode.
  std::vector<std::string> takeReports();
  // The buffers bound at the bound_buffers pass of the frame poll() / wait() last returned, in bind
  // order, as a RenderDoc capture's draw state gives them to the camera search: name (the debug
  // name, else "set S binding B"), kind ("uniform", "storage"; "push_constants": the pass's push
  // constants, offset and range their bytes), set, binding, index, offset and range of the bound
  // range, bytes (the whole buffer's size), data (the range's bytes, max_bytes in all), bound = true.
  const std::vector<RdcBinding>& boundBuffers() const { return boundBuffers_; }
  // The last LiveOptions::history frames decoded, oldest first, with the application's frame numbers
  // (the one poll() / wait() last returned among them); bounded by that many frames' bytes.
  const FrameHistory& history() const { return history_; }
  // The layer's report of one frame's render passes (--suggest), once it came.
  const nlohmann::json* suggestion() const { return suggestion_.is_null() ? nullptr : &suggestion_; }
  bool noMatch() const { return noMatch_; }           // the layer gave up finding any target
  const nlohmann::json& hello() const { return hello_; }  // the application and device, once attached
  bool attached() const { return conn_ >= 0; }
  bool paced() const { return options_.paced; }

  bool running();                      // the application has not exited
  int exitStatus() const { return status_; }  // once it exited: its status (128 + signal if killed)
  long applicationPeakKb() const { return peakKb_; }  // once it exited: its peak resident memory
  pid_t pid() const { return pid_; }
  void detach();                       // the layer goes idle for good; the application runs on
  void stop();                         // detach and end the application (SIGTERM, SIGKILL after 3 s)
  int waitApplication(double seconds = -1.0);  // its exit status, -1 while it still runs

 private:
  bool accept();
  bool receive(FrameSnapshot& out, LiveFrameInfo* info);
  bool decode(const nlohmann::json& frame, FrameSnapshot& out, LiveFrameInfo* info, std::string& error);
  bool decodeBoundBuffers(const nlohmann::json& frame, std::string& error);
  void addReport(const std::string& text);

  LiveOptions options_;
  Layout layout_;                      // its sources as the layer reads them (live_decode.cpp)
  std::vector<std::string> wireNames_; // each target's name in the request (frames name targets so)
  std::string layoutDir_, dir_, socketPath_, request_;
  int listener_ = -1, conn_ = -1, shm_ = -1;
  // The shared-memory files the layer sent, by id (0: its copy of a frame; others: ring buffers read
  // in place, a submission count in their first bytes).
  struct Mapping {
    const uint8_t* data = nullptr;
    size_t size = 0;
  };
  std::map<uint32_t, Mapping> buffers_;
  // The bytes of a frame's buffer range, or null when it lies outside what was mapped.
  const uint8_t* bytesAt(const nlohmann::json& where, size_t& bytes) const;
  // The ring buffers' submission counts are what the frame says (else a reused command buffer wrote
  // them again: the frame is torn).
  bool untouched(const nlohmann::json& frame) const;
  pid_t pid_ = -1;
  int status_ = -1;
  long peakKb_ = 0;
  bool detached_ = false, noMatch_ = false;
  nlohmann::json hello_, suggestion_;
  std::vector<RdcBinding> boundBuffers_, decodedBound_;  // the frame returned; the one being decoded
  std::vector<std::string> reports_;
  std::set<std::string> said_;
  LiveCounts counts_;
  FrameHistory history_;
  TexelPool pool_;
};

// What LiveSession::start resolves before it starts anything: the layout (as given, and as the layer
// streams it), the folder its relative names start from, and the request for the layer. False on a
// layout mistake (one line naming the file, the target and the field). `gblens attach`'s command
// line is checked through it without an application (tests/fuzz/fuzz_attach.cpp).
struct LivePlan {
  Layout original, live;
  std::string layoutDir, request;
};
bool planLive(const LiveOptions& o, LivePlan& plan, std::string& error);

// Where the layer and its manifest are: GBLENS_LAYER_DIR, else layer/ beside the gblens executable.
std::string layerFolder();

// The layout as the layer streams it, and the request that tells the layer so: targets without a
// source read the image of their own name; {"renderdoc": NAME} reads the image NAME. False on a
// source that cannot be streamed (a file, a RenderDoc resource id), with the field named.
bool liveLayout(Layout& layout, std::string& error);
nlohmann::json liveRequest(const Layout& live, const LiveOptions& o);

}  // namespace gb
