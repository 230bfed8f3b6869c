#include "core/height_bound_pyramid.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/interpolant.h"
#include "core/limits.h"

namespace relief {

namespace {

// Ranges of at most this many lattice values are scanned directly (exact; 16 reads, fewer
// than the 18 of a 3 x 3 texel pyramid read).
constexpr std::int64_t kDirectScanValues = 16;
// The finest stored pyramid level has at most (2^8)^2 texels.
constexpr int kMaxStoredLevelLog2 = 8;
// Lattice coordinates beyond 2^50 resolve no cell in double: such an octave gets its global
// extremes (the stage cannot resolve them either, limits.h, kMaxLatticeCoordinate).
constexpr double kMaxResolvedCoordinate = 0x1p50;
// Octaves whose rectangle spans at most this many cells per axis are bounded exactly from S
// at up to (kExactCells + 1)^2 points; wider ones from the pyramid.
constexpr int kExactCells = 4;

}  // namespace

LatticeRangePyramid make_lattice_range_pyramid(const NoiseLattice& lattice) {
  LatticeRangePyramid p;
  p.size = lattice.size;
  p.log2_size = std::countr_zero(static_cast<unsigned>(lattice.size));  // P is a power of two
  p.first_level = std::max(1, p.log2_size - kMaxStoredLevelLog2);
  p.global_lo = lattice.min_value;
  p.global_hi = lattice.max_value;
  p.level_offset.assign(static_cast<std::size_t>(p.log2_size) + 2, 0);
  std::size_t total = 0;
  for (int l = p.first_level; l <= p.log2_size; ++l) {
    p.level_offset[static_cast<std::size_t>(l)] = total;
    const std::size_t side = static_cast<std::size_t>(p.size) >> l;
    total += side * side;
  }
  p.lo.assign(total, 0.0f);
  p.hi.assign(total, 0.0f);
  // The first stored level straight from the lattice, then each level from the one below.
  const int block = 1 << p.first_level;
  const int side = p.size >> p.first_level;
  const std::size_t first = p.level_offset[static_cast<std::size_t>(p.first_level)];
  for (int J = 0; J < side; ++J) {
    for (int I = 0; I < side; ++I) {
      float lo = lattice.at(I * block, J * block);
      float hi = lo;
      for (int j = J * block; j < (J + 1) * block; ++j) {
        for (int i = I * block; i < (I + 1) * block; ++i) {
          lo = std::min(lo, lattice.at(i, j));
          hi = std::max(hi, lattice.at(i, j));
        }
      }
      p.lo[first + static_cast<std::size_t>(J) * side + I] = lo;
      p.hi[first + static_cast<std::size_t>(J) * side + I] = hi;
    }
  }
  for (int l = p.first_level + 1; l <= p.log2_size; ++l) {
    const std::size_t below = p.level_offset[static_cast<std::size_t>(l - 1)];
    const std::size_t here = p.level_offset[static_cast<std::size_t>(l)];
    const std::size_t s = static_cast<std::size_t>(p.size) >> l;
    for (std::size_t J = 0; J < s; ++J) {
      for (std::size_t I = 0; I < s; ++I) {
        const std::size_t b[4] = {
            below + (2 * J) * (2 * s) + 2 * I, below + (2 * J) * (2 * s) + 2 * I + 1,
            below + (2 * J + 1) * (2 * s) + 2 * I, below + (2 * J + 1) * (2 * s) + 2 * I + 1};
        p.lo[here + J * s + I] =
            std::min(std::min(p.lo[b[0]], p.lo[b[1]]), std::min(p.lo[b[2]], p.lo[b[3]]));
        p.hi[here + J * s + I] =
            std::max(std::max(p.hi[b[0]], p.hi[b[1]]), std::max(p.hi[b[2]], p.hi[b[3]]));
      }
    }
  }
  return p;
}

ValueRange lattice_range(const LatticeRangePyramid& pyramid, const NoiseLattice& lattice,
                         std::int64_t i0, std::int64_t ni, std::int64_t j0, std::int64_t nj) {
  const std::int64_t size = pyramid.size;
  if (ni >= size || nj >= size) {
    return {pyramid.global_lo, pyramid.global_hi};
  }
  const std::int64_t mask = size - 1;
  i0 &= mask;  // two's complement: the periodic wrap of negative indices too
  j0 &= mask;
  float lo = lattice.at(static_cast<int>(i0), static_cast<int>(j0));
  float hi = lo;
  if (ni * nj <= kDirectScanValues) {
    for (std::int64_t j = j0; j < j0 + nj; ++j) {
      for (std::int64_t i = i0; i < i0 + ni; ++i) {
        const float v = lattice.at(static_cast<int>(i & mask), static_cast<int>(j & mask));
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    return {lo, hi};
  }
  // The finest stored level on which the range spans at most 3 texels per axis.
  int level = pyramid.first_level;
  while (level < pyramid.log2_size && (((i0 + ni - 1) >> level) - (i0 >> level) > 2 ||
                                       ((j0 + nj - 1) >> level) - (j0 >> level) > 2)) {
    ++level;
  }
  if (level >= pyramid.log2_size) {
    return {pyramid.global_lo, pyramid.global_hi};
  }
  const std::int64_t texel_mask = (size >> level) - 1;
  const std::size_t offset = pyramid.level_offset[static_cast<std::size_t>(level)];
  for (std::int64_t J = j0 >> level; J <= (j0 + nj - 1) >> level; ++J) {
    for (std::int64_t I = i0 >> level; I <= (i0 + ni - 1) >> level; ++I) {
      const std::size_t k =
          offset + static_cast<std::size_t>((J & texel_mask) * (size >> level) + (I & texel_mask));
      lo = std::min(lo, pyramid.lo[k]);
      hi = std::max(hi, pyramid.hi[k]);
    }
  }
  return {lo, hi};
}

namespace {

// The extremes of S over the rectangle [px0, px1] x [pz0, pz1] of lattice coordinates spanning
// at most kExactCells cells per axis (header): S at the rectangle's corners, where its sides
// cross lattice lines, and at the lattice points inside it.
template <Interpolant kKind>
ValueRange exact_range(const NoiseLattice& lattice, double px0, double px1, double pz0,
                       double pz1) {
  double xs[kExactCells + 1], zs[kExactCells + 1];
  int nx = 0, nz = 0;
  xs[nx++] = px0;
  for (double x = std::floor(px0) + 1.0; x < px1; x += 1.0) {
    xs[nx++] = x;
  }
  xs[nx++] = px1;
  zs[nz++] = pz0;
  for (double z = std::floor(pz0) + 1.0; z < pz1; z += 1.0) {
    zs[nz++] = z;
  }
  zs[nz++] = pz1;
  ValueRange r{1e300, -1e300};
  for (int b = 0; b < nz; ++b) {
    for (int a = 0; a < nx; ++a) {
      const double v = sample_lattice<kKind, double>(lattice, xs[a], zs[b]);
      r.lo = std::min(r.lo, v);
      r.hi = std::max(r.hi, v);
    }
  }
  return r;
}

ValueRange exact_range(Interpolant kind, const NoiseLattice& lattice, double px0, double px1,
                       double pz0, double pz1) {
  switch (kind) {
    case Interpolant::kLinear:
      return exact_range<Interpolant::kLinear>(lattice, px0, px1, pz0, pz1);
    case Interpolant::kCubic:
      return exact_range<Interpolant::kCubic>(lattice, px0, px1, pz0, pz1);
    case Interpolant::kQuintic:
      break;
  }
  return exact_range<Interpolant::kQuintic>(lattice, px0, px1, pz0, pz1);
}

// max |R / (R^2 + eps^2)| over R in [r_lo, r_hi] (§2.2's guarded 1/R, fbm.h): |g| grows with
// |R| up to its peak 1 / (2 eps) at |R| = eps and falls beyond, so the maximum is at an end of
// the interval or at +-eps inside it. Domain: eps > 0 (kRoughnessGuard).
double max_guarded_inverse(double r_lo, double r_hi, double eps) {
  const auto g = [eps](double r) { return std::abs(r) / (r * r + eps * eps); };
  double m = std::max(g(r_lo), g(r_hi));
  if ((r_lo <= eps && eps <= r_hi) || (r_lo <= -eps && -eps <= r_hi)) {
    m = 0.5 / eps;
  }
  return m;
}

}  // namespace

RegionalHeightBound::RegionalHeightBound(const TerrainPlan& terrain,
                                         const LatticeRangePyramid& pyramid)
    : terrain_(terrain), pyramid_(pyramid) {
  const double extreme = std::max(std::abs(double(pyramid.global_lo)), double(pyramid.global_hi));
  double sum = 0.0;  // sum_n a_n max |L|: the largest |partial sum| there can be
  for (int n = 0; n < terrain.octaves.count; ++n) {
    sum += terrain.octaves.amplitude[n] * extreme;
  }
  fbm_slack_ = limits::kHeightBoundSlack * sum;
  height_slack_ = limits::kHeightBoundSlack *
                  (terrain.amplitude * sum + std::abs(terrain.relative_base_height));
}

ValueRange RegionalHeightBound::octave_range(int n, double radius, double x0, double x1, double z0,
                                             double z1) const {
  const OctaveTable& o = terrain_.octaves;
  const WarpPlan& w = terrain_.warp;
  const double size = pyramid_.size;
  // Octave n samples offset + f u + W_n (fbm.h), u = d / horizontal_scale. W_k0 = t0 exactly;
  // with warping off, W_n = t0 for every octave (the stage never updates it); otherwise
  // |W_n| <= radius.
  const bool shifted = n == 0 || !w.enabled;
  const double shift_x = shifted ? w.t0x : 0.0, shift_z = shifted ? w.t0z : 0.0;
  const double f = o.frequency[n] * terrain_.inv_horizontal_scale;
  const double base_x = o.offset_x[n] + shift_x, base_z = o.offset_z[n] + shift_z;
  // Float's rounding of p, widened a thousandfold (header).
  const double reach_x = f * std::max(std::abs(x0), std::abs(x1));
  const double reach_z = f * std::max(std::abs(z0), std::abs(z1));
  const double margin_x =
      limits::kHeightBoundSlack * (size + reach_x + std::abs(shift_x) + radius) + 1e-12;
  const double margin_z =
      limits::kHeightBoundSlack * (size + reach_z + std::abs(shift_z) + radius) + 1e-12;
  const double px0 = base_x + f * x0 - radius - margin_x;
  const double px1 = base_x + f * x1 + radius + margin_x;
  const double pz0 = base_z + f * z0 - radius - margin_z;
  const double pz1 = base_z + f * z1 + radius + margin_z;
  const bool resolved = std::max({std::abs(px0), std::abs(px1), std::abs(pz0), std::abs(pz1)}) <
                        kMaxResolvedCoordinate;
  if (!resolved || !(px1 - px0 < size && pz1 - pz0 < size)) {
    return {pyramid_.global_lo, pyramid_.global_hi};
  }
  // The cells holding p0 .. p1 have corners floor(p0) .. floor(p1) + 1.
  const double i0 = std::floor(px0), i1 = std::floor(px1);
  const double j0 = std::floor(pz0), j1 = std::floor(pz1);
  if (i1 - i0 < kExactCells && j1 - j0 < kExactCells) {
    return exact_range(terrain_.interpolant, *terrain_.lattice, px0, px1, pz0, pz1);
  }
  return lattice_range(pyramid_, *terrain_.lattice, static_cast<std::int64_t>(i0),
                       static_cast<std::int64_t>(i1 - i0) + 2, static_cast<std::int64_t>(j0),
                       static_cast<std::int64_t>(j1 - j0) + 2);
}

ValueRange RegionalHeightBound::bound(double x0, double x1, double z0, double z1) const {
  const OctaveTable& o = terrain_.octaves;
  const WarpPlan& w = terrain_.warp;
  // Float rounding of the stage's unit rotation, guarded inverse and lacunarity product: each a
  // few ulps (2^-22 relative); 1 + kHeightBoundSlack covers them with room to spare.
  const double grow = 1.0 + limits::kHeightBoundSlack;
  const double eps = std::sqrt(w.guard_sq);  // > 0: kRoughnessGuard
  const double c3 = std::hypot(w.c3x, w.c3z);
  double lo = 0.0, hi = 0.0;  // bounds of the partial sum after octave n (all weights 1)
  double lowest = 1e300, highest = -1e300;
  double radius = std::hypot(w.t0x, w.t0z);  // bounds |W_n| for n >= 1 (header)
  for (int n = 0; n < o.count; ++n) {
    const ValueRange s = octave_range(n, w.enabled && n > 0 ? radius : 0.0, x0, x1, z0, z1);
    lo += o.amplitude[n] * s.lo;
    hi += o.amplitude[n] * s.hi;
    // §4.1's LOD: the height lies between two consecutive partial sums (header).
    lowest = std::min(lowest, lo);
    highest = std::max(highest, hi);
    if (w.enabled) {
      // §2.2 after octave n (fbm.h): W_n+1 = r (Rot W_n + c3 h_n R_n / (R_n^2 + eps^2)) with
      // R_n = R0 - h_n; the stage updates W only while every weight so far is 1, so h_n is the
      // partial sum, within [lo, hi] (and float's rounding).
      const double h_lo = lo - fbm_slack_, h_hi = hi + fbm_slack_;
      const double h_max = std::max(std::abs(h_lo), std::abs(h_hi));
      const double g = max_guarded_inverse(w.roughness0 - h_hi, w.roughness0 - h_lo, eps);
      radius = w.lacunarity * grow * (radius * grow + c3 * h_max * g * grow);
    }
  }
  if (o.count == 0) {  // a height field without the fractal: the sum is 0
    lowest = highest = 0.0;
  }
  return with_sketch({terrain_.relative_base_height + terrain_.amplitude * lowest - height_slack_,
                      terrain_.relative_base_height + terrain_.amplitude * highest + height_slack_},
                     x0, x1, z0, z1);
}

ValueRange RegionalHeightBound::with_sketch(ValueRange fractal, double x0, double x1, double z0,
                                            double z1) const {
  if (terrain_.sketch == nullptr) {
    return fractal;
  }
  // §3's sketch: the region's texels (height_sketch.h), exact but for float's rounding.
  const SketchRange s = sketch_range(terrain_.sketch_plan, *terrain_.sketch, x0, x1, z0, z1);
  const double slack = limits::kHeightBoundSlack * std::max(std::abs(s.lo), std::abs(s.hi));
  return {fractal.lo + s.lo - slack, fractal.hi + s.hi + slack};
}

ValueRange RegionalHeightBound::global() const {
  const OctaveTable& o = terrain_.octaves;
  double lo = 0.0, hi = 0.0;
  double lowest = 1e300, highest = -1e300;
  for (int n = 0; n < o.count; ++n) {
    lo += o.amplitude[n] * pyramid_.global_lo;
    hi += o.amplitude[n] * pyramid_.global_hi;
    lowest = std::min(lowest, lo);
    highest = std::max(highest, hi);
  }
  if (o.count == 0) {  // a height field without the fractal: the sum is 0
    lowest = highest = 0.0;
  }
  ValueRange fractal{terrain_.relative_base_height + terrain_.amplitude * lowest - height_slack_,
                     terrain_.relative_base_height + terrain_.amplitude * highest + height_slack_};
  if (terrain_.sketch != nullptr) {
    const double s_lo = terrain_.sketch->min_height, s_hi = terrain_.sketch->max_height;
    const double slack = limits::kHeightBoundSlack * std::max(std::abs(s_lo), std::abs(s_hi));
    fractal.lo += s_lo - slack;
    fractal.hi += s_hi + slack;
  }
  return fractal;
}

}  // namespace relief
