// The probe's parts that live in their own files (probe.cpp assembles the dossier).
#pragma once
#include "renderer/core/snapshot.h"
#include "views/analysis/probe.h"

namespace gb {

// Every quantity of the layout decoded at (x, y) (probe_decode.cpp).
void decodeQuantities(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d);
// Every position the layout allows at (x, y), with the difference to a stored one (probe_decode.cpp).
void reconstructAll(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d);

}  // namespace gb
