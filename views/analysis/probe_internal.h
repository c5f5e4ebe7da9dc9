// The probe's parts that live in their own files (probe.cpp assembles the dossier).
#pragma once
#include "renderer/core/snapshot.h"
#include "views/analysis/probe.h"

namespace gb {

// Every quantity of the layout decoded at (x, y) (probe_decode.cpp).
void decodeQuantities(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d);
// Every position the layout allows at (x, y), with the difference to a stored one (probe_decode.cpp).
void reconstructAll(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d);
// The G-buffer as the lighting passes read it at (x, y): false where there is no surface (or the
// layout lacks albedo or normal) (probe.cpp).
struct LightingInputs {
  glm::dvec3 albedo{0.0}, normal{0.0}, P{0.0};
  double specular = 0.0, shadow = 1.0;
  bool unlit = false;
};
bool lightingInputs(const FrameSnapshot& f, uint32_t x, uint32_t y, LightingInputs& in);
// Why lights cannot be evaluated for this frame's layout ("" when they can) (probe.cpp).
std::string lightingNotEvaluated(const FrameSnapshot& f);
// The light ledger of a pixel with a surface at eye-space P (probe_ledger.cpp); needs d's decoded
// G-buffer, its shadow lookup and its drawn lights (probeLights) first.
LightLedger lightLedger(const FrameSnapshot& f, uint32_t x, uint32_t y, const glm::dvec3& P, const PixelDossier& d);

}  // namespace gb
