// The parameters of every stage, derived once per frame from the FramePlan (and, for stage 8,
// the ShadingPlan), in double, and rounded once to the precision the stage runs in. Each stage
// reads exactly one of these structs (plus its input buffers and the scene's resources:
// lattice, textures); it never rounds a plan value itself. They are plain data: scalars,
// fixed-size arrays and nested structs of them, no pointers, so the same struct can be copied
// into a SIMD kernel's registers or a GLSL storage block field by field. Their members are
// declared from the field lists of stage_param_fields.h, from which the GLSL declarations of
// the same structs are generated (gpu/param_codegen.cc), so each is written once.
//
// The rounding of each field is part of the specification: the float frame is defined by these
// float values (Real(double) of the plan's value, one rounding).
#pragma once

#include <cstdint>
#include <vector>

#include "core/frame_plan.h"
#include "core/limits.h"
#include "core/planet_plan.h"
#include "core/projector.h"
#include "core/shading_plan.h"
#include "core/stage_param_fields.h"
#include "core/vec3.h"

namespace relief {

// Stage 2 (§4.1): the projector rays, the screen grid and the LOD rule.
template <class Real>
struct DomainParams {
  RELIEF_DECLARE_FIELDS(RELIEF_DOMAIN_PARAMS_FIELDS)
};

// Stage 2's per-row table, rows -1 .. height at index j + 1, each value formed in double per
// row and rounded once: -ray.y of row j's projector rays (projector.h: the per-vertex form
// would cancel in float), and where the row's columns lie in the projector image (its span
// over the coverage hull's cross-section, screen_grid.h).
template <class Real>
struct DomainRows {
  std::vector<Real> descent;
  std::vector<Real> x0;      // image x of column 0
  std::vector<Real> step_x;  // image x from one column to the next
};

template <class Real>
DomainRows<Real> make_domain_rows(const FramePlan& plan);

// Stage 3 (Eq. 1, §2.2, §4.1): the octave table and the warp.
template <class Real>
struct FbmParams {
  RELIEF_DECLARE_FIELDS(RELIEF_FBM_PARAMS_FIELDS)
};

template <class Real>
FbmParams<Real> make_fbm_params(const TerrainPlan& plan);

// Stage 4 (§4.1 second pass).
template <class Real>
struct SurfaceParams {
  RELIEF_DECLARE_FIELDS(RELIEF_SURFACE_PARAMS_FIELDS)
};

// Stage 5: the rows of the view-projection matrix (vertex_transform.h).
template <class Real>
struct TransformParams {
  RELIEF_DECLARE_FIELDS(RELIEF_TRANSFORM_PARAMS_FIELDS)
};

// Stage 8 (§4.2, §4.3): one material layer's ranges and texture placement.
template <class Real>
struct RampParams {
  RELIEF_DECLARE_FIELDS(RELIEF_RAMP_PARAMS_FIELDS)
};

template <class Real>
struct LayerParams {
  RELIEF_DECLARE_FIELDS(RELIEF_LAYER_PARAMS_FIELDS)
};

// Stage 8 (§4.2, §4.3): light, sky, fog, water, dithering, the background's rays.
template <class Real>
struct ShadeParams {
  RELIEF_DECLARE_FIELDS(RELIEF_SHADE_PARAMS_FIELDS)
};

// The planet's part of stage 8's parameters (nothing on the plane).
template <class Real>
void add_planet_shading(const FramePlan& plan, double base_height, ShadeParams<Real>& params);

// The parameters of stages 2-5, both precisions of which a frame may run.
template <class Real>
struct TerrainParams {
  DomainParams<Real> domain;
  DomainRows<Real> domain_rows;  // stage 2's per-row table
  FbmParams<Real> fbm;
  SketchParams<Real> sketch;  // stage 3, after the fractal: §3's low-frequency base
  SurfaceParams<Real> surface;
  TransformParams<Real> transform;
  PlanetParams<Real> planet;  // stage 2 and the bend on a planet (planet_plan.h)
};

template <class Real>
TerrainParams<Real> make_terrain_params(const FramePlan& plan);

template <class Real>
ShadeParams<Real> make_shade_params(const ShadingPlan& plan);

// Stage 5's share of Gouraud shading (shading.mode = gradient): the flag and the sun's
// direction, from the frame's shading plan (make_terrain_params has no light).
template <class Real>
void add_gouraud_lighting(const ShadingPlan& plan, TransformParams<Real>& transform);

}  // namespace relief
