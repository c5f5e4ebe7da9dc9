// gblens attach without the viewer (cmd_attach.cpp runs it): the next streamed frame or why none
// will come, what a capture of one records, and --capture-frames A..B, the application's frames A to
// B written as one sequence (views/capture/sequence.h; docs/attach.md "A sequence of frames").
#pragma once
#include <string>

#include "app/cli/attach_args.h"
#include "views/capture/capture.h"
#include "views/live/live.h"

namespace gb {

std::string attachAppText(const AttachOptions& o);  // the application and its arguments, as one line
// What a capture of the application's frame `appFrame` records beside its texels.
CaptureMeta attachMeta(const AttachOptions& o, const LiveSession& s, uint64_t appFrame);
// The targets `frame` holds (name, format, size, where each came from) and those absent, a line each.
std::string attachTargetsText(const FrameSnapshot& frame, const LiveFrameInfo& info);

// The next streamed frame (the layer's reports printed as they come). False with `why` when none
// will come: nothing matched the layout, the application ended (before its frame `wanted`, when
// >= 0) or --timeout seconds went by without a frame.
bool nextAttachFrame(const AttachOptions& o, LiveSession& s, FrameSnapshot& frame, LiveFrameInfo& info, int64_t wanted,
                     std::string& why);

// --capture-frames: the frames lo.captureFrame..lo.captureLast, each decoded as --capture-frame
// decodes one, written with writeSequence: 0 when every one came, one after the other; 2 with
// `why` (nothing at -o) when one never came, or the stream skipped one (the gap named).
int captureAttachSequence(const AttachOptions& o, const LiveOptions& lo, LiveSession& s, std::string& why);

}  // namespace gb
