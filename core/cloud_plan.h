// What the cloud layer (core/clouds.h) derives once per frame, in double, from sky.clouds, the
// camera and the light.
#pragma once

#include <glm/vec3.hpp>

#include "core/limits.h"
#include "core/scene/scene.h"

namespace relief {

// The threshold of a coverage of 0 (or 1, negated): beyond any value the fBm takes (its
// amplitudes sum to 1 and the lattice's values are finite normal samples), so no point holds
// cloud (or every point is full); (n - t) x sharpness stays finite in float.
inline constexpr double kCloudThresholdBeyond = 1e30;
// The sun's path through the layer is floored at this sine of elevation (a grazing sun lights
// the layer's side, not a path 1 / sin e long).
inline constexpr double kCloudMinSunSine = 0.05;

struct CloudPlan {
  bool enabled = false;
  int octaves = 0;
  double bottom = 0, top = 0;  // the layer's heights relative to the camera
  // The lowest height the terrain reaches (the frame's height bounds), relative to the
  // camera: a background ray below the horizon without water stands for terrain beyond the
  // far distance, which it meets by this height at the latest.
  double ground = 0;
  double extinction_log2 = 0;  // sky.clouds.density / ln 2
  // Density D = clamp((n - threshold) sharpness, 0, 1) of the fBm n: threshold the n that a
  // share `coverage` of the layer's area exceeds, sharpness 1 / sigma_n (full one standard
  // deviation above it).
  double threshold = 0, sharpness = 1;
  double mean_density = 0;  // E[D]: what a point far beyond its pixel's footprint holds
  double inv_scale[limits::kMaxCloudOctaves]{};  // octave i's lattice cells per world unit
  double offset_x[limits::kMaxCloudOctaves]{};   // the camera in octave i's cells, mod P
  double offset_z[limits::kMaxCloudOctaves]{};
  double amplitude[limits::kMaxCloudOctaves]{};  // 2^-i, normalised to sum 1
  double warp_gain[limits::kMaxCloudOctaves]{};  // the warp in octave i's cells: warp 2^i
  bool warped = false;
  double warp_offset[4]{};  // the two warp samples' camera offsets (x, z each), mod P
  // The light the layer returns: albedo x the sun x max(sin e, 0), dimmed by the cloud above
  // the point (sun_depth_log2: extinction_log2 / 2 x half the thickness / max(sin e, 0.05),
  // per unit of density), plus albedo x (the sky's hemisphere light + ambient).
  glm::dvec3 sun_light{}, sky_light{};
  double sun_depth_log2 = 0;
  int steps = 1;  // points per path: 1 in the frame, more in the ground truth
};

// sigma_n of the fBm of `octaves` octaves (normalised amplitudes): the standard deviation of
// one cubic-interpolated lattice sample of N(0, 1) values, 26/35 per axis in variance
// (E[(1 - s)^2 + s^2] for the cubic fade s of a uniform t), times sqrt(sum a_i^2).
double cloud_fbm_sigma(int octaves);

// Phi^-1(p): the standard normal's quantile for p in (0, 1) (Acklam's rational
// approximation, relative error 1.15e-9), with det_math's log.
double normal_quantile(double p);

// `camera` in world units, `ground_height` the terrain's lowest (world units), `sun_direction`
// unit toward the sun, `sun`, `sky` and `ambient` the light's (shading_plan.h's LightPlan),
// `lattice_size` P.
CloudPlan make_cloud_plan(const CloudSettings& settings, const glm::dvec3& camera,
                          double ground_height, const glm::dvec3& sun_direction,
                          const glm::dvec3& sun, const glm::dvec3& sky, double ambient,
                          int lattice_size);

}  // namespace relief
