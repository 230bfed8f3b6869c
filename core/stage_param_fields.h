// The member lists of the stage parameter structs, written once: stage_params.h declares the
// C++ members from them, and gpu/param_codegen.cc prints from them, at build time, the GLSL
// structs and blocks that take the structs' bytes and the table that checks GL's offsets
// against offsetof (docs/gl-backend.md, "The layout rule").
//
// Each list is a macro LIST(F, A, E) whose entries are
//   F(type, name[, init])        a member `type name = init;` (no initialiser without init),
//   A(type, name, dims[, init])  an array member `type name dims = init;`, dims as in C++
//                                ([n] or [m][n]),
//   E                            the end of a GLSL declaration line: the members since the
//                                previous E share one line (and must share one GLSL type).
// Types are C++ types written with the struct's template parameter Real; the generator maps
// them to GLSL (Real: float, std::int32_t: int, std::uint32_t: uint, double: double, a nested
// struct to its GLSL struct). Comments must be /* */: a // comment would swallow the line
// continuation.
//
// Every struct is declared from its list with RELIEF_DECLARE_FIELDS, in stage_params.h or in
// the header of the stage that owns it (the projector's rays, the planet's and the sketch's
// parameters), except Vec3 (core/vec3.h), which the list only describes to GLSL; stage_params.cc
// checks at compile time that each list names every member of its struct with its type, in
// order (RELIEF_FIELDS_TILE below).
#pragma once

#include <cstddef>
#include <type_traits>

// Declares a struct's members from its list: RELIEF_DECLARE_FIELDS(RELIEF_X_FIELDS).
#define RELIEF_PARAM_MEMBER(type, name, ...) type name __VA_OPT__(= __VA_ARGS__);
#define RELIEF_PARAM_ARRAY(type, name, dims, ...) type name dims __VA_OPT__(= __VA_ARGS__);
#define RELIEF_DECLARE_FIELDS(LIST) LIST(RELIEF_PARAM_MEMBER, RELIEF_PARAM_ARRAY, )

// clang-format off

// ProjectorRays<Real> (core/projector.h): the projector's horizontal frame, stage 2.
#define RELIEF_PROJECTOR_RAYS_FIELDS(F, A, E)                                                   \
  /* Horizontal components of forward, right (horizontal: the projector has no roll) and up. */ \
  F(Real, fx) F(Real, fz) E                                                                     \
  F(Real, rx) F(Real, rz) E                                                                     \
  F(Real, ux) F(Real, uz) E                                                                     \
  F(Real, height_above_plane) E                                                                 \
  F(Real, max_distance_sq) E

// PlanetParams<Real> (core/planet_plan.h): the values stages 2, 4 (the bend) and 8 read.
#define RELIEF_PLANET_PARAMS_FIELDS(F, A, E)                                                    \
  F(std::int32_t, enabled, 0) E                                                                 \
  F(std::int32_t, visible, 0) E                                                                 \
  F(Real, radius, 0) F(Real, inv_radius, 0) E                                                   \
  F(Real, center_distance, 0) /* D */ E                                                         \
  F(Real, grid_c, 0) E                                                                          \
  F(Real, blend, 0) F(Real, one_minus_blend, 1) E                                               \
  F(Real, theta_h, 0) F(Real, theta_limb, 0) E                                                  \
  F(Real, alpha_lo, 0) F(Real, theta_lo, 0) E                                                   \
  F(Real, eq_slope, 0) /* (theta_h - theta_lo) / (alpha_h - alpha_lo) */ E

// SketchParams<Real> (core/height_sketch.h): stage 3's sketch, each plan value rounded once.
#define RELIEF_SKETCH_PARAMS_FIELDS(F, A, E)                                                    \
  F(std::int32_t, enabled, 0) E                                                                 \
  F(std::int32_t, width, 0) F(std::int32_t, height, 0) /* texels */ E                           \
  F(Real, offset_x, 0) F(Real, offset_z, 0) E                                                   \
  F(Real, inv_cell_x, 1) F(Real, inv_cell_z, 1) E                                               \
  /* width + 1, height + 1: the coordinate clamp (with -2) */                                   \
  F(Real, max_x, 0) F(Real, max_z, 0) E                                                         \
  /* A height field's levels of detail (height_sketch.h): 1 for a sketch (level 0 only). A     \
     vertex reads level lod_origin - nu (stage 2's count read as a level); level l's samples   \
     are level_width[l] x level_height[l] at level_offset[l] of the heights, its texel         \
     coordinate level_scale[l] = 2^-l times level 0's. */                                       \
  F(std::int32_t, levels, 1) E                                                                  \
  F(Real, lod_origin, 0) E                                                                      \
  A(std::int32_t, level_width, [limits::kMaxFieldLevels], {}) E                                 \
  A(std::int32_t, level_height, [limits::kMaxFieldLevels], {}) E                                \
  A(std::int32_t, level_offset, [limits::kMaxFieldLevels], {}) E                                \
  A(Real, level_scale, [limits::kMaxFieldLevels], {}) E

// core/vec3.h, Vec3<Real> (declared there): GLSL's Float3, since a vec3 aligns to 16 bytes.
#define RELIEF_VEC3_FIELDS(F, A, E) F(Real, x) F(Real, y) F(Real, z) E

// DomainParams<Real>, stage 2 (§4.1).
#define RELIEF_DOMAIN_PARAMS_FIELDS(F, A, E)                                                    \
  F(ProjectorRays<Real>, rays) E                                                                \
  /* Image point of grid vertex (i, j): (x0_j + i step_x_j, y0 + j step_y), x0_j and         \
     step_x_j from the per-row table (DomainRows). */                                           \
  F(Real, y0, 0) F(Real, step_y, 0) E                                                           \
  F(Real, c0, 0) F(Real, c1, 0) F(Real, nu_max, 1) E /* nu = clamp(c0 - c1 log2(sigma^2),     \
                                                          1, nu_max) */                         \
  F(Real, min_spacing_sq, 0) E /* kMinSpacingSq: the log's domain guard */                     \
  F(std::int32_t, width, 0) F(std::int32_t, height, 0) F(std::int32_t, pitch, 0) E             \
  F(std::int32_t, terrain_visible, 0) E                                                         \
  F(std::int32_t, whole_octaves, 0) E /* 1: nu rounded up (LodPlan::whole_octaves) */

// FbmParams<Real>, stage 3 (Eq. 1, §2.2, §4.1).
#define RELIEF_FBM_PARAMS_FIELDS(F, A, E)                                                       \
  F(std::int32_t, count, 0) E /* N octaves */                                                   \
  F(std::int32_t, interpolant, 0) E /* Interpolant */                                           \
  F(std::int32_t, warp, 0) E /* §2.2 on or off */                                               \
  A(Real, frequency, [limits::kMaxOctaves], {}) E                                               \
  A(Real, amplitude, [limits::kMaxOctaves], {}) E                                               \
  A(Real, offset_x, [limits::kMaxOctaves], {}) E                                                \
  A(Real, offset_z, [limits::kMaxOctaves], {}) E                                                \
  /* Per octave, how its coordinate is formed (octave_coordinates.h): 1 exactly modulo P     \
     from the pieces of g_n and their halves (largest piece first; double uses piece 0       \
     only), 0 directly from inv_scale and frequency. make_fbm_params sets every octave       \
     exact; the frame relaxes them (choose_coordinate_forms). */                                \
  A(std::int32_t, exact_coordinates, [limits::kMaxOctaves], {}) E                               \
  A(Real, scale_piece, [3][limits::kMaxOctaves], {}) E                                          \
  A(Real, scale_piece_hi, [3][limits::kMaxOctaves], {}) E                                       \
  A(Real, scale_piece_lo, [3][limits::kMaxOctaves], {}) E                                       \
  F(Real, period, 1) F(Real, inv_period, 1) E /* P and 1 / P, exact (P a power of two) */      \
  F(Real, inv_scale, 1) E /* world units to octave-0 lattice cells */                           \
  F(Real, relative_base_height, 0) E /* base_height - camera y */                               \
  F(Real, height_scale, 1) E /* amplitude */                                                    \
  F(Real, c1x, 0) F(Real, c1z, 0) F(Real, c2x, 0) F(Real, c2z, 0) F(Real, c3x, 0)               \
  F(Real, c3z, 0) E                                                                             \
  F(Real, r0x, 1) F(Real, r0z, 0) F(Real, t0x, 0) F(Real, t0z, 0) E                             \
  F(Real, roughness0, 1) F(Real, guard_sq, 0) F(Real, min_rotation_sq, 0)                       \
  F(Real, lacunarity, 2) E

// SurfaceParams<Real>, stage 4 (§4.1, second pass).
#define RELIEF_SURFACE_PARAMS_FIELDS(F, A, E)                                                   \
  F(std::int32_t, width, 0) F(std::int32_t, height, 0) F(std::int32_t, pitch, 0) E             \
  F(std::int32_t, water_enabled, 0) E                                                           \
  F(Real, water_level, 0) E /* camera-relative */                                               \
  F(Real, min_sine_sq, 0) E /* kMinTangentSine^2 */                                             \
  F(Real, max_slope, 0) E /* kMaxSlope */                                                       \
  F(Real, inv_silhouette_facing, 4) E /* 1 / kSilhouetteFacing */                               \
  F(Real, hidden_side_weight, 0.03125) E /* kHiddenSideWeight */

// TransformParams<Real>, stage 5: the rows of the view-projection matrix.
#define RELIEF_TRANSFORM_PARAMS_FIELDS(F, A, E)                                                 \
  A(Real, row_x, [3], {}) E                                                                     \
  A(Real, row_y, [3], {}) E                                                                     \
  A(Real, row_w, [3], {}) E                                                                     \
  F(Real, z_clip, 0) E /* the near distance */                                                 \
  /* shading.mode = gradient: Gouraud shading lights each drawn vertex here, as GL's         \
     fixed-function vertex stage did: lambert = max(0, n . sun) (core/vertex_transform.h). */  \
  F(std::int32_t, gouraud, 0) E                                                                 \
  F(Real, sun_x, 0) F(Real, sun_y, 1) F(Real, sun_z, 0) E /* unit, toward the sun */

// RampParams<Real> and LayerParams<Real>, stage 8: one material layer.
#define RELIEF_RAMP_PARAMS_FIELDS(F, A, E)                                                      \
  F(Real, start, 0) E                                                                           \
  F(Real, end, 0) E                                                                             \
  F(std::int32_t, open, 1) E /* 1: the ramp does not limit the layer */

#define RELIEF_LAYER_PARAMS_FIELDS(F, A, E)                                                     \
  F(Real, inv_tile, 1) E /* texture repeats per world unit */                                   \
  F(Real, offset_x, 0) F(Real, offset_y, 0) F(Real, offset_z, 0) E                              \
  F(RampParams<Real>, height_up) F(RampParams<Real>, height_down) E /* camera-relative         \
                                                                         heights */             \
  F(RampParams<Real>, slope_up) F(RampParams<Real>, slope_down) E /* |grad h| */               \
  F(Real, specular, 0) E

// ShadeParams<Real>, stage 8 (§4.2, §4.3).
#define RELIEF_SHADE_PARAMS_FIELDS(F, A, E)                                                     \
  F(std::int32_t, width, 0) F(std::int32_t, height, 0) E /* the image */                        \
  F(std::int32_t, layer_count, 0) E                                                             \
  F(std::int32_t, triplanar, 0) E                                                               \
  A(LayerParams<Real>, layers, [limits::kMaxMaterialLayers]) E                                  \
  /* Light (Scape): sun, hemisphere, ambient. */                                                \
  F(Vec3<Real>, sun_direction, {}) F(Vec3<Real>, sun, {}) F(Vec3<Real>, sky_light, {})          \
  F(Vec3<Real>, ground_light, {}) E                                                             \
  F(Real, ambient, 0) F(Real, shininess, 1) F(Real, exposure, 1) E                              \
  /* Sky and fog. */                                                                            \
  F(Vec3<Real>, zenith, {}) F(Vec3<Real>, horizon, {}) E                                        \
  F(Real, sun_cos_inner, 1) F(Real, sun_cos_outer, 1) F(Real, fog_density_log2, 0) E            \
  /* Water (§4.3). */                                                                           \
  F(std::int32_t, water_enabled, 0) E                                                           \
  F(Real, water_level, 0) E /* camera-relative */                                               \
  F(Vec3<Real>, shallow, {}) F(Vec3<Real>, deep, {}) F(Vec3<Real>, extinction_log2, {}) E       \
  F(Real, inv_full_depth, 1) F(Real, wave_strength, 0) E                                        \
  A(Real, wave_inv_length, [kWaveOctaves], {}) A(Real, wave_offset_x, [kWaveOctaves], {}) E     \
  A(Real, wave_offset_z, [kWaveOctaves], {}) A(Real, wave_amplitude, [kWaveOctaves], {}) E      \
  /* Dithered layer transitions (Scape). */                                                     \
  F(std::int32_t, dither_enabled, 0) E                                                          \
  F(Real, dither_half_amount, 0) E /* 0.5 x shading.dither */                                   \
  F(Real, dither_inv_scale, 1) F(Real, dither_offset_x, 0) F(Real, dither_offset_z, 0) E        \
  F(Real, pixel_angle, 0) E /* radians per pixel */                                             \
  /* What the frame's plan left out (pipeline/frame.h, FrameSkips): the fog pass (off when    \
     its density is 0); the water pass over terrain (off when no drawn vertex lies below     \
     the water level: the open water of the background stays); the specular term where its   \
     weight is 0 (always_specular: computed anyway); the texture fetch of a layer or         \
     projection whose weight is zero. */                                                        \
  F(std::int32_t, fog_enabled, 1) E                                                             \
  F(std::int32_t, terrain_water, 0) E                                                           \
  F(std::int32_t, always_specular, 0) E                                                         \
  F(std::int32_t, skip_zero_weights, 1) E                                                       \
  F(std::int32_t, nearest_mip, 0) E /* 1: GL_LINEAR_MIPMAP_NEAREST (nearest_mip_lod) */         \
  /* The skybox (core/skybox.h) in place of the gradient, and the sun drawn over it. */       \
  F(std::int32_t, skybox, 0) F(std::int32_t, skybox_sun, 1) E                                   \
  /* sky.atmosphere (core/atmosphere.h; atmosphere_plan.h derives each): 1 in place of the   \
     gradient and the fog. */                                                                   \
  F(std::int32_t, atmosphere, 0) E                                                              \
  F(Real, atmosphere_density, 0) F(Real, atmosphere_log2_density, 0) E                         \
  F(Real, atmosphere_scale_height, 1) F(Real, atmosphere_inv_scale_height, 1) E                 \
  F(Real, atmosphere_sun_slope_length, 0) E                                                     \
  F(Real, atmosphere_grazing_term, 1) F(Real, atmosphere_mie_a, 1) E                       \
  F(Real, atmosphere_mie_b, 0) E                                                                \
  F(Vec3<Real>, atmosphere_extinction_log2, {}) E                                               \
  F(Vec3<Real>, atmosphere_camera_sun_depth_log2, {}) E                                         \
  F(Vec3<Real>, atmosphere_rayleigh_sun, {}) F(Vec3<Real>, atmosphere_mie_sun, {}) E            \
  /* castledragmire's height gradient (shading.mode = gradient, core/gradient_shade.h): the   \
     stops at camera-relative heights, 1 / (height[i + 1] - height[i]) per segment (0 for a  \
     step), the colours (linear RGB). */                                                       \
  F(std::int32_t, gradient_enabled, 0) F(std::int32_t, gradient_count, 0) E                     \
  A(Real, gradient_height, [limits::kMaxGradientStops], {}) E                                   \
  A(Real, gradient_inv_span, [limits::kMaxGradientStops], {}) E                                 \
  A(Vec3<Real>, gradient_color, [limits::kMaxGradientStops], {}) E                                  \
  /* sky.clouds (core/clouds.h; cloud_plan.h derives each): 1 where the layer is given;    \
     cloud_steps points per path (1 in the frame, more in the ground truth). */               \
  F(std::int32_t, clouds, 0) F(std::int32_t, cloud_octaves, 0) E                                \
  F(std::int32_t, cloud_warped, 0) F(std::int32_t, cloud_steps, 1) E                            \
  F(Real, cloud_bottom, 0) F(Real, cloud_top, 0) F(Real, cloud_ground, 0) E /* relative */    \
  F(Real, cloud_extinction_log2, 0) F(Real, cloud_sun_depth_log2, 0) E                          \
  F(Real, cloud_threshold, 0) F(Real, cloud_sharpness, 1) F(Real, cloud_mean_density, 0) E      \
  A(Real, cloud_inv_scale, [limits::kMaxCloudOctaves], {}) E                                    \
  A(Real, cloud_offset_x, [limits::kMaxCloudOctaves], {}) E                                     \
  A(Real, cloud_offset_z, [limits::kMaxCloudOctaves], {}) E                                     \
  A(Real, cloud_amplitude, [limits::kMaxCloudOctaves], {}) E                                    \
  A(Real, cloud_warp_gain, [limits::kMaxCloudOctaves], {}) E                                    \
  A(Real, cloud_warp_offset, [4], {}) E                                                         \
  F(Vec3<Real>, cloud_sun_light, {}) F(Vec3<Real>, cloud_sky_light, {}) E                       \
  /* water.reflect_terrain (core/water_reflection.h): 1 where the water mixes its sky toward  \
     the terrain its reflected ray meets (the GL backend refuses it). */                      \
  F(std::int32_t, terrain_reflections, 0) E                                                     \
  /* Unused: keeps the float struct's size a multiple of 16 bytes, the size GL gives the     \
     std430 block that mirrors it (gpu/shaders/shade_params.glsl.in). */                        \
  A(std::int32_t, reserved, [3], {}) E                                                          \
  F(Vec3<Real>, camera_forward, {}) E                                                           \
  /* The background's view ray per pixel is formed in double (it is the sky's direction to   \
     a thousandth of a pixel at any field of view) and rounded once: these stay double. */     \
  A(double, forward, [3], {}) A(double, right, [3], {}) A(double, up, [3], {}) E                \
  F(double, tan_half_fov_x, 0) F(double, tan_half_fov_y, 0) E                                   \
  /* A planet frame (docs/planet.md), in double like the view rays; planet_center_distance   \
     0 on the plane. The background's rays meet the water sphere (radius R + the water       \
     level's elevation) or the datum sphere, or miss both (the sky, its elevation measured   \
     from the limb); c = (D - r)(D + r) of each sphere, formed without cancellation per      \
     frame. */                                                                                  \
  F(double, planet_center_distance, 0) /* D = R + a */                                          \
  F(double, planet_limb_angle, 0) /* nadir angle of the datum's limb (pi/2 on the surface) */   \
  F(double, planet_water_c, 0) F(double, planet_datum_c, 0) E

// clang-format on

namespace relief::stage_fields {

constexpr std::size_t aligned(std::size_t offset, std::size_t alignment) {
  return (offset + alignment - 1) / alignment * alignment;
}

// The members a list names, in order: each must have the type the struct declares and start
// where C++ places the next member after the previous one (its end, rounded up to its own
// alignment), so that no member of the struct lies between them (RELIEF_FIELDS_TILE).
struct Tiling {
  std::size_t next = 0;
  bool ok = true;
  template <class T>
  constexpr void add(std::size_t offset, bool same_type) {
    ok = ok && same_type && offset == aligned(next, alignof(T));
    next = offset + sizeof(T);
  }
};

}  // namespace relief::stage_fields

// A constant bool: whether LIST names every member of Template<RealType>, with its type, in
// order, and only padding lies between or after them (so no member is left out).
#define RELIEF_FIELDS_TILE_F(type, name, ...) \
  tiling.add<type>(offsetof(S, name), std::is_same_v<decltype(S::name), type>);
#define RELIEF_FIELDS_TILE_A(type, name, dims, ...) \
  tiling.add<type dims>(offsetof(S, name), std::is_same_v<decltype(S::name), type dims>);
#define RELIEF_FIELDS_TILE(Template, RealType, LIST)                                           \
  [] {                                                                                         \
    using Real = RealType;                                                                     \
    using S = Template<Real>;                                                                  \
    ::relief::stage_fields::Tiling tiling;                                                     \
    LIST(RELIEF_FIELDS_TILE_F, RELIEF_FIELDS_TILE_A, )                                         \
    return tiling.ok && ::relief::stage_fields::aligned(tiling.next, alignof(S)) == sizeof(S); \
  }()
