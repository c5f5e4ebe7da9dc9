// gblens view: the window, the live renderer, the interface. Split over app/viewer/*.cpp:
// window.cpp (GLFW, swapchain, Dear ImGui's backends), startup.cpp (arguments, context, frame
// source; exit summary, teardown), viewer.cpp (the loop: render on demand),
// controls.cpp (keys, camera, lights), camera_rig.cpp (orbit/fly), probe.cpp (region read-back ->
// the shared dossier), captures.cpp (capture button, --capture / --compare), sequence.cpp (view SEQ:
// the timeline, the frame cache, the probe's track).
#pragma once
#include <array>
#include <chrono>
#include <deque>
#include <future>
#include <memory>
#include <fstream>
#include <string>
#include <vector>

#include "renderer/core/options.h"
#include "renderer/core/progress.h"
#include "renderer/frame/region_readback.h"
#include "renderer/reference/reference.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/swapchain.h"
#include "views/analysis/decompose.h"
#include "views/analysis/error.h"
#include "views/capture/capture.h"
#include "views/capture/sequence.h"
#include "views/live/live.h"
#include "views/live/live_receiver.h"
#include "views/ui/view_decode.h"
#include "views/ui/view_map.h"
#include "views/ui/viewer_model.h"

struct GLFWwindow;

namespace gb {

struct ViewerArgs {
  std::string scene = "builtin:temple";  // SCENE as given (titles, manifests)
  RenderOptions render;            // the common options as parsed
  std::string device;              // --device
  bool validate = false;           // --validate
  std::string commandLine;         // as typed (capture manifests)
  bool sizeGiven = false;          // --size: render at that size, else at the view area's size
  std::string window = "1280x800";  // initial window size
  bool windowGiven = false;        // --window given (else sized to the monitor)
  bool paused = false;
  bool probeReference = false;     // --probe-reference: the Pixel panel's reference starts on
  std::string referenceErrorDir;   // --reference-error DIR: compute the reference error at start, write its maps
  std::string initialView;          // --view NAME (default: the layout's first colour view)
  std::string probeLog;            // --probe-log: each dossier as one JSON line
  std::string eventLog;            // --event-log: layout/probe/exit events as JSON lines (tests)
  std::string capture, compare;    // --capture DIR / --compare B (Capture issue)
  int reduceWhileMoving = 0;       // --reduce-while-moving: ViewerModel::kReduceAuto, kReduceOff or n
  // gblens attach (live_source.cpp): the attached application's stream and its first frame (the
  // command waited for it); the viewer shows the latest frame polled like an opened capture.
  LiveSession* attach = nullptr;
  const FrameSnapshot* attachFirst = nullptr;
  LiveFrameInfo attachFirstInfo;
  // attach --suggest without a layout: the layer's passes and what was found, and the drafted layout
  // the stream is decoded with (the suggestion window shows them; ctrl+S saves the draft).
  std::string attachPasses;
  std::vector<std::string> attachSummary;
  nlohmann::json attachDraft;
};

// The camera the viewer renders: starts as an exact copy of a scene camera; moving it derives
// orbit/fly parameters from that matrix once.
struct CameraRig {
  CameraDesc desc;
  bool derived = false;
  glm::dvec3 position{0.0}, target{0.0};
  double yaw = 0.0, pitch = 0.0, distance = 1.0;
  double sceneRadius = 1.0;
  glm::dvec3 sceneCenter{0.0};
};
void resetRig(CameraRig& rig, const CameraDesc& from, const Bounds& bounds);
void orbitRig(CameraRig& rig, glm::dvec2 pixels);  // turn around the target
void lookRig(CameraRig& rig, glm::dvec2 pixels);   // turn in place (fly)
void moveRig(CameraRig& rig, glm::dvec3 local);    // right, up, back in scene units
void dollyRig(CameraRig& rig, double steps);

struct ImGuiVulkan;  // window.cpp
struct SequenceSource;  // sequence.cpp: the sequence opened, its frame cache
struct TemporalWork;    // temporal_views.cpp: the motion and flicker workers and their maps
struct LiveHistoryFrames;  // live_timeline.cpp: an attached stream's kept frames, held while frozen

// Input as GLFW reported it, queued for the interface frames (input.cpp).
struct InputEvent {
  enum Kind : uint8_t { Key, Button, Move, Scroll, Char } kind = Move;
  int a = 0, b = 0, c = 0, d = 0;  // key: key, scancode, action, mods; button: button, action, mods; char: a
  double x = 0.0, y = 0.0;         // the cursor when it happened (window coordinates)
  double dx = 0.0, dy = 0.0;       // scroll
};
struct InputQueue {
  std::deque<InputEvent> events;
  double x = -1.0, y = -1.0;       // the cursor as the delivered events left it (-1: none yet)
  std::array<bool, 5> down{};      // mouse buttons as the delivered events left them
  double cursorX = -1.0, cursorY = -1.0;  // the last position the cursor callback reported
};

struct Viewer {
  ViewerArgs args;
  GLFWwindow* window = nullptr;
  GpuContext ctx;
  Swapchain swapchain;
  bool swapchainValid = false;
  VkDescriptorPool imguiPool = VK_NULL_HANDLE;
  Scene scene;
  std::unique_ptr<reference::RayScene> referenceRays;  // built the first time the probe asks for the reference
  std::vector<double> baseRadius;  // the scene's light radii before the radius scale
  Renderer renderer;
  bool rendererReady = false;
  ViewMapper mapper;
  // --capture A / --compare B: the captures, and each view of A's layout decoded (visualize.h
  // viewImage) on the CPU and uploaded; B's view of the same name beside it (quantity -1: none).
  Capture captureA, captureB;
  std::vector<CpuImage> decodedA, decodedB;
  std::vector<ViewDef> viewsB;
  ViewImages imagesA, imagesB;
  std::vector<std::string> rangeKeys;  // per view: the settings its CPU range was computed for
  // gblens attach: the views on screen of each streamed frame decoded on the GPU (view_decode.h; off
  // with GBLENS_VIEW_DECODE=cpu), and per view so decoded its range statistics per component.
  ViewDecoder decoder;
  bool gpuDecode = false;
  std::vector<std::vector<RangeStats>> gpuRanges;  // only views with an automatic range have them
  std::vector<bool> gpuDecoded;
  // --compare: FLIP of each colour view (A the reference, B the test), computed by a worker at open
  // (captures.cpp): per view its per-pixel FLIP (hover) and magma image (imagesFlip); empty: none.
  struct FlipMaps {
    std::vector<std::vector<float>> errors;
    std::vector<CpuImage> images;
    std::vector<std::optional<FlipPool>> pools;
  };
  std::future<FlipMaps> flipJob;
  std::shared_ptr<WorkProgress> flipProgress;  // views done of those FLIP applies to
  std::vector<std::vector<float>> flipErrors;
  ViewImages imagesFlip;
  // The reference error, live (reference_error.cpp): the worker computing it and its progress, the
  // frame it was computed for, its result, and its maps as views of the live frame (quantity -1).
  struct ReferenceResult {
    FrameError error;
    Decomposition decomposition;
    std::string decomposeError;  // why there is none
    bool cancelled = false;
  };
  std::future<ReferenceResult> referenceJob;
  std::shared_ptr<WorkProgress> referenceProgress;
  std::chrono::steady_clock::time_point referenceStart, referenceCancelAt;
  int referenceLoggedTenth = 0;   // progress logged to --event-log up to this tenth
  bool referenceStarted = false;  // --reference-error DIR: started once
  RenderOptions referenceOptions;
  uint64_t referenceCamera = 0, referenceLights = 0;
  std::optional<ReferenceResult> referenceResult;
  std::vector<ViewDef> referenceViews;     // "error/<map>", "decompose/<term>"
  std::vector<CpuImage> referenceDecoded;  // their values, as decoded view images
  std::vector<std::optional<std::pair<uint32_t, RangeStats>>> referenceRanges;  // automatic range (component mask, stats)
  ViewImages referenceImages;
  bool referenceBusy = false;   // a worker runs (reference, FLIP): keep iterating to show progress and pick it up
  Scene sceneB;
  bool hasB = false;
  // gblens attach: captureA.frame is the frame shown (the latest polled, frozen while paused).
  LiveFrameInfo attachInfo;
  std::chrono::steady_clock::time_point attachLastStatus, attachOpened;
  bool attachExitLogged = false;
  bool attachPlaying = true;     // m.playing as last seen (pause and resume are logged)
  std::vector<int> attachShown;  // the views decoded from the frame shown (those on screen)
  std::unique_ptr<LiveReceiver> receiver;  // the stream's frames, received and decoded on its own thread
  bool attachPresentPending = false;       // a new frame of the stream goes to the screen with this present
  double attachShownMs = 0.0;              // the last one's latency from the application's frame end to the screen
  bool attachDetachLogged = false;
  // attach --history K: the kept frames the timeline steps through while the stream is frozen (null
  // while it runs), and the frame shown whose kept frames' numbers the strip has (live_timeline.cpp).
  std::shared_ptr<LiveHistoryFrames> liveHistory;
  uint64_t liveNumbersFor = 0;
  // gblens view SEQ: captureA.frame is a copy of the sequence's frame shown (sequence.cpp).
  std::shared_ptr<SequenceSource> sequence;
  std::shared_ptr<TemporalWork> temporal;  // its temporal views (temporal_views.cpp)
  ViewerModel model;
  CameraRig rig;
  uint64_t cameraVersion = 1, lightsVersion = 1;
  float appliedRadiusScale = 1.0f;  // the light radius scale the scene's lights carry
  uint64_t renderedCamera = 0, renderedLights = 0;
  bool frameValid = false;         // targets hold a frame that matches the model
  bool rangesStale = true;
  std::string rangesKey;           // which automatic ranges are current
  std::vector<ViewDraw> draws;     // this interface frame's views (ImGui callback data)
  int uiFramesLeft = 3;            // interface frames still to draw after the last event
  std::chrono::steady_clock::time_point lastTick, clickTime;
  bool clickPending = false;
  bool probeShownPending = false;  // log when the dossier of a click is first on screen
  std::chrono::steady_clock::time_point probeStart;
  std::optional<glm::ivec2> hoverRead;
  std::optional<int> hoverReadView;
  std::string loggedHover;         // the hover text last written to --event-log
  std::vector<TexelValuesDrawn> loggedTexelValues;  // the texel values last written to --event-log
  std::string markCountKey;        // the mark and frame the marked pixels were counted for
  uint64_t framesShown = 0;        // frames of an attached application shown so far (a new one: count again)
  std::optional<glm::ivec2> dossierShownFor;  // the probed pixel whose dossier the panel has settled on
  std::string layoutKey;           // logged layout, to log changes only
  std::ofstream probeLog, eventLog;
  std::vector<double> renderMs, presentMs;
  std::vector<double> renderedLoopMs;  // whole iterations that rendered a frame: render + views + present
  std::vector<int> pressedKeys;    // key presses since the last loop iteration
  InputQueue input;                // events for Dear ImGui, one button transition a frame
  // Responsive rendering (viewer.cpp): what the frame on screen shows at full size, when input last
  // changed it, and the last rendering iterations' times at full size and reduced.
  RenderOptions fullOptions;
  std::chrono::steady_clock::time_point lastInput;
  double fullIterationMs = 0.0, reducedIterationMs = 0.0;
  int autoReduceBy = 2;            // the reduction auto uses next (adapted to the measured times)
};

int runViewer(const ViewerArgs& args, Scene scene);

// startup.cpp
// Checks the arguments, opens the logs, the window, its context and the frame source, and sets
// the model's first state; false (exit 2) after a message, with nothing left open.
bool startViewer(Viewer& v);
// Logs and prints the exit summary and tears everything down; the exit status (1: validation
// messages).
int finishViewer(Viewer& v);

// input.cpp
// GLFW's callbacks: events queued (and the viewer's own key list, click time); focus and cursor enter
// go to ImGui at once.
void installInputCallbacks(Viewer& v);
// Before ImGui's NewFrame: the queued events up to and including the next button or key transition.
void feedInput(Viewer& v);
// After it: the cursor and buttons as those events left them (ImGui's backend polls the current ones).
void applyInputState(Viewer& v);

// controls.cpp
void handleKeys(Viewer& v);
bool updateCamera(Viewer& v, double dt);  // true while keys move the camera
void updateLights(Viewer& v);

// window.cpp
bool openWindow(Viewer& v, uint32_t width, uint32_t height);
void closeWindow(Viewer& v);
bool recreateSwapchain(Viewer& v);
void initImGui(Viewer& v);
void shutdownImGui(Viewer& v);
// Draws the ImGui draw data into the swapchain (views through the renderer's view mapping).
bool presentFrame(Viewer& v);

// probe.cpp
// Reads back the pixel's texels (and the shadow-map block its lookup reads) and computes the
// shared dossier (views/probe.h). `logged`: a user's probe (written to --probe-log).
void probeViewerPixel(Viewer& v, glm::ivec2 pixel, bool logged);
void readHover(Viewer& v);
// How many screen pixels sample the marked shadow-map texel (a full read-back of the depth, once per
// mark and frame).
void countMarkedPixels(Viewer& v);
// The probed pixel again on a new full frame (the same image coordinates); notes when its content changed.
void refreshProbe(Viewer& v);
// Read-back windows (texel (x0, y0) of the target is image texel (0, 0)) placed into a snapshot.
void addRegions(FrameSnapshot& s, const std::vector<RegionImage>& regions);
// The live frame's snapshot with every readable screen-space target read back in the rectangle
// (x, y, width, height): the probe's pixel, the live values in texels' tiles.
FrameSnapshot screenRegionSnapshot(Renderer& r, int x, int y, int width, int height);

// live_texels.cpp
// ViewerModel::texelValue for the live frame: values in texels at high zoom, read back in tiles.
void installLiveTexelValues(Viewer& v);

// region.cpp
// The statistics of the selected region (ViewerModel::region) when it is new or the frame changed.
void updateRegion(Viewer& v);

// captures.cpp
// Captures the live frame (rendered again, whole) to ./gblens-capture-<date>-<time>/; with `rdc`,
// under RenderDoc, the same frame is also a RenderDoc capture written beside it (*rdc: its path).
bool captureLiveFrame(Viewer& v, std::string& written, std::string& error, std::string* rdc = nullptr);
bool openCaptures(Viewer& v);  // false: a message was printed (exit 2)
void probeCapturePixel(Viewer& v, glm::ivec2 pixel);
// A scene holding only a camera (renderers that hold uploaded frames).
Scene emptyScene(const Camera& camera);
// FLIP of the compare views: picks up the worker's maps (true while it runs).
bool updateCompareFlip(Viewer& v);
void stopCompareFlip(Viewer& v);  // teardown
std::string captureHoverText(const Viewer& v, int view, glm::ivec2 texel);

// sequence.cpp (gblens view SEQ, SEQ@N): a sequence's frames shown one at a time, a timeline over them
// True when `text` names a sequence (a folder with sequence.json) or a frame of one (SEQ@N).
bool sequenceArgument(const std::string& text);
// Opens the sequence v.args.capture names and loads its first frame (or frame N) into captureA, the
// timeline's state in the model; false with `error`.
bool openSequence(Viewer& v, std::string& error);
// The timeline's work each iteration: plays at the sequence's rate, shows the frame the strip or a key
// asked for (the views, zoom and pan kept; the probe moved along its track). True while playing.
bool updateSequence(Viewer& v, double dt);
// After a probe of a sequence's frame: the point followed through the other frames (model.track).
void trackSequenceProbe(Viewer& v);
std::string describeCapture(const Capture& c);  // captures.cpp: what the capture panel says of one
// Frame i of the sequence opened, from its cache (loaded when not there); null with `error`.
std::shared_ptr<const Capture> sequenceFrame(Viewer& v, size_t i, std::string& error);
const Sequence& openedSequence(const Viewer& v);  // v.sequence must be set

// temporal_views.cpp (a sequence's temporal views: the motion check of the pair ending at the frame
// shown, the flicker of a view; maps as views of the frame, quantity -1, computed in a worker thread)
// The temporal views appended to a sequence frame's views (setCaptureViews).
void appendTemporalViews(const Viewer& v, std::vector<ViewDef>& views);
// Their decoded images into decodedA and why one cannot show now into unavailable (before the upload).
void fillTemporalViews(Viewer& v);
// The work each iteration: starts the motion check when the frame shown changed (a running one is
// cancelled), the flicker on request, picks up results. True while a worker runs.
bool updateTemporalViews(Viewer& v);
void stopTemporalViews(Viewer& v);  // teardown: cancels and waits
// The hovered temporal view's value at a pixel ("" when `view` is not one).
std::string temporalHoverText(const Viewer& v, int view, glm::ivec2 texel);
// Its value printed in the texel at high zoom (ViewerModel::texelValue); nothing outside its image.
std::optional<TexelValue> temporalTexelValue(const Viewer& v, int view, glm::ivec2 texel);

// reference_error.cpp
// The reference error's work: starts the worker on request, cancels it on request, picks up its
// result and makes its maps views, marks it stale when the frame changes, and with
// --reference-error DIR writes every map there. True while the worker runs (the loop keeps polling).
bool updateReferenceError(Viewer& v);
// Cancels a running worker, waits for it and frees the maps (teardown).
void stopReferenceError(Viewer& v);
// The computed maps appended to the live frame's views (updateLiveViews).
void appendReferenceViews(const Viewer& v, std::vector<ViewDef>& views);
// Why a map's view cannot show now ("" it can); sets its GPU source (a decoded image).
std::string referenceViewStatus(Viewer& v, int view);
ViewImage referenceViewImage(const Viewer& v, int view);
// The hovered map's value at a pixel ("" when `view` is not a map).
std::string referenceHoverText(const Viewer& v, int view, glm::ivec2 texel);
// The automatic ranges of the shown views of a capture (CPU, from the decoded images).
void updateCaptureRanges(Viewer& v);
// The live frame's views (gblens's layout under the frame's options): set when the layout's views
// change, their GPU sources and why a view cannot show now.
void updateLiveViews(Viewer& v);

// The live frame rendered for the loop (frame_render.cpp): on demand, reduced while input changes it.
constexpr double kRefineAfterMs = 100.0;  // a reduced frame is refined this long after the last input
double millisecondsSince(std::chrono::steady_clock::time_point t);
// Picks the next reduction from the iteration's time (ms) when a reduced frame was shown.
void adaptReduction(Viewer& v, int reducedBy, double ms);
// The options the frame on screen should have: the user's, sized to the view area (fbWidth x fbHeight).
RenderOptions wantedOptions(Viewer& v, int fbWidth, int fbHeight);
// Renders when the frame on screen is outdated (reduced while input changes it; `refine`: full now).
void renderIfNeeded(Viewer& v, const RenderOptions& full, bool animating, bool refine = false);
// The automatic ranges of the views on screen (GPU-reduced for live frames, CPU for captures).
void updateRanges(Viewer& v);

// live_source.cpp (gblens attach)
// The attached stream's first frame as the frame shown (openCaptures' work for a stream).
void openAttached(Viewer& v);
// Takes the newest streamed frame unless paused, the layer's reports and the application's state;
// true when the frame shown changed or the status did (another interface frame is due).
bool pollAttached(Viewer& v);
// The frame shown becomes `frame` (the views of a new layout set up, else those on screen decoded
// again); `kept`: one of the stream's kept frames (live_timeline.cpp), not logged as taken.
void showStreamFrame(Viewer& v, FrameSnapshot&& frame, const LiveFrameInfo& info, bool kept = false);
// live_timeline.cpp (attach --history K): the strip over the kept frames; a step or the slider
// freezes the stream, frozen it shows the kept frame asked for. True when the strip or frame changed.
bool updateLiveTimeline(Viewer& v);
// After a probe of a frozen stream's frame: the point followed through the kept frames.
void trackLiveProbe(Viewer& v);
// Writes the frame shown as a capture (the folder ./gblens-attach-<date>-<time>/).
bool captureAttachedFrame(Viewer& v, std::string& written, std::string& error);
// After a present that put a new frame of the stream on screen: its latency from the application's
// frame end to the screen, logged (attach_shown) and shown in the status bar.
void attachedFramePresented(Viewer& v);
// Writes attach --suggest's draft layout (./gblens-layout-<date>-<time>.json, atomically).
bool saveAttachedDraft(const std::string& draft, std::string& written, std::string& error);
// The views of capture A's layout decoded and uploaded again (captures.cpp; a new frame of a stream).
// decode: every view decoded on the CPU now (a stream's frame: false, the views on screen are
// decoded by decodeShown; unavailable says which targets the frame lacks).
void setCaptureViews(Viewer& v, bool decode = true);
// X: multisampled targets show their next sample (captures.cpp); the views, probe and statistics follow.
void showNextSample(Viewer& v);
// The frame's views: its layout's, then a spread view per multisampled target (sample_views.h).
std::vector<ViewDef> frameViews(const FrameSnapshot& f);
std::string samplesNote(const FrameSnapshot& f);  // "multisampled: showing sample 1 of 4 ..." ("" : not)

// Appends one JSON line to a log file (no-op when the file is not open).
void logLine(std::ofstream& f, const nlohmann::json& j);

}  // namespace gb
