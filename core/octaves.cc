#include "core/octaves.h"

#include <cmath>

#include "core/counter_hash.h"

namespace relief {

namespace {

// Veltkamp's split of a double into two halves of at most 26 significant bits each, so that
// products of halves are exact. Valid for |a| < 2^996 (no overflow in kSplitter * a).
void split(double a, double& hi, double& lo) {
  constexpr double kSplitter = 134217729.0;  // 2^27 + 1
  const double t = kSplitter * a;
  hi = t - (t - a);
  lo = a - hi;
}

// a * b = product + error exactly (Dekker 1971), without FMA so that it needs no hardware
// support and contracts to nothing under -ffp-contract=off.
double two_product_error(double a, double b, double product) {
  double a_hi, a_lo, b_hi, b_lo;
  split(a, a_hi, a_lo);
  split(b, b_hi, b_lo);
  return ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
}

double positive_mod(double value, double period) {
  double r = std::fmod(value, period);  // exact
  if (r < 0.0) {
    r += period;
  }
  return r >= period ? r - period : r;
}

}  // namespace

double product_mod(double a, double b, double c, double period) {
  const double product = a * b;
  const double error = two_product_error(a, b, product);
  const double sum = positive_mod(product, period) + positive_mod(error, period) +
                     positive_mod(c, period);  // < 3 period: one rounding
  return positive_mod(sum, period);
}

OctaveTable make_octave_table(const TerrainSettings& terrain, int lattice_size,
                              const Vec3d& camera_position) {
  OctaveTable table;
  table.count = terrain.last_octave - terrain.first_octave + 1;
  const double period = static_cast<double>(lattice_size);
  table.periodic = true;
  for (int n = 0; n < table.count; ++n) {
    const int k = terrain.first_octave + n;
    // r^k by repeated multiplication: exact for integer r while r^k < 2^53.
    double frequency = 1.0;
    for (int step = 0; step < k; ++step) {
      frequency *= terrain.r;
    }
    table.frequency[n] = frequency;
    table.amplitude[n] = std::pow(terrain.r, -k * terrain.H);
    table.scale[n] = frequency / terrain.horizontal_scale;  // > 0: validate_scene
    table.periodic = table.periodic && frequency == std::floor(frequency) && frequency < 0x1p53;
  }
  double camera_x = camera_position[0];
  double camera_z = camera_position[2];
  if (table.periodic) {
    // P is a power of two, so the period is exact; the reduction is exact.
    table.world_period = period * terrain.horizontal_scale;
    camera_x = positive_mod(camera_x, table.world_period);
    camera_z = positive_mod(camera_z, table.world_period);
  }
  const double lattice_x = camera_x / terrain.horizontal_scale;
  const double lattice_z = camera_z / terrain.horizontal_scale;
  for (int n = 0; n < table.count; ++n) {
    const auto k = static_cast<std::uint64_t>(terrain.first_octave + n);
    // omega_k: multiples of P / 2^24 in [0, P), exact in double.
    const double omega_x =
        static_cast<double>(counter_hash(terrain.seed, HashStream::kOctaveOffset, k, 0) >> 40) *
        (period * 0x1p-24);
    const double omega_z =
        static_cast<double>(counter_hash(terrain.seed, HashStream::kOctaveOffset, k, 1) >> 40) *
        (period * 0x1p-24);
    table.offset_x[n] = product_mod(table.frequency[n], lattice_x, omega_x, period);
    table.offset_z[n] = product_mod(table.frequency[n], lattice_z, omega_z, period);
  }
  return table;
}

}  // namespace relief
