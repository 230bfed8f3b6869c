// The built-in material layers: the alpine look of the default scene (sand at the shore,
// grass on gentle slopes, rock on steep ones, snow high up, the bed under water), covering
// every (height, slope) so that the weights never all vanish.
#include "core/scene/scene.h"

namespace relief {

ShadingSettings Scene::default_shading() {
  ShadingSettings shading;
  MaterialLayer bed;
  bed.name = "bed";
  bed.texture = "builtin:bed";
  bed.tile_size = 30.0;
  bed.height = {-1e7, -1.0};
  bed.height_relative_to_water = true;
  bed.height_spread = 2.0;

  MaterialLayer sand;
  sand.name = "sand";
  sand.texture = "builtin:sand";
  sand.tile_size = 24.0;
  sand.height = {-4.0, 7.0};
  sand.height_relative_to_water = true;
  sand.slope_deg = {0.0, 30.0};
  sand.height_spread = 3.0;
  sand.specular = 0.05;

  MaterialLayer grass;
  grass.name = "grass";
  grass.texture = "builtin:grass";
  grass.tile_size = 36.0;
  grass.height = {30.0, 560.0};
  grass.slope_deg = {0.0, 38.0};
  grass.height_spread = 25.0;
  grass.slope_spread_deg = 5.0;

  MaterialLayer rock;
  rock.name = "rock";
  rock.texture = "builtin:rock";
  rock.tile_size = 60.0;
  rock.slope_deg = {32.0, 90.0};
  rock.slope_spread_deg = 5.0;
  rock.specular = 0.02;

  MaterialLayer snow;
  snow.name = "snow";
  snow.texture = "builtin:snow";
  snow.tile_size = 50.0;
  snow.height = {520.0, 1e7};
  snow.slope_deg = {0.0, 40.0};
  snow.height_spread = 70.0;
  snow.slope_spread_deg = 6.0;
  snow.specular = 0.35;

  shading.layers = {bed, sand, grass, rock, snow};
  return shading;
}

}  // namespace relief
