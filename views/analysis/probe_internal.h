// The probe's parts that live in their own files (probe.cpp assembles the dossier).
#pragma once
#include "renderer/core/snapshot.h"
#include "views/analysis/probe.h"

namespace gb {

// Every quantity of the layout decoded at (x, y) (probe_decode.cpp).
void decodeQuantities(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d);
// Every position the layout allows at (x, y), with the difference to a stored one (probe_decode.cpp).
void reconstructAll(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d);
// The light ledger of a pixel with a surface at eye-space P (probe_ledger.cpp); needs d's decoded
// G-buffer, its shadow lookup and its drawn lights (probeLights) first.
LightLedger lightLedger(const FrameSnapshot& f, uint32_t x, uint32_t y, const glm::dvec3& P, const PixelDossier& d);

}  // namespace gb
