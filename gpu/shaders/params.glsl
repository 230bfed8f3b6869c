// The parameter structs of core/stage_params.h (and the lattice header of gpu/gl_terrain.h),
// field by field, in the C++ declaration order. Every member is a 4-byte scalar or an array
// of them, so std430 places each at the C++ offset and gives each array C++'s stride; a nested
// struct's alignment is its largest member's (4), as in C++. GlTerrain checks every offset and
// stride of the linked programs against offsetof() before it runs (gpu/gl_param_layout.cc), so
// the two declarations cannot drift apart unnoticed. RELIEF_MAX_OCTAVES is
// limits::kMaxOctaves (the prelude, gl_shader_prelude.cc).

struct ProjectorRays {  // core/projector.h
  float fx, fz;
  float rx, rz;
  float ux, uz;
  float height_above_plane;
  float max_distance_sq;
};

struct DomainParams {  // stage 2 (§4.1)
  ProjectorRays rays;
  float y0, step_y;
  float c0, c1, nu_max;
  float min_spacing_sq;
  int width, height, pitch;
  int terrain_visible;
  int whole_octaves;
};

struct PlanetParams {  // stage 2 on a planet and the bend (core/planet_plan.h, §4.1)
  int enabled;
  int visible;
  float radius, inv_radius;
  float center_distance;
  float grid_c;
  float blend, one_minus_blend;
  float theta_h, theta_limb;
  float alpha_lo, theta_lo;
  float eq_slope;
};

struct FbmParams {  // stage 3 (Eq. 1, §2.2, §4.1)
  int count;
  int interpolant;
  int warp;
  float frequency[RELIEF_MAX_OCTAVES];
  float amplitude[RELIEF_MAX_OCTAVES];
  float offset_x[RELIEF_MAX_OCTAVES];
  float offset_z[RELIEF_MAX_OCTAVES];
  int exact_coordinates[RELIEF_MAX_OCTAVES];
  float scale_piece[3][RELIEF_MAX_OCTAVES];
  float scale_piece_hi[3][RELIEF_MAX_OCTAVES];
  float scale_piece_lo[3][RELIEF_MAX_OCTAVES];
  float period, inv_period;
  float inv_scale;
  float relative_base_height;
  float height_scale;
  float c1x, c1z, c2x, c2z, c3x, c3z;
  float r0x, r0z, t0x, t0z;
  float roughness0, guard_sq, min_rotation_sq, lacunarity;
};

struct SketchParams {  // stage 3, §3's low-frequency base (core/height_sketch.h)
  int enabled;
  int width, height;
  float offset_x, offset_z;
  float inv_cell_x, inv_cell_z;
  float max_x, max_z;
};

struct SurfaceParams {  // stage 4 (§4.1, second pass)
  int width, height, pitch;
  int water_enabled;
  float water_level;
  float min_sine_sq;
  float max_slope;
};

// A byte of a uint8 stream (valid, need) stored four to a word, little-endian, as the CPU's
// uint8_t arrays lie in memory.
#define RELIEF_BYTE(words, k) ((words[(k) >> 2] >> (8u * (uint(k) & 3u))) & 0xffu)
