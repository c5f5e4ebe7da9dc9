// Views of any G-buffer: a frame whose layout is not gblens's own is decoded, quantity by quantity,
// into gblens's targets (colours linear, normals unit in eye space, eye depth, hardware depth from
// it) so that every examination view, the viewer's GPU mapping and previews show it unchanged. The
// probe and compare keep reading the frame itself, through its own layout.
#pragma once
#include <string>

#include "renderer/core/snapshot.h"

namespace gb {

// Whether the frame's layout is gblens's own G-buffer (under its options).
bool nativeFrame(const FrameSnapshot& f);

// The frame as gblens's targets: a copy of `f` when it is native; else a snapshot in gblens's
// layout under decoding-friendly options (rgba16f normals, eye depth, d32s8, rgba32f hdr, stored
// position) whose targets hold the decoded quantities; a target no quantity fills is absent as
// Absent::NotInLayout.
FrameSnapshot viewableFrame(const FrameSnapshot& f);

}  // namespace gb
