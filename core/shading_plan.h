// What stage 8 (proto-texture shading, §4.2-§4.3) derives once per frame: layer ranges in the
// units the pixels use, texture-coordinate offsets of the camera (reduced in double, as the
// terrain's lattice offsets are), light, sky and water constants.
#pragma once

#include <span>
#include <vector>

#include "core/atmosphere_plan.h"
#include "core/camera.h"
#include "core/cloud_plan.h"
#include "core/frame_plan.h"
#include "core/limits.h"
#include "core/scene/scene.h"

namespace relief {

// One ramp of a layer's range: weight rises from 0 at `start` to 1 at `end` (a step where
// start == end); `open` ramps are always 1 (a range reaching the domain's end).
struct Ramp {
  double start = 0;
  double end = 0;
  bool open = true;
};

struct LayerPlan {
  double inv_tile = 1;  // texture repeats per world unit
  // Camera position in texture repeats, reduced modulo 1: u = offset_x + dx * inv_tile.
  double offset_x = 0, offset_y = 0, offset_z = 0;
  Ramp height_up, height_down;  // heights relative to the camera, water level applied
  Ramp slope_up, slope_down;    // |grad h| (tangents of the slope angles)
  double specular = 0;
};

struct LightPlan {
  glm::dvec3 sun_direction;  // unit, toward the sun
  glm::dvec3 sun;            // radiance: colour * intensity
  glm::dvec3 sky, ground;    // hemispherical light (Scape)
  double ambient = 0;
  double shininess = 1;
  double exposure = 1;
};

struct SkyPlan {
  glm::dvec3 zenith, horizon;
  double sun_cos_inner = 1, sun_cos_outer = 1;  // the disc's smooth edge
  double fog_density_log2 = 0;                  // density / ln 2, for exp2
  bool skybox = false;                          // sky.skybox given (core/skybox.h)
  bool skybox_sun = true;                       // its sun_disc
  AtmospherePlan atmosphere;                    // sky.atmosphere (core/atmosphere.h)
};

inline constexpr int kWaveOctaves = 3;

struct WaterPlan {
  bool enabled = false;  // water level set and the camera above it
  double level = 0;      // water level relative to the camera (negative: below it)
  glm::dvec3 shallow, deep;
  glm::dvec3 extinction_log2;  // per world unit, / ln 2
  double inv_full_depth = 1;
  double strength = 0;
  bool reflect_terrain = false;            // water.reflect_terrain, where enabled
  double wave_inv_length[kWaveOctaves]{};  // lattice cells per world unit
  double wave_offset_x[kWaveOctaves]{};    // (camera + velocity time) in cells, mod P
  double wave_offset_z[kWaveOctaves]{};
  double wave_amplitude[kWaveOctaves]{};
};

struct DitherPlan {
  double amount = 0;  // 0: no dithering
  double inv_scale = 1;
  double offset_x = 0, offset_z = 0;  // camera in lattice cells, mod P
};

// castledragmire's height-to-colour gradient (shading.mode = gradient): its stops at heights
// relative to the camera, formed in double from shading.gradient's `at` and range (the
// terrain's height bounds where the range is null).
struct GradientPlan {
  bool enabled = false;
  std::vector<double> height;  // non-decreasing
  std::vector<glm::dvec3> color;
};

struct ShadingPlan {
  GradientPlan gradient;
  std::vector<LayerPlan> layers;
  bool triplanar = true;
  bool nearest_mip = false;  // shading.texture_filter = bilinear
  LightPlan light;
  SkyPlan sky;
  WaterPlan water;
  DitherPlan dither;
  CloudPlan clouds;  // sky.clouds (core/clouds.h); disabled without them
  CameraFrame camera;
  int width = 0, height = 0;  // the image
  double pixel_angle = 0;     // radians subtended by one pixel (vertical field / height)
};

// `lattice_size`: P of the terrain's noise lattice, which the dithering and the waves reuse
// (their offsets are reduced modulo it). The textures and the lattice themselves are
// resources the stage reads (shade.h), not part of the plan.
ShadingPlan make_shading_plan(const Scene& scene, const FramePlan& frame, int lattice_size);

}  // namespace relief
