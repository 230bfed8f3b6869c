// The FramePlan: everything derived once per frame from the scene (docs/architecture.md). Stages
// read it and never re-derive it: projector and screen grid (stages 1-2), LOD constants (stage 2),
// octave table and warp constants (stage 3), water (stage 4).
#pragma once

#include "core/camera.h"
#include "core/grid_buffers.h"
#include "core/height_bounds.h"
#include "core/height_sketch.h"
#include "core/lattice.h"
#include "core/octaves.h"
#include "core/planet_plan.h"
#include "core/projector.h"
#include "core/scene/scene.h"
#include "core/screen_grid.h"
#include "core/vertex_transform.h"

namespace relief {

// §4.1 octave count: nu = clamp(c0 - c1 log2(sigma^2), 1, N), the log taken of the squared
// spacing so that no square root is needed. See make_lod_plan for c0 and c1.
struct LodPlan {
  double c0 = 0;
  double c1 = 0;
  double nu_max = 1;           // N: all octaves
  bool whole_octaves = false;  // nu rounded up to a whole number (terrain.lod.fractional off)
};

// §2.2 domain warping constants, Relief's reading (docs/paper-reading.md).
struct WarpPlan {
  bool enabled = false;
  double c1x = 0, c1z = 0, c2x = 0, c2z = 0, c3x = 0, c3z = 0;
  double r0x = 1, r0z = 0;  // initial rotation, normalised
  double t0x = 0, t0z = 0;  // initial displacement, base-domain cells
  double roughness0 = 1;    // R0 = r^H
  double lacunarity = 2;    // r: rescales W from one octave's cells to the next's
  double guard_sq = 0;      // kRoughnessGuard^2
};

// What the fractal of stage 3 needs: the terrain as a function of camera-relative position,
// giving camera-relative heights (design rule: per-vertex data are camera-relative float, so
// the float error depends on the distance from the camera to the terrain, not on where they
// are: a base height of 1e7 seen from 700 units above it is as accurate as one of 100).
struct TerrainPlan {
  const NoiseLattice* lattice = nullptr;
  Interpolant interpolant = Interpolant::kQuintic;
  OctaveTable octaves;
  WarpPlan warp;
  double inv_horizontal_scale = 1;  // world units to octave-0 lattice cells
  double relative_base_height = 0;  // terrain.base_height - camera y, formed in double
  double amplitude = 1;
  // §3's low-frequency base, added to the fractal (height_sketch.h); null: none.
  const HeightSketch* sketch = nullptr;
  SketchPlan sketch_plan;
};

struct FramePlan {
  CameraFrame camera;
  HeightBounds bounds;
  Projector projector;
  ScreenGrid screen;  // stage 1
  GridLayout layout;
  LodPlan lod;
  TerrainPlan terrain;
  ClipTransform clip;  // stage 5
  // Water (§4.3), decided once for every stage: a water level is set and the camera is above
  // it (from below, the surface is not drawn: the terrain is seen as if there were none).
  bool water_enabled = false;
  double relative_water_level = 0;  // terrain.water_level - camera y, formed in double
  // §4.1's spherical domain (planet_plan.h); planet.enabled false on the plane.
  PlanetPlan planet;
};

// Precondition: the scene passed validate_scene and `lattice` is stage 3's grid: the noise
// lattice built from its seed and lattice_size, or with terrain.basis the composed grid of its
// images (core/basis_images.h), whose side and tile_size then set the period and the cell; `sketch`
// was loaded from scene.terrain.sketch or .heightfield (pipeline/scene_resources.h). Throws
// std::invalid_argument when the scene has either and `sketch` is null (a caller that forgot it would otherwise render
// another terrain). `parallel` runs the projector's refinement (projector.h), the same plan
// whoever runs it.
FramePlan make_frame_plan(const Scene& scene, const NoiseLattice& lattice,
                          const HeightSketch* sketch = nullptr, const ParallelRows& parallel = {});

TerrainPlan make_terrain_plan(const TerrainSettings& terrain, const NoiseLattice& lattice,
                              const Vec3d& camera_position, const HeightSketch* sketch = nullptr);

LodPlan make_lod_plan(const TerrainSettings& terrain);
// A height field's levels of detail in place of the octaves (the fractal off): stage 2's count
// nu read as level levels - nu (height_sketch.h). Precondition: the terrain has a height field
// and `field` is its samples.
LodPlan make_field_lod_plan(const TerrainSettings& terrain, const HeightSketch& field);

}  // namespace relief
