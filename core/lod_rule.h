// §4.1's octave count from a squared vertex spacing, nu = clamp(c0 - c1 log2(sigma^2), 1,
// nu_max): the one form stage 2 (projected_domain_rows.h), the ground truth's distance rule
// (eval/distance_lod.h) and the shadows' cache levels (sun_horizons.h) share. The constants
// are a LodPlan's (frame_plan.h) or a DistanceLod's, in the caller's precision.
#pragma once

#include <algorithm>

#include "core/det_math.h"

namespace relief {

// nu_max where spacing_sq <= min_spacing_sq (log2_det's domain is x > 0: spacings below the
// guard take every octave).
template <class Real>
Real lod_octave_count(Real c0, Real c1, Real nu_max, Real min_spacing_sq, Real spacing_sq) {
  if (!(spacing_sq > min_spacing_sq)) {
    return nu_max;
  }
  return std::clamp(c0 - c1 * log2_det(spacing_sq), Real(1), nu_max);
}

}  // namespace relief
