// The reflected rays' set-up (core/water_reflection.h, reflection_ray) as a Highway kernel for
// float: the view ray, its surface point, the wave normal and the reflected direction and weight
// of as many pixels per step as the target's vectors hold, each lane with the scalar code's
// operations in its order, so every ray is bit-identical to reflection_ray<float> on every
// target. The march that follows stays scalar (pipeline/tile_reflections.h).
#pragma once

#include <cstdint>

#include "core/lattice.h"
#include "core/stage_params.h"

namespace relief::simd {

// One row of pixels' rays, `count` of each.
struct ReflectionRayRow {
  float* start_x;
  float* start_z;
  float* surface;
  float* direction_x;
  float* direction_y;
  float* direction_z;
  float* weight;
};

// For i < count where primitive[i] != 0xffffffff and height[i] < p.water_level (the water in
// front: tile_reflections.h): the ray of reflection_ray<float>(p, lattice, dx[i], height[i],
// dz[i], depth[i]) into row's i-th values (start.y is the water level); weight 0 elsewhere,
// the other values unspecified.
void reflection_rays(const ShadeParams<float>& p, const NoiseLattice& lattice,
                     const std::uint32_t* primitive, const float* dx, const float* height,
                     const float* dz, const float* depth, int count, const ReflectionRayRow& row);

}  // namespace relief::simd
