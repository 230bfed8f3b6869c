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
  // The farthest arc offset stage 2 may give a vertex is kMaxPlanetAngle R: its coarsest
  // lattice coordinate must stay where float holds every cell (as camera.far's footprint).
  const double farthest = limits::kMaxPlanetAngle * t.planet->radius;
  const double coordinate =
      std::pow(t.r, t.first_octave) * farthest / t.horizontal_scale + t.lattice_size;
  if (coordinate > limits::kMaxLatticeCoordinate) {
    throw SceneError(
        "terrain.planet.radius",
        "scene: terrain.planet.radius = " + format_number(t.planet->radius) +
            " puts the far side of the planet (" + format_number(farthest) +
            " units along the surface) at lattice coordinate " +
            format_number(std::round(coordinate)) + " of the coarsest octave, beyond " +
            format_number(limits::kMaxLatticeCoordinate) + "; allowed terrain.planet.radius <= " +
            format_number((limits::kMaxLatticeCoordinate - t.lattice_size) * t.horizontal_scale /
                          std::pow(t.r, t.first_octave) / limits::kMaxPlanetAngle) +
            " for this terrain.horizontal_scale, terrain.r and terrain.first_octave");
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
