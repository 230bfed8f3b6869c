// The scene file's "terrain" section and its "lod" and "warp" objects
// (docs/scene-reference.md); terrain.sketch, .basis and .planet have files of their own.
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

const Schema<LodSettings>& lod_schema() {
  using S = LodSettings;
  static const Schema<S> schema({
      choice_field("criterion", &S::criterion,
                   {{"amplitude", LodCriterion::kAmplitude}, {"nyquist", LodCriterion::kNyquist}},
                   {"", "§4.1's amplitude rule, or two grid spacings per lattice cell"}),
      number_field("bias", &S::bias, Range{-limits::kMaxLodBias, limits::kMaxLodBias},
                   {"octaves", "added to the criterion's octave count"}),
      boolean_field("fractional", &S::fractional,
                    {"",
                     "§4.1's fractional octave (geomorphing); false sums whole octaves, the "
                     "count rounded up"}),
  });
  return schema;
}

const Schema<WarpSettings>& warp_schema() {
  using S = WarpSettings;
  const Range component{-limits::kMaxWarpComponent, limits::kMaxWarpComponent};
  static const Schema<S> schema({
      boolean_field("enabled", &S::enabled, {"", "§2.2 domain warping"}),
      vector_field("c1", &S::c1, component, {"", "rotation per unit roughness (Figure 3's)"}),
      vector_field("c2", &S::c2, component, {"", "constant rotation update"}),
      vector_field("c3", &S::c3, component, {"", "translation per unit height / roughness"}),
      vector_field("r0", &S::r0, component,
                   {"", "initial rotation vector (cos a, sin a), need not be unit", "non-zero"}),
      vector_field("t0", &S::t0, component,
                   {"lattice cells", "initial displacement, in cells of octave k0"}),
  });
  return schema;
}

}  // namespace

const Schema<TerrainSettings>& terrain_schema() {
  using S = TerrainSettings;
  const Range height{-limits::kMaxBaseHeight, limits::kMaxBaseHeight};
  static const Schema<S> schema({
      unsigned64_field("seed", &S::seed, {"", "lattice seed"}),
      power_of_two_field("lattice_size", &S::lattice_size, limits::kMinLatticeSize,
                         limits::kMaxLatticeSize, {"lattice cells", "P, the lattice is P × P"}),
      choice_field("interpolant", &S::interpolant,
                   {{"linear", Interpolant::kLinear},
                    {"cubic", Interpolant::kCubic},
                    {"quintic", Interpolant::kQuintic}},
                   {"", "C0, C1, C2 interpolation of the lattice"}),
      number_field("r", &S::r, Range{limits::kMinLacunarity, limits::kMaxLacunarity},
                   {"", "lacunarity (Eq. 1)"}),
      number_field("H", &S::H, Range{limits::kMinHurst, limits::kMaxHurst},
                   {"", "Hurst exponent, H = 3 − D (Eq. 1)",
                    "with the amplitude criterion H·log2 r ≥ 2⁻¹⁰ (H ≥ 0.00098 at r = 2)"}),
      integer_field("first_octave", &S::first_octave, 0, limits::kMaxFirstOctave,
                    {"octaves", "k0 (Eq. 1): the global structure"}),
      integer_field("last_octave", &S::last_octave, 0,
                    limits::kMaxFirstOctave + limits::kMaxOctaves - 1,
                    {"octaves", "the finest octave the LOD may add",
                     "≥ first_octave, at most 24 octaves, last_octave·log2 r ≤ 40"}),
      section_field("lod", &S::lod, lod_schema(), {"", "how many octaves each vertex sums"}),
      section_field("warp", &S::warp, warp_schema(), {"", "§2.2 domain warping"}),
      number_field("horizontal_scale", &S::horizontal_scale,
                   Range{limits::kMinHorizontalScale, limits::kMaxHorizontalScale},
                   {"world units", "per lattice cell of octave 0: the largest features' size",
                    "≥ r^first_octave·F/(2²⁴ − lattice_size) with F = 2·far·√(1 + tan²(fov_x/2) "
                    "+ tan²(fov_y/2)) (0.0097 for the default view)"}),
      number_field("base_height", &S::base_height, height,
                   {"world units", "world height of fBm value 0"}),
      number_field("amplitude", &S::amplitude, Range{limits::kMinAmplitude, limits::kMaxAmplitude},
                   {"world units", "per unit of fBm (the N(0,1) lattice)"}),
      nullable_number_field("water_level", &S::water_level, height,
                            {"world units", "water surface height; `null`: no water"}),
      optional_section_field("sketch", &S::sketch, sketch_schema(), "image", "an \"image\"",
                             {"",
                              "§3's low-frequency base, added to the fractal "
                              "(docs/terrain-spec.md §11)"}),
      optional_section_field("heightfield", &S::heightfield, heightfield_schema(), "file",
                             "a \"file\"",
                             {"",
                              "a finite height field as the terrain (docs/terrain-spec.md §11), "
                              "sampled as the sketch is; not with sketch"}),
      optional_section_field("basis", &S::basis, basis_schema(), "images", "\"images\"",
                             {"",
                              "§3 Eq. 2: basis images in place of the noise lattice in "
                              "stage 3 (docs/terrain-spec.md §12); horizontal_scale is then "
                              "unused"}),
      optional_section_field(
          "planet", &S::planet, planet_schema(), "", "",
          {"", "§4.1's spherical domain (docs/planet.md); absent or radius 0: the plane"},
          +[](const PlanetSettings& planet) { return planet.radius != 0.0; }),
  });
  return schema;
}

}  // namespace relief
