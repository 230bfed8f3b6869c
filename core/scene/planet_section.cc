// terrain.planet (§4.1's spherical domain, docs/planet.md): its fields and its rules across
// fields.
#include <cmath>
#include <optional>
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

constexpr Range kPlanetLength{0.0, limits::kMaxPlanetLength};

// 0 (the plane) or kMinPlanetRadius to kMaxPlanetRadius.
Field<PlanetSettings> radius_field() {
  Field<PlanetSettings> field =
      number_field("radius", &PlanetSettings::radius, Range{0.0, limits::kMaxPlanetRadius},
                   {"world units", "the datum sphere's radius; 0: the plane",
                    "0, or ≥ 1000 (a smaller planet is smaller than a mountain range)"});
  field.read = [](const LayerContext& cx, const json& v, const std::string& p, PlanetSettings& s) {
    s.radius = cx.in.number(v, p, Range{0.0, limits::kMaxPlanetRadius});
    if (s.radius != 0.0 && s.radius < limits::kMinPlanetRadius) {
      cx.in.fail(p, p + " = " + brief(v) + " is out of range; allowed 0 (the plane) or " +
                        format_number(limits::kMinPlanetRadius) + " <= " + p +
                        " <= " + format_number(limits::kMaxPlanetRadius));
    }
  };
  return field;
}

// The equal-angle band [begin, end): a pair written as an object.
const Schema<Vec2d>& band_schema() {
  auto end_of_band = [](std::size_t index, const char* key, std::string_view meaning) {
    return Field<Vec2d>{
        {key, range_text(kPlanetLength), {"world units", meaning}},
        [index](const LayerContext& cx, const json& v, const std::string& p, Vec2d& band) {
          band[index] = cx.in.number(v, p, kPlanetLength);
        },
        [index](const Vec2d& band) -> std::optional<json> { return json(band[index]); }};
  };
  static const Schema<Vec2d> schema(
      {
          end_of_band(0, "begin", "altitude where the blend starts"),
          end_of_band(1, "end", "altitude where sampling is all equal-angle"),
      },
      {}, Vec2d{0.0, 1.0});
  return schema;
}

// null removes the band; an object patches it (a new one starts from [0, 1]).
Field<PlanetSettings> equal_angle_field() {
  return {{"equal_angle",
           "`null` or an object",
           {"",
            "the camera altitudes (above base_height) over which the projected grid on the "
            "sphere blends into equal-angle sampling; `null`: the projected grid always",
            "begin < end"},
           {},
           &band_schema()},
          [](const LayerContext& cx, const json& v, const std::string& p, PlanetSettings& s) {
            if (v.is_null()) {
              s.equal_angle.reset();
              return;
            }
            Vec2d band = s.equal_angle.value_or(band_schema().prototype());
            band_schema().apply(cx, v, p, band);
            if (!(band[0] < band[1])) {
              cx.in.fail(p, p + " = {\"begin\": " + format_number(band[0]) + ", \"end\": " +
                                format_number(band[1]) + "} is empty; allowed begin < end");
            }
            s.equal_angle = band;
          },
          [](const PlanetSettings& s) -> std::optional<json> {
            return s.equal_angle ? band_schema().write(*s.equal_angle) : json(nullptr);
          }};
}

}  // namespace

const Schema<PlanetSettings>& planet_schema() {
  static const Schema<PlanetSettings> schema({
      radius_field(),
      number_field("horizon", &PlanetSettings::horizon, kPlanetLength,
                   {"world units",
                    "artificial horizon, an arc length along the datum; 0: the "
                    "geometric one"}),
      equal_angle_field(),
  });
  return schema;
}

void validate_planet(const Scene& scene) {
  const TerrainSettings& t = scene.terrain;
  if (!t.planet || t.planet->radius == 0.0) {
    return;
  }
  const double radius = t.planet->radius;
  // The horizon cache's rows are straight lines along the sun's azimuth on the plane; on a
  // sphere the sun's direction turns from point to point (docs/stages.md, "Cast shadows").
  if (scene.lighting.shadows) {
    throw SceneError("lighting.shadows",
                     "scene: lighting.shadows = true on a planet (terrain.planet.radius = " +
                         format_number(radius) +
                         "): cast shadows are built for the plane only; allowed false here");
  }
  // Sky light reads the same cache (docs/stages.md, "Sky light").
  if (scene.lighting.sky_occlusion) {
    throw SceneError("lighting.sky_occlusion",
                     "scene: lighting.sky_occlusion = true on a planet (terrain.planet.radius = " +
                         format_number(radius) +
                         "): sky light is built for the plane only; allowed false here");
  }
  // The reflected rays march over the same cache (docs/stages.md, "Reflections").
  if (scene.water.reflect_terrain && t.water_level) {
    throw SceneError("water.reflect_terrain",
                     "scene: water.reflect_terrain = true on a planet (terrain.planet.radius = " +
                         format_number(radius) +
                         "): reflections are built for the plane only; allowed false here");
  }
  // The atmosphere's closed form integrates over flat ground (core/atmosphere.h); a sphere's
  // shell has none.
  if (scene.sky.atmosphere) {
    throw SceneError("sky.atmosphere",
                     "scene: sky.atmosphere is set on a planet (terrain.planet.radius = " +
                         format_number(radius) +
                         "): the atmosphere is built for the plane only; allowed null here");
  }
  // The cloud layer is a band of heights over the plane (core/clouds.h); a planet's clouds
  // would follow its sphere.
  if (scene.sky.clouds) {
    throw SceneError(
        "sky.clouds",
        "scene: sky.clouds is set on a planet (terrain.planet.radius = " + format_number(radius) +
            "): the cloud layer is built for the plane only; allowed null here");
  }
  // The water sphere's radius R + (water level - base height) must be positive: at or below
  // the centre there is no sphere (its equation would draw one of radius |R + w| instead).
  if (t.water_level && !(radius + (*t.water_level - t.base_height) > 0.0)) {
    throw SceneError("terrain.water_level",
                     "scene: terrain.water_level = " + format_number(*t.water_level) +
                         " puts the water sphere at or past the planet's centre (" +
                         format_number(*t.water_level - t.base_height) +
                         " below the datum of terrain.planet.radius = " + format_number(radius) +
                         "); allowed terrain.water_level > " +
                         format_number(t.base_height - radius) + ", or null (no water)");
  }
  // The farthest arc offset stage 2 may give a vertex is kMaxPlanetAngle R: its coarsest
  // lattice coordinate must stay where float holds every cell (as camera.far's footprint).
  // Stage 3's cell and period: horizontal_scale and lattice_size, or with basis images
  // tile_size / P and P for the largest P any image can give (P is known only once they are
  // read; a smaller P gives a larger cell), as validate_basis takes them.
  const double period = t.basis ? double(limits::kMaxLatticeSize) : double(t.lattice_size);
  const double cell = t.basis ? t.basis->tile_size / period : t.horizontal_scale;
  const char* cell_fields =
      t.basis ? "terrain.basis.tile_size" : "terrain.horizontal_scale, terrain.lattice_size";
  const double farthest = limits::kMaxPlanetAngle * radius;
  const double coordinate = std::pow(t.r, t.first_octave) * farthest / cell + period;
  if (coordinate > limits::kMaxLatticeCoordinate) {
    throw SceneError(
        "terrain.planet.radius",
        "scene: terrain.planet.radius = " + format_number(t.planet->radius) +
            " puts the far side of the planet (" + format_number(farthest) +
            " units along the surface) at lattice coordinate " +
            format_number(std::round(coordinate)) + " of the coarsest octave, beyond " +
            format_number(limits::kMaxLatticeCoordinate) + "; allowed terrain.planet.radius <= " +
            format_number((limits::kMaxLatticeCoordinate - period) * cell /
                          std::pow(t.r, t.first_octave) / limits::kMaxPlanetAngle) +
            " for this " + cell_fields + ", terrain.r and terrain.first_octave");
  }
}

}  // namespace relief
