// terrain.sketch (§3's low-frequency base, core/height_sketch.h) and terrain.heightfield (a
// finite height field as the terrain, sampled the same way): their fields. Whether the file can
// be read is checked when it is loaded (pipeline/scene_resources.h).
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

// [x0, z0, x1, z1] with each side at least kMinSketchSpan long.
template <class S>
Field<S> extent_field() {
  const Range coordinate{-limits::kMaxCameraCoordinate, limits::kMaxCameraCoordinate};
  Field<S> field =
      vector_field<S, 4>("extent", &S::extent, coordinate,
                         {"world units",
                          "[x0, z0, x1, z1]: the rectangle the image covers; outside it the edge "
                          "texels extend (no tiling)",
                          "x1 − x0 and z1 − z0 ≥ 1e−3"});
  field.read = [coordinate](const LayerContext& cx, const json& v, const std::string& p, S& s) {
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

// terrain.heightfield.file: a path only (no built-in field ships).
Field<HeightFieldSettings> heightfield_file_field() {
  Field<HeightFieldSettings> field = input_file_field<HeightFieldSettings>(
      "file", &HeightFieldSettings::image,
      {"",
       "the heights; row 0 at z0 (a map with north, −z, up); the format from "
       "the extension",
       "a grey PNG (8 or 16 bits), a one-channel PFM, EXR or TIFF (float), or RAW16 "
       "(.r16, .raw: little-endian, top row first); 2…16385 samples a side"});
  field.info.allowed = "a file path (relative to the scene file)";
  return field;
}

const Schema<GeoMipMapSettings>& geomipmap_schema() {
  using S = GeoMipMapSettings;
  static const Schema<S> schema({
      power_of_two_field<S>("tile_cells", &S::tile_cells, 2, 256,
                            {"cells",
                             "T: lattice cells a tile spans a side; level L keeps every 2^L-th "
                             "vertex (de Boer's GeoMipMapping)"}),
      number_field<S>("pixel_error", &S::pixel_error,
                      Range{limits::kMinGeoMipMapPixelError, limits::kMaxGeoMipMapPixelError},
                      {"pixels",
                       "tau: each tile takes the coarsest level whose geometric error, projected "
                       "from the tile's nearest point, is at most this many pixels"}),
      boolean_field<S>("occlusion", &S::occlusion,
                       {"",
                        "tiles hidden behind nearer ground are not drawn (the image is the same "
                        "bit for bit; a skip, counted in --stats)"}),
  });
  return schema;
}

}  // namespace

const Schema<SketchSettings>& sketch_schema() {
  using S = SketchSettings;
  static const Schema<S> schema({
      input_file_field("image", &S::image,
                       {"", "the heights; row 0 at z0 (a map with north, −z, up)",
                        "NAME `island`; the PNG: one grey channel, 8 or 16 bits, 2…4096 texels "
                        "a side"}),
      extent_field<S>(),
      increasing_pair_field("height", &S::height,
                            Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight},
                            {"world units", "world heights of black and of white"}),
  });
  return schema;
}

const Schema<HeightFieldSettings>& heightfield_schema() {
  using S = HeightFieldSettings;
  static const Schema<S> schema({
      heightfield_file_field(),
      extent_field<S>(),
      increasing_pair_field<S>(
          "height", &S::height, Range{-limits::kMaxBaseHeight, limits::kMaxBaseHeight},
          {"world units",
           "world heights of stored values 0 and 1 (PNG and RAW16 levels divided by their "
           "largest, 255 or 65535; a PFM's floats as they are: [0, 1] keeps them)",
           "every sample's world height within ±1e7"}),
      integer_field<S>("raw_width", &S::raw_width, 0, limits::kMaxHeightFieldSize,
                       {"samples",
                        "RAW16's samples per row; 0: square, the side from the file's size "
                        "(other formats: 0)"}),
      boolean_field<S>("fractal", &S::fractal,
                       {"",
                        "the paper's fractal adds its detail on top (terrain.amplitude and "
                        "the octaves); false: the terrain is base_height plus the field"}),
      boolean_field<S>("level_of_detail", &S::level_of_detail,
                       {"",
                        "without the fractal, each vertex reads the field filtered to its grid "
                        "spacing (levels of detail, geomorphed; terrain.lod.bias finer); false: "
                        "the samples themselves"}),
      boolean_field<S>("interpolating", &S::interpolating,
                       {"",
                        "the surface passes through every sample (point heights: real elevation "
                        "data, a relief export map); false: the smoothing B-spline of the "
                        "samples"}),
      boolean_field<S>("georeferenced", &S::georeferenced,
                       {"",
                        "a GeoTIFF's own placement (projected metres or feet, north up) gives "
                        "the extent, which is then not read"}),
      optional_section_field<S>(
          "geomipmap", &S::geomipmap, geomipmap_schema(), "", "",
          {"",
           "draw the field by GeoMipMapping (tiles at levels of detail, stitched, culled by a "
           "quadtree and by occlusion) instead of the projected grid; null: the projected grid",
           "needs fractal and level_of_detail false, the plane"}),
  });
  return schema;
}

void validate_geomipmap(const Scene& scene) {
  const TerrainSettings& t = scene.terrain;
  const std::string why = " with terrain.heightfield.geomipmap: ";
  if (t.heightfield->fractal) {
    throw SceneError("terrain.heightfield.fractal",
                     "terrain.heightfield.fractal = true" + why +
                         "the mesh's vertices are the field's own surface, with no fractal "
                         "detail to carry; allowed false (or geomipmap null)");
  }
  if (t.heightfield->level_of_detail) {
    throw SceneError("terrain.heightfield.level_of_detail",
                     "terrain.heightfield.level_of_detail = true" + why +
                         "GeoMipMapping chooses its own levels per tile; allowed false");
  }
  if (t.planet && t.planet->radius != 0.0) {
    throw SceneError("terrain.planet.radius",
                     "terrain.planet.radius = " + format_number(t.planet->radius) + why +
                         "a field is flat; allowed 0");
  }
}

}  // namespace relief
