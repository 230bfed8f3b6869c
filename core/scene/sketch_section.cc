// terrain.sketch (§3's low-frequency base, core/height_sketch.h): its fields. Whether the image
// can be read is checked when it is loaded (pipeline/scene_resources.h).
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

// [x0, z0, x1, z1] with each side at least kMinSketchSpan long.
Field<SketchSettings> extent_field() {
  const Range coordinate{-limits::kMaxCameraCoordinate, limits::kMaxCameraCoordinate};
  Field<SketchSettings> field =
      vector_field("extent", &SketchSettings::extent, coordinate,
                   {"world units",
                    "[x0, z0, x1, z1]: the rectangle the image covers; outside it the edge "
                    "texels extend (no tiling)",
                    "x1 − x0 and z1 − z0 ≥ 1e−3"});
  field.read = [coordinate](const LayerContext& cx, const json& v, const std::string& p,
                            SketchSettings& s) {
    s.extent = cx.in.vector<4>(v, p, coordinate);
    const auto& e = s.extent;
    if (!(e[2] - e[0] >= limits::kMinSketchSpan && e[3] - e[1] >= limits::kMinSketchSpan)) {
      cx.in.fail(p, p + " = " + brief(v) +
                        " is empty or too thin; allowed [x0, z0, x1, z1] with x1 - x0 and z1 - z0 "
                        "at least " +
                        format_number(limits::kMinSketchSpan));
    }
  };
  return field;
}

}  // namespace

const Schema<SketchSettings>& sketch_schema() {
  using S = SketchSettings;
  static const Schema<S> schema({
      input_file_field("image", &S::image,
                       {"", "the heights; row 0 at z0 (a map with north, −z, up)",
                        "NAME `island`; the PNG: one grey channel, 8 or 16 bits, 2…4096 texels "
                        "a side"}),
      extent_field(),
      increasing_pair_field("height", &S::height,
                            Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight},
                            {"world units", "world heights of black and of white"}),
  });
  return schema;
}

}  // namespace relief
