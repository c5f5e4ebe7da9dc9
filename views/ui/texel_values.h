// Values printed inside texels at high zoom (tev's and RenderDoc's pixel values): drawn over a view
// slot by view_panel.cpp from ViewerModel::texelValue, recorded in ViewerModel::texelValuesDrawn.
#pragma once
#include "views/ui/view_layout.h"
#include "views/ui/viewer_model.h"

namespace gb {

// Prints each visible texel's value lines in view `view`'s slot `r` (placement `pl`, its range for
// the text's contrast) when every one of them fits inside its texel; nothing otherwise.
void drawTexelValues(ViewerModel& m, int view, FrameSide side, const Rect& r, const Placement& pl,
                     const ResolvedRange& range);

}  // namespace gb
