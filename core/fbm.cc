#include "core/fbm.h"

#include <cmath>

#include "core/interpolant.h"
#include "core/limits.h"
#include "core/octave_coordinates.h"

namespace relief {

namespace {

template <Interpolant kKind, class Real>
Real fbm_point(const FbmParams<Real>& c, const NoiseLattice& lattice, Real dx, Real dz, Real nu,
               std::uint64_t& octaves_summed) {
  const Real ux = dx * c.inv_scale;
  const Real uz = dz * c.inv_scale;
  // Octave n's coordinate g_n d, without offset and warp: exact modulo P or direct
  // (octave_coordinates.h, as the frame chose).
  const auto scaled = [&](int n, Real d, Real u) {
    if (!c.exact_coordinates[n]) {
      return c.frequency[n] * u;
    }
    Real d_hi, d_lo, piece[kScalePieces<Real>], hi[kScalePieces<Real>], lo[kScalePieces<Real>];
    split_halves(d, d_hi, d_lo);
    for (int q = 0; q < kScalePieces<Real>; ++q) {
      piece[q] = c.scale_piece[q][n];
      hi[q] = c.scale_piece_hi[q][n];
      lo[q] = c.scale_piece_lo[q][n];
    }
    return exact_scaled_mod(piece, hi, lo, d, d_hi, d_lo, c.period, c.inv_period);
  };
  const Real whole = std::floor(nu);
  const int full_octaves = whole < Real(c.count) ? static_cast<int>(whole) : c.count;
  const Real fraction = nu - whole;
  Real h = Real(0);
  Real wx = c.t0x, wz = c.t0z;  // W_n, §2.2, in lattice cells of octave n
  Real rx = c.r0x, rz = c.r0z;  // rot_n, §2.2
  for (int n = 0; n < c.count; ++n) {
    // §4.1: floor(nu) whole octaves, then one weighted by the fractional part.
    const Real weight = n < full_octaves ? Real(1) : fraction;
    if (n > full_octaves || weight == Real(0)) {
      break;
    }
    // Eq. 1: S(r^k x), camera-relative, displaced by the warp.
    const Real px = c.offset_x[n] + scaled(n, dx, ux) + wx;
    const Real pz = c.offset_z[n] + scaled(n, dz, uz) + wz;
    h = h + (weight * c.amplitude[n]) * sample_lattice<kKind>(lattice, px, pz);
    ++octaves_summed;
    if (!c.warp || n == full_octaves || n + 1 == c.count) {
      continue;  // no further octave reads W
    }
    // §2.2: roughness R_n = R0 - H_n and the guarded 1/R_n (limits.h, kRoughnessGuard).
    const Real roughness = c.roughness0 - h;
    const Real inv_roughness = roughness / (roughness * roughness + c.guard_sq);
    // §2.2: r_{n+1} = c1 R_n + c2 + r_n, renormalised; kept when its length vanishes
    // (the sqrt's domain: length_sq > kMinRotationLengthSq > 0).
    const Real vx = c.c1x * roughness + c.c2x + rx;
    const Real vz = c.c1z * roughness + c.c2z + rz;
    const Real length_sq = vx * vx + vz * vz;
    if (length_sq > c.min_rotation_sq) {
      const Real inv_length = Real(1) / std::sqrt(length_sq);
      rx = vx * inv_length;
      rz = vz * inv_length;
    }
    // §2.2: t_{n+1} = c3 H_n / R_n; W_{n+1} = r (Rot(r_{n+1}) W_n + t_{n+1}): rotate and
    // translate in octave n's cells, then rescale to octave n+1's cells.
    const Real height_over_roughness = h * inv_roughness;
    const Real next_wx = (rx * wx - rz * wz) + c.c3x * height_over_roughness;
    const Real next_wz = (rz * wx + rx * wz) + c.c3z * height_over_roughness;
    wx = c.lacunarity * next_wx;
    wz = c.lacunarity * next_wz;
  }
  return c.relative_base_height + c.height_scale * h;
}

template <Interpolant kKind, class Real>
FbmWork evaluate_range(const FbmParams<Real>& c, const NoiseLattice& lattice, IndexRange range,
                       std::span<const Real> dx, std::span<const Real> dz, std::span<const Real> nu,
                       std::span<const std::uint8_t> mask, std::span<Real> height) {
  FbmWork work;
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (!mask.empty() && !mask[k]) {
      height[k] = Real(0);  // not needed (core/vertex_culling.h): no consumer reads it
      continue;
    }
    height[k] = fbm_point<kKind>(c, lattice, dx[k], dz[k], nu[k], work.octaves);
    ++work.points;
  }
  return work;
}

}  // namespace

template <class Real>
FbmWork evaluate_fbm(const FbmParams<Real>& params, const NoiseLattice& lattice, IndexRange range,
                     std::span<const Real> dx, std::span<const Real> dz, std::span<const Real> nu,
                     std::span<const std::uint8_t> mask, std::span<Real> height) {
  switch (static_cast<Interpolant>(params.interpolant)) {
    case Interpolant::kLinear:
      return evaluate_range<Interpolant::kLinear>(params, lattice, range, dx, dz, nu, mask, height);
    case Interpolant::kCubic:
      return evaluate_range<Interpolant::kCubic>(params, lattice, range, dx, dz, nu, mask, height);
    case Interpolant::kQuintic:
      return evaluate_range<Interpolant::kQuintic>(params, lattice, range, dx, dz, nu, mask,
                                                   height);
  }
  return {};
}

template <class Real>
Real fbm_height(const TerrainPlan& plan, Real dx, Real dz, Real nu) {
  Real height = 0;
  FbmParams<Real> params = make_fbm_params<Real>(plan);
  const std::uint8_t valid = 1;
  choose_coordinate_forms(
      plan,
      octave_reach<Real>(IndexRange{0, 1}, std::span<const Real>(&dx, 1),
                         std::span<const Real>(&dz, 1), std::span<const Real>(&nu, 1),
                         std::span<const std::uint8_t>(&valid, 1)),
      params);
  evaluate_fbm<Real>(params, *plan.lattice, IndexRange{0, 1}, std::span<const Real>(&dx, 1),
                     std::span<const Real>(&dz, 1), std::span<const Real>(&nu, 1), {},
                     std::span<Real>(&height, 1));
  return height;
}

template FbmWork evaluate_fbm<float>(const FbmParams<float>&, const NoiseLattice&, IndexRange,
                                     std::span<const float>, std::span<const float>,
                                     std::span<const float>, std::span<const std::uint8_t>,
                                     std::span<float>);
template FbmWork evaluate_fbm<double>(const FbmParams<double>&, const NoiseLattice&, IndexRange,
                                      std::span<const double>, std::span<const double>,
                                      std::span<const double>, std::span<const std::uint8_t>,
                                      std::span<double>);
template float fbm_height<float>(const TerrainPlan&, float, float, float);
template double fbm_height<double>(const TerrainPlan&, double, double, double);

}  // namespace relief
