// Everything the viewer's interface shows and edits, as plain data. The app (app/viewer) owns
// it: it renders from it and fills in what the renderer produced; the panels (views/*_panel.cpp,
// ImGui only) read and write it and never touch the renderer.
#pragma once
#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "renderer/frame/renderer.h"
#include "views/analysis/flip.h"
#include "views/analysis/probe.h"
#include "views/analysis/probe_reference.h"
#include "views/analysis/probe_track.h"
#include "views/analysis/region_stats.h"
#include "views/analysis/shadow_marks.h"
#include "views/ui/view_layout.h"

struct ImDrawList;
struct ImDrawCmd;

namespace gb {

struct CompareReport;  // views/analysis/compare.h

// Which frame a view shows: the live one (or capture A), capture B, |A - B|, or the FLIP map of A
// against B (views/analysis/flip.h; colour views).
enum class FrameSide { A, B, Difference, Flip };

// How --compare shows a view (views/ui/compare_panel.cpp): A or B in place (Space flips them, the
// same zoom and pan), swiped (A left of a handle, B right), |A - B|, FLIP, or A, B and |A - B| in a row.
enum class CompareMode { Alternate, Swipe, Difference, Flip, Row };

// A view to draw inside the ImGui draw data: the app's callback records it (views/ui/view_map),
// reading view `view` of the side's frame.
struct ViewDraw {
  int view = 0;
  gpu::ViewParams params;
  Rect rect;  // framebuffer pixels: the view's rectangle (the draw command's clip rect clips it)
  FrameSide side = FrameSide::A;
  double splitX = -1.0;  // framebuffer x: A left of it, B right of it (compare split); < 0: none
};

// Where the frame comes from: the live renderer, a capture (--capture), or two (--compare).
enum class FrameSource { Live, Capture, Compare };
using ViewDrawCallback = void (*)(const ImDrawList*, const ImDrawCmd*);

enum class CameraMode { Orbit, Fly };

// A texel's value as the viewer prints it inside the texel at high zoom (views/ui/texel_values.cpp):
// the lines (views/analysis/view_text.h texelValueLines) and the decoded components, which pick the
// text's colour (black on light texels, white on dark ones).
struct TexelValue {
  std::vector<std::string> lines;
  std::array<float, 4> value{};
  bool empty = true;  // nothing drawn there
};
using TexelValueSource = std::function<std::optional<TexelValue>(int view, FrameSide side, glm::ivec2 texel)>;
// What the last interface frame printed in one view (the app logs it: "texel_values" events).
struct TexelValuesDrawn {
  int view = -1;
  FrameSide side = FrameSide::A;
  double scale = 0.0;  // window pixels per texel
  std::vector<std::pair<glm::ivec2, std::vector<std::string>>> texels;
  bool operator==(const TexelValuesDrawn&) const = default;
};

struct ViewerModel {
  FrameSource source = FrameSource::Live;
  std::string captureA, captureB;    // directories (capture modes)
  std::string captureInfo;           // what the capture(s) hold, for the panel
  std::string samplesNote;           // a multisampled frame: the sample shown (X: the next)
  uint32_t sampleShown = 0;          // ... which X chose (a stream's frames keep it)
  std::string compareSummary;        // `gblens compare`'s report of A vs B (text), or why there is none
  std::shared_ptr<const CompareReport> compareReport;  // the same, shown as tables
  CompareMode compareMode = CompareMode::Alternate;
  FrameSide compareSide = FrameSide::A;  // Alternate: the capture shown
  float splitAt = 0.5f;              // split position, fraction of the view's width
  bool draggingSplit = false;
  std::vector<double> differenceMax;  // compare: largest |A - B| of each view (white point)
  std::vector<std::optional<FlipPool>> flipPools;  // compare: FLIP of each colour view, once computed
  std::string flipStatus;            // why a view has no FLIP map yet ("computing FLIP: 1 of 3 views")
  bool dossierDifferencesOnly = false;  // compare dossiers: only the rows that differ

  // ---- what is shown: the views of the frame's layout (views/analysis/view_table.h) ----
  std::vector<ViewDef> views;          // setViews(): every per-view vector below has one entry a view
  LayoutMode layout = LayoutMode::Single;
  int primary = 0, secondary = 1;      // indices into views
  std::vector<ViewSettings> settings;
  std::vector<ViewGpuSource> gpuSources;  // how the GPU reads each view (the app sets them)
  Layout frameLayout;                     // the layout the views come from (bit names, ids' names, ...)
  int edited = 0;                      // the view whose settings the panel shows (last used)
  ViewTransform transform;
  bool grid = true;
  // Values printed in texels once a texel is large enough for them (tev, RenderDoc): the app gives
  // the values of the frames it holds on the CPU (captures); none: the view shows the grid only.
  bool texelValues = true;
  TexelValueSource texelValue;
  std::vector<TexelValuesDrawn> texelValuesDrawn;  // this interface frame's, one per view that printed
  double texelScale = 0.0;  // window pixels per texel of the first view slot drawn (the zoom label)
  bool showControls = true, showPixel = true;

  // ---- the frame as rendered (the app fills these) ----
  RenderOptions rendered;                       // options of the frame on screen
  glm::uvec2 shadowMapSize{1, 1};
  FrameStats stats;
  double presentMs = 0.0;                       // views + interface, last presented frame
  uint64_t framesRendered = 0, framesPresented = 0;
  std::vector<std::vector<RangeStats>> ranges;  // automatic ranges (one per selected component)
  std::vector<std::string> unavailable;         // why a view has nothing to show now ("": it has)
  std::string deviceName, sceneName;
  std::vector<std::string> cameraNames;         // the scene's (glTF) cameras

  // ---- what the user asks for (the app compares with `rendered`) ----
  RenderOptions wanted;
  bool fixedSize = false;          // render at wanted.width x height, else at the view area's size
  int renderScale = 1;             // render at 1/renderScale of the view area (faster camera moves)
  // While input changes the frame (camera, options, lights, a time step) the viewer may render at
  // 1/n of the full size and refine to full when the input stops: kReduceAuto picks n from the
  // measured frame times (none where a full frame is fast), kReduceOff never, n >= 2 always 1/n.
  static constexpr int kReduceAuto = 0, kReduceOff = 1;
  int reduceWhileMoving = kReduceAuto;
  int reducedBy = 1;               // the frame on screen is 1/reducedBy of the full size (1: full)
  glm::uvec2 fullSize{0, 0};       // the full frame's size: views place a reduced frame at it
  int lightCount = 256;
  float lightRadiusScale = 1.0f;
  bool cullingStats = true;        // culling efficiency: reads back coverage and depth each frame
  bool playing = true;
  float timeSpeed = 1.0f;
  bool stepForward = false, stepBack = false;
  CameraMode cameraMode = CameraMode::Orbit;
  float moveSpeed = 1.0f;          // fly speed, scene units per second (scaled by the scene size)
  bool resetCamera = false;
  int gltfCamera = -1;             // a scene camera to jump to (-1: none)
  glm::dvec2 cameraDrag{0.0};      // right-drag this frame (window pixels): orbit / look
  double cameraDolly = 0.0;        // ctrl+wheel this frame (orbit distance)

  // ---- hover and probe ----
  std::optional<glm::ivec2> hover;          // screen texel under the mouse (every view marks it)
  std::optional<int> hoverView;             // the view under the mouse
  std::optional<glm::ivec2> hoverShadowTexel;
  std::string hoverText;                    // values under the mouse (app fills)
  std::optional<glm::ivec2> probeRequest;   // a click or an arrow key: the app probes it
  std::optional<glm::ivec2> probePixel;     // the pixel of the dossier shown
  std::optional<glm::ivec2> shadowMark;     // shadow-map texel clicked: the pixels sampling it are marked
  std::optional<ShadowMarks> shadowMarks;   // those pixels in the frame shown (none: not counted yet)
  std::string shadowMarkNote;               // why none are marked, or why they are not counted yet
  std::optional<glm::ivec2> shadowTexelOfProbe;  // the texel the probed pixel's shadow lookup read
  std::optional<PixelDossier> dossier;      // the shared dossier (views/probe.h) of probePixel
  nlohmann::json dossierJson;               // the same as JSON (copy, --probe-log)
  std::optional<PixelDossier> dossierB;     // compare: capture B's dossier of the same pixel
  std::string probeError;
  std::string probeNote;                    // the dossier is of an earlier frame, or its pixel's content changed
  double probeLatencyMs = 0.0;
  // The reference column (views/analysis/probe_reference.h): asked for in the panel, computed by
  // the app with each probe of a live frame; `referenceNote` says why there is none.
  bool probeReference = false;
  // The reference error, live: the maps of `gblens error -o` for the frame on screen, computed on
  // request in a worker thread (views/ui/reference_error_panel.cpp, app/viewer/reference_error.cpp).
  // The maps are views of the live frame (quantity -1, named "error/<map>" and "decompose/<term>"),
  // appended to its layout's views once computed.
  struct ReferenceErrorUi {
    bool computeRequested = false;  // the panel's button, the View menu
    bool cancelRequested = false;   // the panel's Cancel, Escape
    bool computing = false, ready = false;
    bool stale = false;             // the frame changed since it was computed
    double seconds = 0.0;           // computing: so far; ready: what it took
    double progress = 0.0;          // computing: fraction of the work done
    std::string summary, error, decomposeNote;
    std::map<std::string, std::string> legends;  // a map's view name -> what its colours mean
  } referenceError;
  std::optional<ReferencePixel> reference;
  std::string referenceNote;
  double referenceMs = 0.0;
  bool copyJson = false;
  size_t copiedBytes = 0;   // the last copy, for the confirmation
  double copiedAt = -1e9;   // ImGui time of it

  // ---- region statistics: ctrl + left drag in a screen view (views/analysis/region_stats.h) ----
  std::optional<glm::ivec2> regionAnchor;      // drag in progress: the first corner (frame pixels)
  std::optional<RegionRect> region;            // the selected rectangle (frame pixels)
  bool regionDirty = false;                    // selection finished or frame changed: the app recomputes
  std::optional<RegionStats> regionStats;      // of capture A or of the live frame's read-back
  std::string regionNote;                      // why there are no numbers yet (a reduced frame, ...)
  int regionSeries = -1;                       // the series whose histogram is drawn (-1: the first)

  // ---- capture ----
  bool captureAvailable = false;
  std::string captureHint;                  // tooltip: what the button does, or why it is grey
  bool captureRequested = false;
  bool renderDocRequested = false;          // "Capture in RenderDoc" (live frames under RenderDoc)
  bool renderDocAvailable = false;          // gblens runs under RenderDoc
  std::string captureStatus;

  // ---- gblens attach: the frame is the latest one streamed from an application (app/viewer/live_source.cpp) ----
  struct AttachUi {
    bool on = false;             // the frames come from an attached application (source is Capture)
    bool detachRequested = false;  // the menu's "Detach": the layer goes idle, the last frame stays
    std::string application;     // its name and device, as the layer said hello
    std::string status;          // frames received, dropped, the application's state (the status bar)
    std::string frame;           // which application frame is shown, its latency
    std::vector<std::string> reports;  // what the layer said (a target never drawn, a format mismatch)
    std::string passes, draft;   // --suggest: the layer's report of one frame's passes, the layout drafted from it
    std::vector<std::string> summary;  // what was found and what was left out (shown wrapped: sources end the lines)
    // ... and each drafted quantity's verdict for the table: target, channels, quantity ("unknown" when
    // the evidence did not decide), confidence, the evidence.
    struct Verdict {
      std::string target, channels, quantity, confidence, evidence;
    };
    std::vector<Verdict> verdicts;
    bool draftStreamed = false;  // the stream is decoded with that draft (attach --suggest without a layout)
    bool saveDraftRequested = false;  // ctrl+S or the window's button: ./gblens-layout-<date>-<time>.json
    std::string draftStatus;     // where it was saved, or why not
  } attach;

  // ---- a sequence (gblens view SEQ): the timeline strip (views/ui/timeline_panel.cpp) and the probe's
  // track across its frames (views/analysis/probe_track.h, drawn by views/ui/track_panel.cpp) ----
  struct TimelineUi {
    bool on = false;                          // the frames are a sequence's (source is Capture)
    std::string dir;                          // the sequence's folder
    std::vector<int64_t> numbers;             // each frame's number (the N of SEQ@N)
    std::vector<std::optional<double>> times; // each frame's time (seconds), when the sequence says
    int shown = 0;                            // index of the frame shown
    int requested = -1;                       // the strip or a key asks for this frame (-1: none)
    bool playing = false;
    double fps = 30.0;                        // the sequence's rate: from the frames' times, else 30
    bool fpsFromTimes = false;
    size_t cached = 0, cacheLimit = 0;        // frames in memory now, at most
    std::string status;                       // why a frame could not be shown ("" none)
    // An attached stream's kept frames (attach --history K, app/viewer/live_timeline.cpp): the numbers
    // are the application's frames, the times seconds from the newest kept frame's end, cacheLimit K.
    // While the stream runs (ViewerModel::playing) the strip sits on its newest frame; stepping or the
    // slider freezes it, Space or the strip's Live button returns to the stream's newest frame.
    bool history = false;
    size_t historyBytes = 0;                  // the kept frames' texels
    // The temporal views (app/viewer/temporal_views.cpp): the motion check of the pair ending at the
    // frame shown (its maps: the views "Motion error" and "Motion class") and the flicker of a view
    // over the whole sequence ("Flicker stddev", "Flicker max step"); the strip's second row.
    std::string motionLine;                   // the pair's verdict in words ("" : no motion quantity)
    bool motionComputing = false;
    std::string flickerOf;                    // the view the Flicker button runs on ("" : none can)
    bool flickerRequested = false;            // the button or F
    bool flickerComputing = false;
    std::string flickerLine;                  // what the last flicker found, or why there is none
  } timeline;
  std::optional<ProbeTrack> track;            // the probed point across the sequence (none: not probed)
  // Views of classes (quantity -1, Visual::Id; the motion check's class map): each value's name, in
  // the legend (a swatch per class) and the hover.
  std::map<std::string, std::vector<std::string>> classNames;

  // Set by the panels when anything changed that needs another interface frame.
  bool uiChanged = false;
};

// The frame on screen was rendered with `rendered`; the viewer renders again when the options it
// wants now differ in anything (every member of RenderOptions).
inline bool frameOutdated(const RenderOptions& rendered, const RenderOptions& wanted) { return !(rendered == wanted); }

// Sets the views of the frame shown; settings of views of the same name are kept, the rest default.
void setViews(ViewerModel& m, std::vector<ViewDef> views);

// Image size a view shows (the shadow map has its own): the full frame's size, also while a
// reduced frame stands in for it (texel coordinates, marks and probes stay full-resolution).
glm::uvec2 viewImageSize(const ViewerModel& m, int view);

// The whole interface for one ImGui frame: menu bar, panels, and the view area, whose views are
// emitted as ImDrawList callbacks to `callback` with `draws[i]` as user data index i.
void drawViewerUi(ViewerModel& m, ViewDrawCallback callback, std::vector<ViewDraw>& draws);

// The view area's rectangle for the current window size and panels (the app renders at its size).
Rect viewArea(const ViewerModel& m, double windowWidth, double windowHeight);

// The views of the grid: every view the frame can show now (none unavailable), in table order.
std::vector<int> gridViews(const ViewerModel& m);
// Which views are on screen now.
std::vector<int> visibleViews(const ViewerModel& m);

// Each view on screen with its rectangle and which frame it shows (compare: A, B, |A - B|).
struct ViewSlot {
  int view = 0;
  FrameSide side = FrameSide::A;
  Rect rect;
  bool split = false;
};
std::vector<ViewSlot> viewSlots(const ViewerModel& m, const Rect& area);
// The part of a slot its image is placed in: the slot less the strip below it that holds its legend
// (views never draw a legend over the picture). Needs an ImGui frame (text sizes).
Rect imageRectOf(const ViewerModel& m, const ViewSlot& s);

// The timeline's step: asks for the frame `delta` away from the one shown (clamped), pauses playing.
void stepTimeline(ViewerModel& m, int delta);
// V in a sequence: the view "Motion error" alone, and from it "Motion class"; false when there is none.
bool cycleMotionViews(ViewerModel& m);

// Keyboard shortcuts: 1 grid, 0 / Return the first view, 2..9 the next ones (view_table.h keys).
// Returns true if handled.
bool applyViewKey(ViewerModel& m, int digit);

// "Zoom to marks": every view (linked) frames the pixels the clicked shadow-map texel marks; false
// when none are marked.
bool zoomToShadowMarks(ViewerModel& m);

}  // namespace gb
