// What a frame leaves out because its scene does not need it (docs/stages.md, "Skipped work"),
// each decided once per frame from the plan and from what the earlier stages found. Every skip
// is on by default; a test turns one off to prove that the image does not change by a bit while
// the work counters drop (tests/pipeline/skip_test.cc).
#pragma once

#include "core/stage_params.h"

namespace relief {

struct FrameSkips {
  bool invalid_vertices = true;  // stages 3-5: nothing at invalid and padding vertices
  bool unseen_vertices = true;   // stages 3-5: nothing at vertices no visible triangle needs
  bool unused_octaves = true;    // stage 3: octaves above the frame's largest nu not in the table
  bool empty_tiles = true;       // tiles: no raster and resolve where no triangle is binned
  bool water = true;             // no water depth, and none resolved, with no terrain under water
  bool fog = true;               // no fog pass when its density is 0
  bool dither = true;            // no dithering noise when its amount is 0
  bool specular = true;          // no specular term where its weight is 0
  bool zero_weights = true;      // no texture fetch for a layer or projection of zero weight
  bool lit_shadows = true;       // no share of the sun disc evaluated where four samples prove it
  bool unread_shadow_levels = true;  // no cache level that no drawn pixel can read
  bool occluded_tiles = true;        // GeoMipMapping: no tile hidden behind nearer ground's floors
};

// Stage 8's share of the skips: the plan's parameters have them all on (make_shade_params);
// a skip turned off puts the work back. `water_in_view`: some drawn vertex lies below the water
// level (the backend knows after stage 3).
template <class Real>
void apply_skips(const FrameSkips& skips, bool water_in_view, ShadeParams<Real>& p) {
  p.terrain_water = p.water_enabled && water_in_view ? 1 : 0;
  p.fog_enabled = p.fog_enabled || !skips.fog ? 1 : 0;
  p.dither_enabled = p.dither_enabled || !skips.dither ? 1 : 0;
  p.always_specular = skips.specular ? 0 : 1;
  p.skip_zero_weights = skips.zero_weights ? 1 : 0;
}

}  // namespace relief
