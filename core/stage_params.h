// The parameters of every stage, derived once per frame from the FramePlan (and, for stage 8,
// the ShadingPlan), in double, and rounded once to the precision the stage runs in. Each stage
// reads exactly one of these structs (plus its input buffers and the scene's resources:
// lattice, textures); it never rounds a plan value itself. They are plain data: scalars,
// fixed-size arrays and nested structs of them, no pointers, so the same struct can be copied
// into a SIMD kernel's registers or a GLSL storage block field by field.
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
#include "core/vec3.h"

namespace relief {

// Stage 2 (§4.1): the projector rays, the screen grid and the LOD rule.
template <class Real>
struct DomainParams {
  ProjectorRays<Real> rays;
  // Image point of grid vertex (i, j): (x0_j + i step_x_j, y0 + j step_y), x0_j and step_x_j
  // from the per-row table (DomainRows).
  Real y0 = 0, step_y = 0;
  Real c0 = 0, c1 = 0, nu_max = 1;  // nu = clamp(c0 - c1 log2(sigma^2), 1, nu_max)
  Real min_spacing_sq = 0;          // kMinSpacingSq: the log's domain guard
  std::int32_t width = 0, height = 0, pitch = 0;
  std::int32_t terrain_visible = 0;
  std::int32_t whole_octaves = 0;  // 1: nu rounded up (LodPlan::whole_octaves)
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
  std::int32_t count = 0;        // N octaves
  std::int32_t interpolant = 0;  // Interpolant
  std::int32_t warp = 0;         // §2.2 on or off
  Real frequency[limits::kMaxOctaves] = {};
  Real amplitude[limits::kMaxOctaves] = {};
  Real offset_x[limits::kMaxOctaves] = {};
  Real offset_z[limits::kMaxOctaves] = {};
  // Per octave, how its coordinate is formed (octave_coordinates.h): 1 exactly modulo P from
  // the pieces of g_n and their halves (largest piece first; double uses piece 0 only), 0
  // directly from inv_scale and frequency. make_fbm_params sets every octave exact; the frame
  // relaxes them (choose_coordinate_forms).
  std::int32_t exact_coordinates[limits::kMaxOctaves] = {};
  Real scale_piece[3][limits::kMaxOctaves] = {};
  Real scale_piece_hi[3][limits::kMaxOctaves] = {};
  Real scale_piece_lo[3][limits::kMaxOctaves] = {};
  Real period = 1, inv_period = 1;  // P and 1 / P, exact (P a power of two)
  Real inv_scale = 1;               // world units to octave-0 lattice cells
  Real relative_base_height = 0;    // base_height - camera y
  Real height_scale = 1;            // amplitude
  Real c1x = 0, c1z = 0, c2x = 0, c2z = 0, c3x = 0, c3z = 0;
  Real r0x = 1, r0z = 0, t0x = 0, t0z = 0;
  Real roughness0 = 1, guard_sq = 0, min_rotation_sq = 0, lacunarity = 2;
};

template <class Real>
FbmParams<Real> make_fbm_params(const TerrainPlan& plan);

// Stage 4 (§4.1 second pass).
template <class Real>
struct SurfaceParams {
  std::int32_t width = 0, height = 0, pitch = 0;
  std::int32_t water_enabled = 0;
  Real water_level = 0;  // camera-relative
  Real min_sine_sq = 0;  // kMinTangentSine^2
  Real max_slope = 0;    // kMaxSlope
};

// Stage 5: the rows of the view-projection matrix (vertex_transform.h).
template <class Real>
struct TransformParams {
  Real row_x[3] = {}, row_y[3] = {}, row_w[3] = {};
  Real z_clip = 0;  // the near distance
};

// Stage 8 (§4.2, §4.3): one material layer's ranges and texture placement.
template <class Real>
struct RampParams {
  Real start = 0, end = 0;
  std::int32_t open = 1;  // 1: the ramp does not limit the layer
};

template <class Real>
struct LayerParams {
  Real inv_tile = 1;  // texture repeats per world unit
  Real offset_x = 0, offset_y = 0, offset_z = 0;
  RampParams<Real> height_up, height_down;  // camera-relative heights
  RampParams<Real> slope_up, slope_down;    // |grad h|
  Real specular = 0;
};

template <class Real>
struct ShadeParams {
  std::int32_t width = 0, height = 0;  // the image
  std::int32_t layer_count = 0;
  std::int32_t triplanar = 0;
  LayerParams<Real> layers[limits::kMaxMaterialLayers];
  // Light (Scape): sun, hemisphere, ambient.
  Vec3<Real> sun_direction{}, sun{}, sky_light{}, ground_light{};
  Real ambient = 0, shininess = 1, exposure = 1;
  // Sky and fog.
  Vec3<Real> zenith{}, horizon{};
  Real sun_cos_inner = 1, sun_cos_outer = 1, fog_density_log2 = 0;
  // Water (§4.3).
  std::int32_t water_enabled = 0;
  Real water_level = 0;  // camera-relative
  Vec3<Real> shallow{}, deep{}, extinction_log2{};
  Real inv_full_depth = 1, wave_strength = 0;
  Real wave_inv_length[kWaveOctaves] = {}, wave_offset_x[kWaveOctaves] = {};
  Real wave_offset_z[kWaveOctaves] = {}, wave_amplitude[kWaveOctaves] = {};
  // Dithered layer transitions (Scape).
  std::int32_t dither_enabled = 0;
  Real dither_half_amount = 0;  // 0.5 x shading.dither
  Real dither_inv_scale = 1, dither_offset_x = 0, dither_offset_z = 0;
  Real pixel_angle = 0;  // radians per pixel
  // What the frame's plan left out (pipeline/frame.h, FrameSkips): the fog pass (off when its
  // density is 0); the water pass over terrain (off when no drawn vertex lies below the water
  // level: the open water of the background stays); the specular term where its weight is 0
  // (always_specular: computed anyway); the texture fetch of a layer or projection whose
  // weight is zero.
  std::int32_t fog_enabled = 1;
  std::int32_t terrain_water = 0;
  std::int32_t always_specular = 0;
  std::int32_t skip_zero_weights = 1;
  std::int32_t nearest_mip = 0;  // 1: GL_LINEAR_MIPMAP_NEAREST (nearest_mip_lod)
  // Unused: keeps the float struct's size a multiple of 16 bytes, the size GL gives the
  // std430 block that mirrors it (gpu/shaders/shade_params.glsl).
  std::int32_t reserved[3] = {};
  Vec3<Real> camera_forward{};
  // The background's view ray per pixel is formed in double (it is the sky's direction to a
  // thousandth of a pixel at any field of view) and rounded once: these stay double.
  double forward[3] = {}, right[3] = {}, up[3] = {};
  double tan_half_fov_x = 0, tan_half_fov_y = 0;
  // A planet frame (docs/planet.md), in double like the view rays; planet_center_distance 0 on
  // the plane. The background's rays meet the water sphere (radius R + the water level's
  // elevation) or the datum sphere, or miss both (the sky, its elevation measured from the
  // limb); c = (D - r)(D + r) of each sphere, formed without cancellation per frame.
  double planet_center_distance = 0;  // D = R + a
  double planet_limb_angle = 0;       // nadir angle of the datum's limb (pi/2 on the surface)
  double planet_water_c = 0;
  double planet_datum_c = 0;
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

}  // namespace relief
