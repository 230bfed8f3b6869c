#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_bounds.h"
#include "core/lattice.h"
#include "core/limits.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

NoiseLattice uniform_lattice(int size, float value) {
  NoiseLattice l;
  l.size = size;
  l.mask = size - 1;
  l.values.assign(static_cast<std::size_t>(size) * size, value);
  l.min_value = l.max_value = value;
  return l;
}

// L(i, j) = alpha i + beta j: bilinear interpolation reproduces alpha x + beta z exactly
// inside [0, P - 1]^2 (the wrap seam excluded).
NoiseLattice linear_lattice(int size, float alpha, float beta) {
  NoiseLattice l;
  l.size = size;
  l.mask = size - 1;
  l.values.resize(static_cast<std::size_t>(size) * size);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      l.values[static_cast<std::size_t>(j) * size + i] = alpha * float(i) + beta * float(j);
    }
  }
  l.min_value = 0;
  l.max_value = alpha * float(size - 1) + beta * float(size - 1);
  return l;
}

TerrainSettings six_octaves(bool warp) {
  TerrainSettings t;
  t.first_octave = 0;
  t.last_octave = 5;
  t.base_height = 10.0;
  t.amplitude = 100.0;
  t.horizontal_scale = 50.0;
  t.warp.enabled = warp;
  return t;
}

// Closed form of Eq. 1 with S == c: base + A c (sum of whole octaves + frac * next).
double constant_lattice_height(const TerrainSettings& t, double c, double nu) {
  double sum = 0;
  const int count = t.last_octave - t.first_octave + 1;
  for (int n = 0; n < count; ++n) {
    const double a = std::pow(t.r, -(t.first_octave + n) * t.H);
    const double w = n < std::floor(nu) ? 1.0 : (n == std::floor(nu) ? nu - std::floor(nu) : 0.0);
    sum += w * a;
  }
  return t.base_height + t.amplitude * c * sum;
}

TEST_CASE("fbmMatchesTheClosedFormOnAConstantLattice", "[fbm]") {
  const NoiseLattice lattice = uniform_lattice(16, 0.7f);
  for (bool warp : {false, true}) {
    const TerrainSettings t = six_octaves(warp);
    const TerrainPlan plan = make_terrain_plan(t, lattice, {123.0, 0.0, -77.0});
    for (double nu : {0.0, 0.3, 1.0, 1.5, 3.25, 5.999, 6.0, 9.0}) {
      const double expected = constant_lattice_height(t, 0.7f, nu);
      for (double d : {0.0, 13.7, -2500.0}) {
        CHECK(fbm_height<double>(plan, d, -d, nu) == Approx(expected).epsilon(1e-14));
        CHECK(fbm_height<float>(plan, float(d), float(-d), float(nu)) ==
              Approx(expected).epsilon(2e-6));
      }
    }
  }
}

TEST_CASE("fbmMatchesTheClosedFormOnALinearLattice", "[fbm]") {
  // Three octaves, bilinear: H = base + A sum_n w_n a_n (alpha px_n + beta pz_n) with
  // p_n = offset_n + f_n d / scale, wherever every p_n stays inside [0, P - 1].
  const float alpha = 1.0f / 64, beta = -1.0f / 128;
  const NoiseLattice lattice = linear_lattice(1024, alpha, beta);
  TerrainSettings t = six_octaves(false);
  t.last_octave = 2;
  t.interpolant = Interpolant::kLinear;
  const TerrainPlan plan = make_terrain_plan(t, lattice, {5000.0, 0.0, 9000.0});
  test::TestRandom random(21);
  int checked = 0;
  for (int k = 0; k < 4000; ++k) {
    const double dx = random.uniform(-4000, 4000), dz = random.uniform(-4000, 4000);
    const double nu = random.uniform(0, 3);
    double expected = t.base_height;
    bool inside = true;
    for (int n = 0; n < 3; ++n) {
      const double px =
          plan.octaves.offset_x[n] + plan.octaves.frequency[n] * dx / t.horizontal_scale;
      const double pz =
          plan.octaves.offset_z[n] + plan.octaves.frequency[n] * dz / t.horizontal_scale;
      inside = inside && px >= 0 && px < 1023 && pz >= 0 && pz < 1023;
      const double w = n < std::floor(nu) ? 1.0 : (n == std::floor(nu) ? nu - std::floor(nu) : 0.0);
      expected += t.amplitude * w * plan.octaves.amplitude[n] * (alpha * px + beta * pz);
    }
    if (inside) {
      ++checked;
      REQUIRE(fbm_height<double>(plan, dx, dz, nu) == Approx(expected).epsilon(1e-12));
    }
  }
  CHECK(checked > 100);
}

TEST_CASE("fbmIsContinuousInTheOctaveCount", "[fbm]") {
  // §4.1 geomorphing: dH/dnu = A a_n S_n, so |H(nu + e) - H(nu)| <= A max(a) max|L| e, also
  // across integers, where one octave reaches full weight and the next starts from zero.
  const NoiseLattice lattice = make_noise_lattice(1, 64);
  for (bool warp : {false, true}) {
    const TerrainSettings t = six_octaves(warp);
    const TerrainPlan plan = make_terrain_plan(t, lattice, {0.0, 0.0, 0.0});
    const double lipschitz =
        t.amplitude * std::max(-lattice.min_value, lattice.max_value) * 1.0000001;
    test::TestRandom random(4);
    for (int k = 0; k < 50; ++k) {
      const double dx = random.uniform(-500, 500), dz = random.uniform(-500, 500);
      for (double nu = 0.0; nu < 6.0; nu += 0.01) {
        const double step = 0.01;
        const double h0 = fbm_height<double>(plan, dx, dz, nu);
        const double h1 = fbm_height<double>(plan, dx, dz, nu + step);
        REQUIRE(std::abs(h1 - h0) <= lipschitz * step + 1e-9);
      }
      for (int n = 1; n < 6; ++n) {
        const double e = 1e-9;
        const double below = fbm_height<double>(plan, dx, dz, n - e);
        const double at = fbm_height<double>(plan, dx, dz, n);
        const double above = fbm_height<double>(plan, dx, dz, n + e);
        REQUIRE(std::abs(at - below) <= lipschitz * e * 1.01 + 1e-9);
        REQUIRE(std::abs(above - at) <= lipschitz * e * 1.01 + 1e-9);
      }
    }
  }
}

TEST_CASE("fbmAmplitudeBoundReallyBoundsTheHeight", "[fbm]") {
  const NoiseLattice lattice = make_noise_lattice(1, 64);
  for (bool warp : {false, true}) {
    for (Interpolant kind : {Interpolant::kLinear, Interpolant::kCubic, Interpolant::kQuintic}) {
      TerrainSettings t = six_octaves(warp);
      t.interpolant = kind;
      const HeightBounds bounds = derive_height_bounds(lattice, t);
      const TerrainPlan plan = make_terrain_plan(t, lattice, {0.0, 0.0, 0.0});
      test::TestRandom random(8);
      double lowest = 1e300, highest = -1e300;
      for (int k = 0; k < 50000; ++k) {
        const double dx = random.uniform(-5000, 5000), dz = random.uniform(-5000, 5000);
        const double nu = k % 2 ? 6.0 : random.uniform(0, 6);
        const double hd = fbm_height<double>(plan, dx, dz, nu);
        const float hf = fbm_height<float>(plan, float(dx), float(dz), float(nu));
        lowest = std::min({lowest, hd, double(hf)});
        highest = std::max({highest, hd, double(hf)});
      }
      CHECK(lowest >= bounds.world_min);
      CHECK(highest <= bounds.world_max);
      // ...and it is a bound of this terrain, not of some other scale: within a factor 6.
      CHECK(bounds.world_max - t.base_height < 6 * (highest - t.base_height));
    }
  }
}

TEST_CASE("warpedAndPlainTerrainsDifferButShareTheirFirstOctave", "[fbm]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  const TerrainPlan plain = make_terrain_plan(six_octaves(false), lattice, {0.0, 0.0, 0.0});
  const TerrainPlan lava = make_terrain_plan(six_octaves(true), lattice, {0.0, 0.0, 0.0});
  test::TestRandom random(2);
  double diff_sq = 0, plain_sq = 0;
  for (int k = 0; k < 5000; ++k) {
    const double dx = random.uniform(-5000, 5000), dz = random.uniform(-5000, 5000);
    // §2.2 with r0 = (1, 0), t0 = 0: the first octave is not displaced.
    REQUIRE(fbm_height<double>(plain, dx, dz, 1.0) == fbm_height<double>(lava, dx, dz, 1.0));
    const double p = fbm_height<double>(plain, dx, dz, 6.0) - 10.0;
    const double w = fbm_height<double>(lava, dx, dz, 6.0) - 10.0;
    diff_sq += (w - p) * (w - p);
    plain_sq += p * p;
  }
  CHECK(std::sqrt(diff_sq / plain_sq) > 0.2);
}

// The largest |dS/dx| (and |dS/dz|) of the interpolated lattice, per lattice cell: along x,
// S = (1 - fade(tz)) lerp(L00, L10, fade(tx)) + fade(tz) lerp(L01, L11, fade(tx)), so
// dS/dx = fade'(tx) ((1 - fade(tz)) (L10 - L00) + fade(tz) (L11 - L01)), a convex combination
// of two lattice differences times the fade's slope: at most (max L - min L) max fade', with
// max fade' = 1 (linear), 3/2 (cubic, at t = 1/2) and 15/8 (quintic, at t = 1/2).
double lattice_gradient_bound(const NoiseLattice& l, Interpolant interpolant) {
  const double max_fade_slope[] = {1.0, 1.5, 1.875};
  return (double(l.max_value) - double(l.min_value)) *
         max_fade_slope[static_cast<int>(interpolant)];
}

TEST_CASE("plainTerrainSlopeStaysWithinItsLipschitzBound", "[fbm]") {
  // Without the warp, octave n samples S at offset_n + f_n x / horizontal_scale, so
  //   |dH/dx| <= amplitude * sum_n a_n * G * f_n / horizontal_scale   (G: the gradient bound)
  // and two heights a step s apart differ by at most that times s. A jump (a cell located on
  // the wrong side, a seam of the wrapped lattice) exceeds it at once.
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  for (const Interpolant kind :
       {Interpolant::kLinear, Interpolant::kCubic, Interpolant::kQuintic}) {
    TerrainSettings t = six_octaves(false);
    t.interpolant = kind;
    const TerrainPlan plan = make_terrain_plan(t, lattice, {0.0, 0.0, 0.0});
    const double gradient = lattice_gradient_bound(lattice, kind);
    double slope_sum = 0;
    for (int n = 0; n < plan.octaves.count; ++n) {
      slope_sum += plan.octaves.amplitude[n] * gradient * plan.octaves.frequency[n];
    }
    const double lipschitz = plan.amplitude * slope_sum * plan.inv_horizontal_scale;
    const double step = 1e-4;
    double steepest = 0;
    for (double x = -3000; x < 3000; x += 0.5) {
      const double a = fbm_height<double>(plan, x, 17.0, 6.0);
      const double b = fbm_height<double>(plan, x + step, 17.0, 6.0);
      // Double rounding of heights near 100: below 1e-12.
      REQUIRE(std::abs(b - a) <= lipschitz * step + 1e-9);
      steepest = std::max(steepest, std::abs(b - a) / step);
    }
    INFO("steepest slope " << steepest << " against the bound " << lipschitz);
    CHECK(steepest > 0);
  }
}

// The partial height h_m (octaves 0 .. m - 1, without base and amplitude) at (x, z): the
// height with nu = m sums exactly those octaves, warped as in the full sum (fbm.h).
double partial_height(const TerrainPlan& plan, double x, double z, int m) {
  return (fbm_height<double>(plan, x, z, double(m)) - plan.relative_base_height) / plan.amplitude;
}

// A bound on |dH/dx| of the warped terrain at (x, z), with nu = N, propagated through fbm.h's
// recurrence from the point's own partial heights (the warp's gain depends on where it is).
// Per unit of u = x / horizontal_scale, with |.| the Euclidean norm and D[.] a bound on the
// derivative's norm:
//   p_n = offset_n + f_n u e_x + W_n:   |dS_n| <= G (f_n + sqrt(2) D[W_n])  (G as above)
//   h_n+1 = h_n + a_n S_n:              D[h_n+1] <= D[h_n] + a_n |dS_n|
//   R = R0 - h_n+1, v = c1 R + c2 + rot_n, rot_n+1 = v / |v|:
//                                       D[rot_n+1] <= (|c1| D[h_n+1] + D[rot_n]) / |v|
//   t = c3 phi(h), phi = h R / (R^2 + eps^2), phi'(h) = R / (R^2 + eps^2)
//                                                     - h (eps^2 - R^2) / (R^2 + eps^2)^2:
//                                       D[t] <= |c3| |phi'(h_n+1)| D[h_n+1]
//   W_n+1 = r (Rot(rot_n+1) W_n + t):   D[W_n+1] <= r (D[rot_n+1] |W_n| + D[W_n] + D[t])
// (Rot(q) w has norm |q| |w|, and rot stays a unit vector.) The guard keeps |phi'| finite
// where R crosses zero: at most 1/(2 eps) + |h| / eps^2.
double warped_slope_bound(const TerrainPlan& plan, double x, double z) {
  const WarpPlan& w = plan.warp;
  const OctaveTable& o = plan.octaves;
  const double gradient = lattice_gradient_bound(*plan.lattice, plan.interpolant);
  const double c1 = std::hypot(w.c1x, w.c1z), c3 = std::hypot(w.c3x, w.c3z);
  double wx = w.t0x, wz = w.t0z, rx = w.r0x, rz = w.r0z;  // W_n and rot_n at the point
  double d_h = 0, d_w = 0, d_rot = 0;
  for (int n = 0; n < o.count; ++n) {
    d_h += o.amplitude[n] * gradient * (o.frequency[n] + std::sqrt(2.0) * d_w);
    if (n + 1 == o.count) {
      break;
    }
    const double h = partial_height(plan, x, z, n + 1);
    const double r = w.roughness0 - h;
    const double q = r * r + w.guard_sq;
    const double vx = w.c1x * r + w.c2x + rx, vz = w.c1z * r + w.c2z + rz;
    const double length = std::hypot(vx, vz);
    if (length * length > limits::kMinRotationLengthSq) {
      d_rot = (c1 * d_h + d_rot) / length;
      rx = vx / length;
      rz = vz / length;
    }
    const double phi_slope = std::abs(r / q - h * (w.guard_sq - r * r) / (q * q));
    const double d_t = c3 * phi_slope * d_h;
    d_w = w.lacunarity * (d_rot * std::hypot(wx, wz) + d_w + d_t);
    const double t = h * r / q;
    const double next_x = (rx * wx - rz * wz) + w.c3x * t;
    const double next_z = (rz * wx + rx * wz) + w.c3z * t;
    wx = w.lacunarity * next_x;
    wz = w.lacunarity * next_z;
  }
  return plan.amplitude * d_h * plan.inv_horizontal_scale;
}

TEST_CASE("warpedTerrainIsContinuousInPosition", "[fbm]") {
  // The guarded 1/R keeps the warp continuous where the roughness R crosses zero: two heights
  // a step s apart differ by at most s times the slope bound of warped_slope_bound, which a
  // jump would exceed whatever the step. The bound is evaluated at both ends of the step and
  // doubled: over 1e-4 units the quantities it reads (|v|, phi', |W|) change by a relative
  // 1e-4 times their own slopes, far below a factor 2.
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  const TerrainSettings t = six_octaves(true);
  const TerrainPlan lava = make_terrain_plan(t, lattice, {0.0, 0.0, 0.0});
  const double step = 1e-4;
  double worst_ratio = 0;
  for (double x = -3000; x < 3000; x += 0.5) {
    const double a = fbm_height<double>(lava, x, 17.0, 6.0);
    const double b = fbm_height<double>(lava, x + step, 17.0, 6.0);
    const double slope_bound =
        std::max(warped_slope_bound(lava, x, 17.0), warped_slope_bound(lava, x + step, 17.0));
    REQUIRE(std::abs(b - a) <= 2.0 * slope_bound * step + 1e-9);
    worst_ratio = std::max(worst_ratio, std::abs(b - a) / (slope_bound * step));
  }
  INFO("largest step difference over the local bound: " << worst_ratio);
  CHECK(worst_ratio > 0);
}

// A priori bound on |H_float - H_double| for the unwarped fBm at one point, from the rounding
// of each float operation (unit roundoff e = 2^-24):
//   u = d * (1/scale):                  |du| <= 2e |u|
//   q = f u, f = float(r^k):            |dq| <= 4e |q|     (f itself rounded, then the product)
//   p = offset + q, offset rounded:     |dp| <= e (|offset| + |p| + P) + |dq|  (P: the wrap)
//   S moves by at most G |dp| per axis, G = (Lmax - Lmin) max|fade'|, plus 6 e M for the lerps
//   sum: each of the N additions rounds by e |partial| <= e sum(a) M.
double plain_float_error_bound(const TerrainPlan& plan, const NoiseLattice& l, double dx, double dz,
                               double nu) {
  const double e = 0x1.0p-24;
  const double fade_slope[] = {1.0, 1.5, 1.875};
  const double m = std::max(-l.min_value, l.max_value);
  const double g = (l.max_value - l.min_value) * fade_slope[static_cast<int>(plan.interpolant)];
  const OctaveTable& o = plan.octaves;
  double amplitude_sum = 0, bound = 0;
  for (int n = 0; n < o.count && n <= nu; ++n) {
    const double ux = dx * plan.inv_horizontal_scale, uz = dz * plan.inv_horizontal_scale;
    const double qx = o.frequency[n] * ux, qz = o.frequency[n] * uz;
    const double px = std::abs(o.offset_x[n] + qx), pz = std::abs(o.offset_z[n] + qz);
    const double dpx = e * (o.offset_x[n] + px + l.size) + 6 * e * std::abs(qx);
    const double dpz = e * (o.offset_z[n] + pz + l.size) + 6 * e * std::abs(qz);
    bound += o.amplitude[n] * (g * (dpx + dpz) + 6 * e * m);
    amplitude_sum += o.amplitude[n];
  }
  bound += o.count * e * amplitude_sum * m;
  const double height = plan.relative_base_height + plan.amplitude * amplitude_sum * m;
  return plan.amplitude * bound * 1.01 + 2 * e * std::abs(height);
}

TEST_CASE("fbmFloatErrorStaysWithinItsDerivedBound", "[fbm]") {
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  for (Interpolant kind : {Interpolant::kLinear, Interpolant::kCubic, Interpolant::kQuintic}) {
    TerrainSettings t;  // the default terrain: 15 octaves, amplitude 360
    t.interpolant = kind;
    const TerrainPlan plan = make_terrain_plan(t, lattice, {3.0e6, 0.0, -7.0e8});
    test::TestRandom random(3);
    double worst = 0, worst_ratio = 0;
    for (int k = 0; k < 20000; ++k) {
      const float dx = float(random.uniform(-3000, 3000));
      const float dz = float(random.uniform(-3000, 3000));
      const float nu = float(random.uniform(1, 15));
      const double error =
          std::abs(fbm_height<float>(plan, dx, dz, nu) - fbm_height<double>(plan, dx, dz, nu));
      const double bound = plain_float_error_bound(plan, lattice, dx, dz, nu);
      REQUIRE(error <= bound);
      worst = std::max(worst, error);
      worst_ratio = std::max(worst_ratio, error / bound);
    }
    INFO("worst float error " << worst << ", worst error / bound " << worst_ratio);
    CHECK(worst < 0.02);  // the bound is not vacuous either: below 1e-4 of the amplitude
  }
}

TEST_CASE("warpedFbmFloatErrorIsSmallExceptNearTheRoughnessZero", "[fbm]") {
  // The warp feeds each octave's height back into the next octave's position, so no useful
  // a-priori bound exists where the roughness R crosses zero (its guarded reciprocal has
  // slope 1/eps^2 there). Elsewhere float tracks double like the plain terrain does.
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  TerrainSettings t;
  t.warp.enabled = true;
  const TerrainPlan plan = make_terrain_plan(t, lattice, {0.0, 0.0, 0.0});
  test::TestRandom random(3);
  std::vector<double> errors;
  for (int k = 0; k < 20000; ++k) {
    const float dx = float(random.uniform(-3000, 3000));
    const float dz = float(random.uniform(-3000, 3000));
    const float nu = float(random.uniform(1, 15));
    errors.push_back(
        std::abs(fbm_height<float>(plan, dx, dz, nu) - fbm_height<double>(plan, dx, dz, nu)));
  }
  std::sort(errors.begin(), errors.end());
  const auto percentile = [&](double p) { return errors[std::size_t(p * (errors.size() - 1))]; };
  INFO("median " << percentile(0.5) << ", p99 " << percentile(0.99) << ", p99.9 "
                 << percentile(0.999) << ", max " << errors.back());
  CHECK(percentile(0.5) < 0.005);
  CHECK(percentile(0.99) < 0.15);
  CHECK(errors.back() < 5.0);  // 0.4% of the terrain's 1400 units of relief
}

}  // namespace
}  // namespace relief
