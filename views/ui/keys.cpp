// The viewer's key and mouse table (keys.h): the one place a binding is written.
#include "views/ui/keys.h"

#include <cstring>

#include "views/ui/viewer_model.h"

namespace gb {

unsigned keySession(const ViewerModel& m) {
  if (m.attach.on) return m.timeline.on && m.timeline.history ? kAttach | kHistory : kAttach;
  if (m.timeline.on && m.source == FrameSource::Capture) return kCapture | kSequence;
  return m.source == FrameSource::Compare ? kCompare : m.attach.on ? kAttach : m.source == FrameSource::Live ? kLive : kCapture;
}

const std::vector<KeyBinding>& keyBindings() {
  using A = KeyAction;
  static const std::vector<KeyBinding> table = {
      {"1", A::Grid, kEverywhere, "every view at once (grid; cells keep the images' aspect)"},
      {"0, Return", A::FirstView, kEverywhere, "the first colour view alone (gblens: final)"},
      {"2..9", A::ViewKey, kEverywhere,
       "the frame's next views in layout order (gblens: albedo, normal, depth, specular, shadow, shadow map, "
       "coverage); the View menu has every view, those without a key too"},
      {"Space", A::PlayPause, kLive, "play / pause the animation"},
      {"Space", A::FlipCompare, kCompare, "flip A and B in place (the same zoom and pan)"},
      {"Space", A::PauseStream, kAttach,
       "pause the stream (the application runs on); with --history K the strip then steps through the kept frames, "
       "Space again returns to the newest"},
      {"Space", A::PlaySequence, kSequence, "play / pause the sequence at its rate (from the frames' times, else 30 fps)"},
      {"S", A::CompareSwipe, kCompare, "swipe: A left of the mouse, B right of it"},
      {"D", A::CompareDifference, kCompare, "|A - B| of every view shown"},
      {"F", A::CompareFlip, kCompare, "FLIP of the colour views (others: |A - B|)"},
      {"R", A::CompareRow, kCompare, "A, B and |A - B| side by side"},
      {"C", A::CaptureShown, kAttach, "capture the frame shown"},
      {"ctrl+S", A::SaveDraft, kAttach, "save the suggested layout (attach --suggest)"},
      {".", A::StepForward, kLive, "step the animation forward"},
      {",", A::StepBack, kLive, "step the animation back"},
      {".", A::NextFrame, kSequence, "the sequence's next frame (the view, zoom and probe stay; the probe follows its point)"},
      {",", A::PreviousFrame, kSequence, "the sequence's previous frame"},
      {".", A::NextFrame, kHistory, "the next kept frame (freezes the stream; the probe follows its point)"},
      {",", A::PreviousFrame, kHistory, "the previous kept frame (freezes the stream)"},
      {"V", A::MotionViews, kSequence,
       "the motion check of the pair ending at the frame shown: the Motion error view (again: Motion class); the verdict "
       "is in the strip"},
      {"F", A::FlickerView, kSequence,
       "flicker of the view shown over the whole sequence, at the frame shown's pixels: views Flicker stddev and "
       "Flicker max step"},
      {"Home", A::ResetCamera, kLive, "reset the camera"},
      {"Escape", A::CancelReference, kLive, "cancel the reference error's computation"},
      {"G", A::TexelGrid, kEverywhere, "texel grid on / off (zoomed in: values in texels)"},
      {"Z", A::Fit, kEverywhere, "fit the views (undo zoom and pan)"},
      {"X", A::NextSample, kCapture | kAttach,
       "multisampled targets: show their next sample (after the last, sample 0 again); each has a spread view"},
      {"M", A::ZoomToMarks, kEverywhere, "zoom to the pixels a clicked shadow-map texel marks"},
      {"arrows", A::MoveProbe, kEverywhere, "move the probed pixel"},
      {"W A S D Q E", A::MoveCamera, kLive, "move the camera while held (shift: faster)"},
      {"ctrl+Q", A::Quit, kEverywhere, "quit"},
      {"left click", A::Mouse, kEverywhere, "probe a pixel: its dossier in the Pixel panel (as gblens probe)"},
      {"ctrl + left drag", A::Mouse, kEverywhere, "a region's statistics and histogram (as gblens stats)"},
      {"click on the shadow map", A::Mouse, kEverywhere, "mark the screen pixels whose shadow lookup reads that texel (M zooms to them)"},
      {"wheel", A::Mouse, kEverywhere, "zoom about the mouse, every view alike"},
      {"middle drag, shift + drag", A::Mouse, kEverywhere, "pan, every view alike"},
      {"mouse over a swipe", A::Mouse, kCompare, "the swipe follows the mouse: A left of it, B right of it, each labelled"},
      {"right drag", A::Mouse, kLive, "orbit the camera (fly mode: look)"},
      {"ctrl + wheel", A::Mouse, kLive, "dolly the camera"},
  };
  return table;
}

static bool oneKeyOf(const KeyBinding& b, const std::string& key, bool ctrl) {
  const std::string keys = b.keys;
  if (keys.rfind("ctrl+", 0) == 0) return ctrl && keys.substr(5) == key;
  if (ctrl) return false;
  if (b.action == KeyAction::ViewKey) return key.size() == 1 && key[0] >= '2' && key[0] <= '9';
  if (b.action == KeyAction::FirstView) return key == "0" || key == "Return";
  if (b.action == KeyAction::MoveProbe) return key == "Left" || key == "Right" || key == "Up" || key == "Down";
  return keys == key;
}

std::optional<KeyAction> keyAction(const std::string& key, bool ctrl, unsigned session) {
  for (const KeyBinding& b : keyBindings())
    if (b.action != KeyAction::Mouse && b.action != KeyAction::MoveCamera && (b.sessions & session) && oneKeyOf(b, key, ctrl))
      return b.action;
  return std::nullopt;
}

std::string keysMarkdown() {
  static const std::pair<unsigned, const char*> kNames[] = {
      {kLive, "live"}, {kCapture, "capture"}, {kCompare, "compare"}, {kAttach, "attach"}, {kSequence, "sequence"}, {kHistory, "attach --history"}};
  std::string out = "| input | in | does |\n| --- | --- | --- |\n";
  for (const KeyBinding& b : keyBindings()) {
    std::string in;
    if (b.sessions == kEverywhere) in = "every session";
    else
      for (const auto& [bit, name] : kNames)
        if (b.sessions & bit) in += (in.empty() ? "" : ", ") + std::string(name);
    out += "| `" + std::string(b.keys) + "` | " + in + " | " + b.does + " |\n";
  }
  return out;
}

}  // namespace gb
