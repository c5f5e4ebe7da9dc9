// The viewer's keys and mouse as one table: what each does in which kind of session. The key handler
// (app/viewer/controls.cpp) dispatches through it, Help prints the rows of the session shown, and
// README.md's input table is `gblens view --keys` (tests/cli/test_keys.cpp compares them).
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace gb {

// Kinds of session a row applies to (bits). A sequence (gblens view SEQ) is a capture session with a
// timeline: keySession gives it kCapture | kSequence, so the capture rows apply there too.
// An attached stream with kept frames (attach --history K) is an attach session with a timeline:
// kAttach | kHistory (Space still freezes the stream; `,` and `.` step through the kept frames).
enum KeySession : unsigned { kLive = 1, kCapture = 2, kCompare = 4, kAttach = 8, kSequence = 16, kEverywhere = 31, kHistory = 32 };

// What a key does (the handler's switch); Mouse rows are described only.
enum class KeyAction {
  Quit, SaveDraft, Grid, FirstView, ViewKey, FlipCompare, PlayPause, PauseStream, CancelReference, CaptureShown,
  StepForward, StepBack, ResetCamera, TexelGrid, Fit, MoveProbe, MoveCamera, CompareSwipe, CompareDifference,
  CompareFlip, CompareRow, ZoomToMarks, NextSample, NextFrame, PreviousFrame, PlaySequence, MotionViews,
  FlickerView, Mouse
};

struct KeyBinding {
  const char* keys;   // as a person reads them: "Space", "ctrl+Q", "2..9", "left drag"
  KeyAction action;
  unsigned sessions;  // KeySession bits
  const char* does;
};

struct ViewerModel;
// The kind of session the viewer shows (what Help lists and the handler dispatches for).
unsigned keySession(const ViewerModel& m);

// Every row, in the order Help and the README show them.
const std::vector<KeyBinding>& keyBindings();

// The action of a key in a session: `key` is the name the table uses for one key ("Space", "G",
// "Return", "5", "Left"), `ctrl` whether ctrl is held. Nothing when the key does nothing there.
std::optional<KeyAction> keyAction(const std::string& key, bool ctrl, unsigned session);

// Every row as the README's Markdown table (input | sessions | does).
std::string keysMarkdown();

}  // namespace gb
