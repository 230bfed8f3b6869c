// Per-octave constants of Eq. 1, derived once per frame in double.
//
// Octave k samples S at lattice coordinates r^k x / scale + omega_k, where x is the world
// position in the base domain (x, z) and omega_k a per-octave offset drawn from the seed, so
// that the octaves do not all pass through the same lattice point at the origin. Kernels work
// camera-relative: with x = camera + d,
//   r^k x / scale + omega_k = offset_k + r^k d / scale,
//   offset_k = (r^k camera / scale + omega_k) mod P,
// and offset_k is reduced here, in double, with an exact product, so a kernel never adds a
// large number to a small one (docs/architecture.md, Conventions). A camera 1e9 units from the
// origin gets offsets in [0, P) just as one at the origin does.
#pragma once

#include <array>

#include "core/limits.h"
#include "core/scene/scene.h"

namespace relief {

struct OctaveTable {
  int count = 0;  // N = last_octave - first_octave + 1; entry n is octave k0 + n
  std::array<double, limits::kMaxOctaves> frequency{};  // r^k
  std::array<double, limits::kMaxOctaves> amplitude{};  // r^(-kH), Eq. 1
  std::array<double, limits::kMaxOctaves> offset_x{};   // offset_k above, in [0, P)
  std::array<double, limits::kMaxOctaves> offset_z{};
  // g_n = r^k / horizontal_scale, correctly rounded: world units to octave n's lattice cells
  // (octave_coordinates.h forms g_n d exactly modulo P).
  std::array<double, limits::kMaxOctaves> scale{};
  // True when every r^k is an integer: the terrain then repeats every P * horizontal_scale
  // world units, and the camera position is reduced by that period before anything else, so
  // that moving the camera by whole periods reproduces every buffer bit for bit.
  bool periodic = false;
  double world_period = 0;  // P * horizontal_scale when periodic
};

OctaveTable make_octave_table(const TerrainSettings& terrain, int lattice_size,
                              const Vec3d& camera_position);

// (a * b + c) mod period, in [0, period), for finite a, b, c and period > 0. The product is
// split exactly into hi + lo (Dekker's two-product with Veltkamp's split, using only
// correctly rounded + - *), each part reduced with the exact fmod, then summed: the error is
// one rounding of a number below 3 * period, whatever the size of a * b.
double product_mod(double a, double b, double c, double period);

}  // namespace relief
