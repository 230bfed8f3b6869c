// The built-in material layers: the alpine look of the default scene (sand at the shore,
// grass on gentle slopes, rock on steep ones, snow high up, the bed under water), covering
// every (height, slope) so that the weights never all vanish. Fields not named keep
// MaterialLayer's defaults (scene.h).
#include "core/scene/scene.h"

namespace relief {

ShadingSettings Scene::default_shading() {
  ShadingSettings shading;
  shading.layers = {
      {.name = "bed",
       .texture = "builtin:bed",
       .tile_size = 30.0,
       .height = {-1e7, -1.0},
       .height_relative_to_water = true,
       .height_spread = 2.0},
      {.name = "sand",
       .texture = "builtin:sand",
       .tile_size = 24.0,
       .height = {-4.0, 7.0},
       .height_relative_to_water = true,
       .slope_deg = {0.0, 30.0},
       .height_spread = 3.0,
       .specular = 0.05},
      {.name = "grass",
       .texture = "builtin:grass",
       .tile_size = 36.0,
       .height = {30.0, 560.0},
       .slope_deg = {0.0, 38.0},
       .height_spread = 25.0,
       .slope_spread_deg = 5.0},
      {.name = "rock",
       .texture = "builtin:rock",
       .tile_size = 60.0,
       .slope_deg = {32.0, 90.0},
       .slope_spread_deg = 5.0,
       .specular = 0.02},
      {.name = "snow",
       .texture = "builtin:snow",
       .tile_size = 50.0,
       .height = {520.0, 1e7},
       .slope_deg = {0.0, 40.0},
       .height_spread = 70.0,
       .slope_spread_deg = 6.0,
       .specular = 0.35},
  };
  // castledragmire's height-to-colour table (heights on a 0 to 1 scale): 0 to 1/8 blue, dark
  // to light; 1/8 to 4/8 green, light to dark; 4/8 to 7/8 brown, light to dark; 7/8 to 1
  // white, dark to light. Each band's ends are the two stops of its ramp; the bands meet in
  // steps (two stops at one height). Linear RGB.
  shading.gradient.stops = {
      {0.0, {0.010, 0.030, 0.180}},   {0.125, {0.060, 0.200, 0.550}},
      {0.125, {0.180, 0.420, 0.080}}, {0.5, {0.040, 0.150, 0.025}},
      {0.5, {0.330, 0.220, 0.110}},   {0.875, {0.110, 0.065, 0.030}},
      {0.875, {0.560, 0.560, 0.580}}, {1.0, {0.950, 0.950, 0.970}},
  };
  return shading;
}

}  // namespace relief
