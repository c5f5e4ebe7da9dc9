// The table of error maps (error.h errorMaps): one name and legend per map, for gblens error -o
// and the viewer's "Reference error" window.
#include "views/analysis/error.h"

namespace gb {

const std::vector<ErrorMapDef>& errorMaps() {
  static const std::vector<ErrorMapDef> maps = {
      {"shadow", "light / dark grey: both lit / both shadowed; yellow: penumbra band (not compared); red: GPU "
                 "shadowed where the sun ray is free (acne); blue: GPU lit where the ray is blocked (leak); dark "
                 "blue-grey: faces away (not compared); magenta: silhouettes",
       shadowErrorImage},
      {"silhouettes", "grey: same triangle; magenta: another triangle; red: only the GPU has a surface; cyan: only the "
                      "reference; black: sky",
       silhouetteImage},
      {"normal", "angle to the reference's normal, log scale 1e-4 (blue) .. 1 degree (red); black: none", normalErrorImage},
      {"hdr", "relative error of the final HDR colour, log scale 1e-5 (blue) .. 1 (red)", hdrErrorImage},
      {"position", "|P - P_ref| / eye depth from the eye-depth target, log scale 1e-8 (blue) .. 1e-4 (red)",
       positionErrorImage},
      {"lighting", "the lighting passes alone, error per light contribution, log scale 1e-8 (blue) .. 1e-4 (red)",
       lightingErrorImage},
  };
  return maps;
}

}  // namespace gb
