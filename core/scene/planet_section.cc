// terrain.planet (§4.1's spherical domain, docs/planet.md): the field's strict reading and its
// rules across fields.
#include <cmath>
#include <optional>
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"

namespace relief {

void apply_planet(const LayerReader& in, const json& value, const std::string& path,
                  std::optional<PlanetSettings>& planet) {
  if (value.is_null()) {
    planet.reset();
    return;
  }
  PlanetSettings s = planet.value_or(PlanetSettings{});
  const Range length{0.0, limits::kMaxPlanetLength};
  in.object(
      value, path,
      Handlers{
          {"radius",
           [&](const json& v, const std::string& p) {
             s.radius = in.number(v, p, Range{0.0, limits::kMaxPlanetRadius});
             if (s.radius != 0.0 && s.radius < limits::kMinPlanetRadius) {
               in.fail(p, p + " = " + brief(v) + " is out of range; allowed 0 (the plane) or " +
                              format_number(limits::kMinPlanetRadius) + " <= " + p +
                              " <= " + format_number(limits::kMaxPlanetRadius));
             }
           }},
          {"horizon",
           [&](const json& v, const std::string& p) { s.horizon = in.number(v, p, length); }},
          {"equal_angle",
           [&](const json& v, const std::string& p) {
             if (v.is_null()) {
               s.equal_angle.reset();
               return;
             }
             Vec2d band = s.equal_angle.value_or(Vec2d{0.0, 1.0});
             in.object(
                 v, p,
                 Handlers{
                     {"begin", [&](const json& w,
                                   const std::string& q) { band[0] = in.number(w, q, length); }},
                     {"end", [&](const json& w,
                                 const std::string& q) { band[1] = in.number(w, q, length); }},
                 });
             if (!(band[0] < band[1])) {
               in.fail(p, p + " = {\"begin\": " + format_number(band[0]) + ", \"end\": " +
                              format_number(band[1]) + "} is empty; allowed begin < end");
             }
             s.equal_angle = band;
           }},
      });
  planet = s;
}

void validate_planet(const Scene& scene) {
  const TerrainSettings& t = scene.terrain;
  if (!t.planet || t.planet->radius == 0.0) {
    return;
  }
  const double radius = t.planet->radius;
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

json planet_to_json(const PlanetSettings& planet) {
  return {{"radius", planet.radius},
          {"horizon", planet.horizon},
          {"equal_angle", planet.equal_angle ? json{{"begin", (*planet.equal_angle)[0]},
                                                    {"end", (*planet.equal_angle)[1]}}
                                             : json(nullptr)}};
}

}  // namespace relief
