#include "core/frame_plan.h"

#include <cmath>
#include <stdexcept>

#include "core/basis_images.h"
#include "core/limits.h"

namespace relief {

LodPlan make_lod_plan(const TerrainSettings& terrain) {
  // The finest octave worth summing has continuous index kappa; octaves k0 .. kappa make
  // nu = kappa + bias - k0 + 1 octaves (so that kappa = k0 gives one whole octave).
  //   amplitude (§4.1): amplitude r^(-kappa H) = sigma
  //       kappa = (log2 amplitude - log2 sigma) / (H log2 r)
  //   Nyquist: the octave's lattice cell, scale r^-kappa, spans two grid spacings
  //       kappa = (log2 scale - 1 - log2 sigma) / log2 r
  // with log2 sigma = log2(sigma^2) / 2.
  const double log2_r = std::log2(terrain.r);
  const double offset = terrain.lod.bias - terrain.first_octave + 1.0;
  LodPlan lod;
  if (terrain.lod.criterion == LodCriterion::kAmplitude) {
    lod.c0 = std::log2(terrain.amplitude) / (terrain.H * log2_r) + offset;
    lod.c1 = 0.5 / (terrain.H * log2_r);
  } else {
    lod.c0 = (std::log2(terrain.horizontal_scale) - 1.0) / log2_r + offset;
    lod.c1 = 0.5 / log2_r;
  }
  lod.nu_max = terrain.last_octave - terrain.first_octave + 1;
  lod.whole_octaves = !terrain.lod.fractional;
  return lod;
}

LodPlan make_field_lod_plan(const TerrainSettings& terrain, const HeightSketch& field) {
  // A height field without the fractal reads level lambda = levels - nu (height_sketch.h):
  // the level whose sample spacing cell 2^lambda is the vertex's grid spacing sigma,
  //   lambda = log2(sigma / cell) - bias,   nu = levels + log2 cell + bias - log2(sigma^2) / 2,
  // so c0 = levels + log2 cell + bias, c1 = 1/2, and stage 2's clamp of nu to [1, levels] is
  // the clamp of lambda to [0, levels - 1]. `cell` the coarser axis's sample spacing (> 0:
  // validate_scene keeps each side of the extent at least kMinSketchSpan long).
  const SketchSettings& s = *added_height_field(terrain);
  const auto& e = sketch_extent(s, field);
  const double cell = std::max((e[2] - e[0]) / field.width, (e[3] - e[1]) / field.height);
  LodPlan lod;
  lod.nu_max = field.levels();
  lod.c0 = lod.nu_max + std::log2(cell) + terrain.lod.bias;
  lod.c1 = 0.5;
  lod.whole_octaves = !terrain.lod.fractional;
  return lod;
}

TerrainPlan make_terrain_plan(const TerrainSettings& settings, const NoiseLattice& lattice,
                              const Vec3d& camera_position, const HeightSketch* sketch) {
  // With §3's basis images, `lattice` is their composed grid and sets the period and cell.
  const TerrainSettings terrain = stage3_terrain(settings, lattice.size);
  TerrainPlan plan;
  plan.lattice = &lattice;
  plan.interpolant = terrain.interpolant;
  plan.octaves = make_octave_table(terrain, lattice.size, camera_position);
  if (!fractal_enabled(terrain)) {
    // A height field without the fractal: stage 3 sums no octave, every backend's loop over
    // them runs zero times and leaves base - camera_y (the skip the --stats octave counter
    // shows); the LOD plan keeps its range, so stage 2 is unchanged.
    plan.octaves.count = 0;
  }
  plan.inv_horizontal_scale = 1.0 / terrain.horizontal_scale;
  plan.relative_base_height = terrain.base_height - camera_position[1];
  plan.amplitude = terrain.amplitude;
  const WarpSettings& w = terrain.warp;
  WarpPlan& warp = plan.warp;
  warp.enabled = w.enabled;
  warp.c1x = w.c1[0];
  warp.c1z = w.c1[1];
  warp.c2x = w.c2[0];
  warp.c2z = w.c2[1];
  warp.c3x = w.c3[0];
  warp.c3z = w.c3[1];
  const double r0_length = std::hypot(w.r0[0], w.r0[1]);  // > 0: validate_scene
  warp.r0x = w.r0[0] / r0_length;
  warp.r0z = w.r0[1] / r0_length;
  warp.t0x = w.t0[0];
  warp.t0z = w.t0[1];
  warp.roughness0 = std::pow(terrain.r, terrain.H);
  warp.lacunarity = terrain.r;
  warp.guard_sq = limits::kRoughnessGuard * limits::kRoughnessGuard;
  if (const SketchSettings* field = added_height_field(terrain); field && sketch != nullptr) {
    plan.sketch = sketch;
    plan.sketch_plan = make_sketch_plan(*field, *sketch, camera_position[0], camera_position[2]);
  }
  return plan;
}

FramePlan make_frame_plan(const Scene& scene, const NoiseLattice& lattice,
                          const HeightSketch* sketch, const ParallelRows& parallel) {
  if (added_height_field(scene.terrain) != nullptr && sketch == nullptr) {
    throw std::invalid_argument(
        "make_frame_plan: the scene has a terrain.sketch or terrain.heightfield but no field "
        "was loaded for it");
  }
  FramePlan plan;
  plan.camera = make_camera_frame(scene.camera, scene.viewport);
  plan.bounds = derive_height_bounds(lattice, scene.terrain, sketch);
  plan.layout = make_grid_layout(scene.grid.width, scene.grid.height);
  plan.lod = sketch != nullptr && sketch->levels() > 1 && !fractal_enabled(scene.terrain)
                 ? make_field_lod_plan(scene.terrain, *sketch)
                 : make_lod_plan(stage3_terrain(scene.terrain, lattice.size));
  plan.terrain = make_terrain_plan(scene.terrain, lattice, scene.camera.position, sketch);
  plan.planet = make_planet_plan(scene.terrain, plan.camera, plan.bounds);
  if (plan.planet.enabled) {
    plan.projector =
        make_planet_projector(plan.camera, plan.bounds, scene.terrain.base_height, plan.planet);
  } else {
    // After the terrain plan: the projector refines the slab by its regional height bound.
    plan.projector = make_projector(plan.camera, plan.bounds, scene.terrain.base_height,
                                    &plan.terrain, parallel);
  }
  plan.screen = make_screen_grid(scene.grid, plan.projector);
  plan.clip = make_clip_transform(plan.camera);
  plan.relative_water_level = scene.terrain.water_level.value_or(0.0) - scene.camera.position[1];
  plan.water_enabled = scene.terrain.water_level.has_value() && plan.relative_water_level < 0.0;
  return plan;
}

}  // namespace relief
