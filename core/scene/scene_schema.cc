// The whole scene file: its sections and "time" (docs/scene-reference.md).
#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

const Schema<Scene>& scene_schema() {
  using S = Scene;
  static const Schema<S> schema({
      section_field("camera", &S::camera, camera_schema(), {"", "the view"}),
      section_field("viewport", &S::viewport, viewport_schema(), {"", "the image"}),
      section_field("grid", &S::grid, grid_schema(), {"", "the projected grid (§4.1)"}),
      section_field("terrain", &S::terrain, terrain_schema(), {"", "the height field (§2, §3)"}),
      section_field("shading", &S::shading, shading_schema(),
                    {"", "the proto-texture layers (§4.2)"}),
      section_field("lighting", &S::lighting, lighting_schema(), {"", "sun, sky and ambient"}),
      section_field("water", &S::water, water_schema(), {"", "§4.3's water"}),
      section_field("sky", &S::sky, sky_schema(), {"", "the background and fog"}),
      number_field("time", &S::time, Range{-limits::kMaxTime, limits::kMaxTime},
                   {"seconds", "animates the water's waves"}),
      section_field("output", &S::output, output_schema(), {"", "the files written"}),
  });
  return schema;
}

}  // namespace relief
