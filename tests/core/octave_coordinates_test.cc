// Each octave's lattice coordinate keeps the precision of its type at every octave a scene
// allows (core/octave_coordinates.h): the exact form against an independent reduction, the
// frame's choice of form, and float heights against double over the accepted range of r, H
// and octave counts.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/octave_coordinates.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "pipeline/basis_resources.h"
#include "pipeline/scene_resources.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// g d mod P from an independent route: the product split exactly in double (d is a float, so
// d * g is at most 77 bits: a double product plus its exact error, found with std::fma, which
// is correctly rounded by definition), each part reduced with the exact std::fmod, summed in
// long double.
long double reference_scaled_mod(double g, float d, double period) {
  const double product = double(d) * g;
  const double error = std::fma(double(d), g, -product);
  long double sum = (long double)std::fmod(product, period) + std::fmod(error, period);
  sum = std::fmod(sum, (long double)period);
  return sum < 0 ? sum + period : sum;
}

// The distance between two coordinates on the circle of circumference P.
double circular_distance(long double a, long double b, double period) {
  const long double d = std::fmod(std::abs(a - b), (long double)period);
  return double(std::min(d, period - d));
}

TEST_CASE("theExactFormKeepsTheProductModuloThePeriodToAFewUlpAtEveryMagnitude", "[octaves]") {
  test::TestRandom random(11);
  for (const double period : {4.0, 256.0, 4096.0}) {
    double worst_float = 0, worst_double = 0;
    for (int k = 0; k < 200000; ++k) {
      // |g d| from 2^-10 to 2^64, the most a scene allows (limits.h: coarsest octave below
      // 2^24 cells at the farthest footprint, r^k <= 2^40 more for the finest).
      const double magnitude = std::exp2(random.uniform(-10, 64));
      const float d =
          float(std::exp2(random.uniform(-20, 37)) * (random.uniform(0, 1) < 0.5 ? -1 : 1));
      const double g = magnitude / std::abs(double(d)) * random.uniform(1, 2);
      const long double expected = reference_scaled_mod(g, d, period);
      const auto f = split_scale<float>(g);
      float f_hi, f_lo;
      split_halves(d, f_hi, f_lo);
      const float got_float =
          exact_scaled_mod(f.piece, f.hi, f.lo, d, f_hi, f_lo, float(period), float(1 / period));
      const auto dd = split_scale<double>(g);
      double d_hi, d_lo;
      split_halves(double(d), d_hi, d_lo);
      const double got_double =
          exact_scaled_mod(dd.piece, dd.hi, dd.lo, double(d), d_hi, d_lo, period, 1 / period);
      REQUIRE(got_float >= 0.0f);
      REQUIRE(got_float <= float(period));
      worst_float = std::max(worst_float, circular_distance(got_float, expected, period));
      worst_double = std::max(worst_double, circular_distance(got_double, expected, period));
    }
    INFO("P " << period << ": worst float " << worst_float << ", worst double " << worst_double);
    // Six wrapped sums of values below 2P, each rounding by half an ulp of 2P at most.
    CHECK(worst_float <= 6 * period * 0x1p-23);
    CHECK(worst_double <= 2 * period * 0x1p-52);
    CHECK(worst_float > 0);  // the measure is not blind
  }
}

TEST_CASE("theDirectFormIsWhatFramesOfTheShippedScenesUseAndFineOctavesGetTheExactOne",
          "[octaves]") {
  const auto exact_octaves = [](const char* preset, const std::vector<std::string>& overrides) {
    const Scene scene = resolve_scene(preset, overrides);
    const std::optional<NoiseLattice> basis = load_basis_grid(scene);  // stage 3's grid
    const NoiseLattice lattice =
        basis ? *basis : make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const std::optional<HeightSketch> sketch = load_height_sketch(scene);
    const FramePlan plan = make_frame_plan(scene, lattice, sketch ? &*sketch : nullptr);
    TerrainParams<float> params = make_terrain_params<float>(plan);
    GridBuffers<float> b(plan.layout);
    project_domain<float>(params.domain, params.domain_rows, {0, plan.layout.height}, b.domain());
    const OctaveReach reach =
        octave_reach<float>(IndexRange{0, b.layout.size()}, b.dx, b.dz, b.nu, b.valid);
    choose_coordinate_forms(plan.terrain, reach, params.fbm);
    int exact = 0;
    for (int n = 0; n < params.fbm.count; ++n) {
      exact += params.fbm.exact_coordinates[n];
      // Direct only where the product stays within a period.
      if (!params.fbm.exact_coordinates[n]) {
        CHECK(plan.terrain.octaves.scale[n] * reach.extent[n] <= lattice.size);
      }
    }
    return exact;
  };
  // Not the basis presets (craters, badlands): their image tiles span 8 and 10 km, less than
  // the view's reach, so the coarse octaves' coordinates pass one period and take the exact
  // form, as they must.
  for (const char* preset : {"default", "alpine", "dunes", "island", "lake", "lava", "plain"}) {
    INFO(preset);
    CHECK(exact_octaves(preset, {}) == 0);
  }
  CHECK(exact_octaves("craters", {}) > 0);  // and direct only within a period (checked inside)
  // The case: r = 2, H = 0.05 sums all 24 octaves out to the horizon.
  CHECK(exact_octaves("default", {"terrain.H=0.05", "terrain.last_octave=23"}) >= 8);
}

// A double as --set writes it, to the last bit.
std::string exact_text(double value) {
  std::ostringstream text;
  text << std::setprecision(17) << value;
  return text.str();
}

struct HeightError {
  double max = 0, median = 0;
  double worst_ratio = 0;  // largest error / a-priori bound over the vertices
  double amplitude_sum = 0;
};

// A-priori bound on |H_float - H_double| at one point of the unwarped fBm, from the rounding of
// each float operation (unit roundoff e = 2^-24), the same derivation as fbm_test.cc's for the
// direct form, with the exact form's own term:
//   direct: G = float(r^k) * (d * float(1/scale)):  |dG| <= 4e |G|
//   exact:  G = g d mod P, one rounding below 2P and a wrap:  |dG| <= 3e P
//   p = offset + G (+ W = 0), offset rounded:  |dp| <= e (|offset| + |p| + P) + |dG|
//   S moves by at most slope |dp| per axis, slope = (Lmax - Lmin) max|fade'|, + 6e M (lerps);
//   the sum: each of the N additions rounds by e |partial| <= e sum(a) M.
double float_error_bound(const TerrainPlan& plan, const FbmParams<float>& forms,
                         const NoiseLattice& l, double dx, double dz, double nu) {
  const double e = 0x1.0p-24;
  const double fade_slope[] = {1.0, 1.5, 1.875};
  const double m = std::max(-l.min_value, l.max_value);
  const double slope = (l.max_value - l.min_value) * fade_slope[static_cast<int>(plan.interpolant)];
  const double period = l.size;
  const OctaveTable& o = plan.octaves;
  double amplitude_sum = 0, bound = 0;
  for (int n = 0; n < o.count && n < nu; ++n) {
    double dp[2];
    const double d[2] = {dx, dz};
    const double offset[2] = {o.offset_x[n], o.offset_z[n]};
    for (int axis = 0; axis < 2; ++axis) {
      const double g = o.scale[n] * d[axis];
      const double term = forms.exact_coordinates[n] ? 3 * e * period : 4 * e * std::abs(g);
      const double p = std::abs(offset[axis] + g);
      dp[axis] = e * (offset[axis] + p + period) + term;
    }
    bound += o.amplitude[n] * (slope * (dp[0] + dp[1]) + 6 * e * m);
    amplitude_sum += o.amplitude[n];
  }
  bound += o.count * e * amplitude_sum * m;
  const double height = plan.relative_base_height + plan.amplitude * amplitude_sum * m;
  return plan.amplitude * bound * 1.01 + 2 * e * std::abs(height);
}

// Float stage 3 of a frame (its own choice of forms) against double stage 3 at the same float
// inputs (every octave in the exact form): the arithmetic of stage 3 alone, as a
// re-implementation that reads the frame's domain buffer sees it.
HeightError float_versus_double_fbm(const Scene& scene) {
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> f(plan.layout);
  run_terrain_stages(plan, f);  // chooses the forms as below
  FbmParams<float> forms = make_fbm_params<float>(plan.terrain);
  choose_coordinate_forms(
      plan.terrain, octave_reach<float>(IndexRange{0, f.layout.size()}, f.dx, f.dz, f.nu, f.valid),
      forms);
  const FbmParams<double> exact = make_fbm_params<double>(plan.terrain);
  std::vector<double> errors;
  HeightError e;
  for (std::size_t k = 0; k < f.layout.size(); ++k) {
    if (!f.valid[k]) {
      continue;
    }
    const double dx = f.dx[k], dz = f.dz[k], nu = f.nu[k];
    double height = 0;
    evaluate_fbm<double>(exact, lattice, IndexRange{0, 1}, {&dx, 1}, {&dz, 1}, {&nu, 1}, {},
                         {&height, 1});
    const double error = std::abs(height - double(f.height[k]));
    errors.push_back(error);
    if (!scene.terrain.warp.enabled) {
      e.worst_ratio = std::max(e.worst_ratio,
                               error / float_error_bound(plan.terrain, forms, lattice, dx, dz, nu));
    }
  }
  std::sort(errors.begin(), errors.end());
  e.max = errors.empty() ? 0 : errors.back();
  e.median = errors.empty() ? 0 : errors[errors.size() / 2];
  for (int n = 0; n < plan.terrain.octaves.count; ++n) {
    e.amplitude_sum += plan.terrain.octaves.amplitude[n];
  }
  e.amplitude_sum *= scene.terrain.amplitude;
  return e;
}

// The figure of the default scene: below 1e-4 of the amplitude sum (the relief's scale; the
// default sits at 2e-5), and every vertex within the a-priori bound above.
constexpr double kRelativeBound = 1e-4;

TEST_CASE("fineOctavesKeepFloatHeightsWithinTheDefaultScenesBoundOverTheAcceptedRange",
          "[octaves][precision]") {
  const std::vector<std::string> small = {"grid.width=96", "grid.height=96"};
  const HeightError reference = float_versus_double_fbm(resolve_scene("default", small));
  INFO("default: max " << reference.max << " = " << reference.max / reference.amplitude_sum
                       << " of the amplitude sum");
  REQUIRE(reference.max <= kRelativeBound * reference.amplitude_sum);
  REQUIRE(reference.worst_ratio <= 1.0);
  int cases = 0;
  for (const double r : {1.001, 2.0, 2.17, 3.0, 16.0}) {
    const double log2_r = std::log2(r);
    const double smallest_h = std::max(0.00025, 0x1p-10 / log2_r);
    const int last = std::min(23, static_cast<int>(std::floor(40 / log2_r)));
    for (const double h : {smallest_h, 0.05, 0.5, 1.0}) {
      if (h < smallest_h) {
        continue;
      }
      for (const double scale : {0.01, 3000.0}) {
        for (const char* camera : {"0", "1e9"}) {
          std::vector<std::string> overrides = small;
          overrides.push_back("terrain.r=" + exact_text(r));
          overrides.push_back("terrain.H=" + exact_text(h));
          overrides.push_back("terrain.last_octave=" + std::to_string(last));
          overrides.push_back("terrain.horizontal_scale=" + exact_text(scale));
          overrides.push_back(std::string("camera.position=[") + camera + ", 700, 0]");
          const Scene scene = resolve_scene("default", overrides);  // accepted, or throws
          const HeightError e = float_versus_double_fbm(scene);
          INFO("r " << r << ", H " << h << ", octaves 0.." << last << ", scale " << scale
                    << ", camera x " << camera << ": median " << e.median << ", max " << e.max
                    << " = " << e.max / e.amplitude_sum << " of the amplitude sum, "
                    << e.worst_ratio << " of the a-priori bound");
          // Every vertex within the bound; and the relief-relative figure of the default
          // scene where the scale is not far below the lattice's own (at 0.01 world units a
          // cell, every vertex lands on a random lattice spot and the worst of them on the
          // steepest: the bound still holds, the maximum is 1.6e-4 of the amplitude sum).
          CHECK(e.worst_ratio <= 1.0);
          if (scale > 1) {
            CHECK(e.max <= kRelativeBound * e.amplitude_sum);
          }
          ++cases;
        }
      }
    }
  }
  CHECK(cases >= 60);
  // The warp at the Hurst exponents where its feedback stays tame (docs/scene-limits.md,
  // "Warping": with a small H the float warp departs from double however its coordinates
  // are formed).
  for (const double r : {2.0, 2.17, 16.0}) {
    for (const double h : {0.85, 1.0}) {
      std::vector<std::string> overrides = small;
      overrides.push_back("terrain.r=" + exact_text(r));
      overrides.push_back("terrain.H=" + exact_text(h));
      overrides.push_back("terrain.last_octave=" +
                          std::to_string(std::min(23, static_cast<int>(40 / std::log2(r)))));
      overrides.push_back("terrain.warp.enabled=true");
      const HeightError e = float_versus_double_fbm(resolve_scene("default", overrides));
      INFO("warped, r " << r << ", H " << h << ": max " << e.max);
      CHECK(e.max <= kRelativeBound * e.amplitude_sum);
    }
  }
}

}  // namespace
}  // namespace relief
