#include "tests/gl/gl_terrain_support.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/octave_coordinates.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "gpu/gl_terrain.h"
#include "pipeline/scene_resources.h"
#include "tests/gl/gl_arithmetic.h"
#include "tests/gl/gl_test_context.h"
#include "tests/oracles/gl_interpolation_bound.h"  // float_ulp

namespace relief::test {

namespace {

constexpr double kUnit = kFloatUnit;  // the largest relative spacing of floats (gl_arithmetic.h)

// The sine of the angle between vertex k's two tangents (x, h, z), as stage 4 forms them
// from `g`'s streams (central, one-sided next to invalid vertices); 1 where there are not
// two: the condition number of the normal (docs/gl-backend.md).
double tangent_sine(const GridBuffers<float>& g, int i, int j) {
  const GridLayout& l = g.layout;
  const auto valid_at = [&](int ii, int jj) {
    return ii >= 0 && ii < l.width && jj >= 0 && jj < l.height && g.valid[l.index(ii, jj)];
  };
  const auto tangent = [&](int di, int dj, double t[3]) {
    const bool minus = valid_at(i - di, j - dj), plus = valid_at(i + di, j + dj);
    const std::size_t from = minus ? l.index(i - di, j - dj) : l.index(i, j);
    const std::size_t to = plus ? l.index(i + di, j + dj) : l.index(i, j);
    t[0] = double(g.dx[to]) - g.dx[from];
    t[1] = double(g.height[to]) - g.height[from];
    t[2] = double(g.dz[to]) - g.dz[from];
    return minus || plus;
  };
  double a[3], b[3];
  if (!tangent(1, 0, a) || !tangent(0, 1, b)) {
    return 1.0;
  }
  const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (la == 0 || lb == 0) {
    return 1.0;
  }
  return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (la * lb);
}

double angle(const GridBuffers<float>& r, const GridBuffers<float>& g, std::size_t k) {
  const double cx = double(r.ny[k]) * g.nz[k] - double(r.nz[k]) * g.ny[k];
  const double cy = double(r.nz[k]) * g.nx[k] - double(r.nx[k]) * g.nz[k];
  const double cz = double(r.nx[k]) * g.ny[k] - double(r.ny[k]) * g.nx[k];
  const double dot =
      double(r.nx[k]) * g.nx[k] + double(r.ny[k]) * g.ny[k] + double(r.nz[k]) * g.nz[k];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot);
}

// Each GL stage against the CPU stage on the GL's own inputs (gpu::staged_reference).
void check_stages(const GlTerrainRun& run, bool gl_exact, const std::string& what) {
  const FramePlan& plan = run.plan;
  const GridBuffers<float>& gl = run.gl;
  const GridBuffers<float> staged = gpu::staged_reference(plan, run.cpu, gl);
  // Stage 3 in double on the same inputs: how far the float reference is from the function.
  const GridLayout& l = plan.layout;
  AlignedVector<double> dx(l.size()), dz(l.size()), nu(l.size()), exact(l.size());
  for (std::size_t k = 0; k < l.size(); ++k) {
    dx[k] = gl.dx[k];
    dz[k] = gl.dz[k];
    nu[k] = gl.nu[k];
  }
  FbmParams<double> fbm = make_fbm_params<double>(plan.terrain);
  const IndexRange all{0, l.size()};
  choose_coordinate_forms(plan.terrain, octave_reach<double>(all, dx, dz, nu, gl.valid), fbm);
  evaluate_fbm<double>(fbm, *plan.terrain.lattice, all, dx, dz, nu, gl.valid, exact);

  const double c1 = plan.lod.c1;
  const bool warp = plan.terrain.warp.enabled;
  // On a planet stage 2's footprint takes two square roots, two divisions and two atan2_det
  // (a division each) before its product (core/planet_domain.cc): 16 units where the 4 of
  // the plane's one division stand. The bend on the same inputs: a square root and a
  // division (sinc) before its products: 8 units of the bent position's size. The normals'
  // rotation adds a few roundings of a unit vector: 8 units of angle.
  // On a GL whose double operations are no better than GLSL promises (tests/gl/gl_arithmetic.h;
  // the stages form each division and square root in double and round it to float): each
  // square root 4.5 + 0.5 + 0.5 (the CPU's) units, each division 2.5 + 0.5 + 0.5, each
  // atan2_det 7 ulp of the angle and 2.5 (t + |u|) <= 2.5 (1.27 + 1) units of it more
  // (tests/gl/gl_glsl_functions_test.cc), about 13: passed on with a gain of 1, a first-order
  // count (not a derivation with the condition numbers: at grazing rays dc + sqrt(disc) may
  // amplify more), 2 * 5.5 + 2 * 3.5 + 2 * 13 + the products' 2: 46 units on a planet
  // (measured on an NVIDIA H100 with its built-in float division: 26); the plane's one
  // division 3.5 and its product: 4.5.
  const bool planet = !gl.bent_x.empty();
  const double domain_units = planet ? (gl_exact ? 16 : 46) : (gl_exact ? 4 : 4.5);
  // Stage 3's sketch (height_sketch.h) divides each B-spline weight by 6: on such a GL the
  // weights lie within 3 + 0.5 units of the CPU's, which moves the sketch's weighted sum of
  // 16 texels (weights >= 0, summing to 1) by 2 * 3.5 units of the largest texel H; both sides'
  // float sums (8 roundings of half a unit each, first order) add 2 * 4 units; the height's
  // last addition an ulp. Without a sketch, or where the GL divides as the CPU: exact.
  double sketch_units_of = 0;
  if (plan.terrain.sketch != nullptr && !gl_exact) {
    for (const float texel : plan.terrain.sketch->heights) {
      sketch_units_of = std::max(sketch_units_of, std::abs(double(texel)));
    }
  }
  const double sketch_bound = 15.01 * kUnit * sketch_units_of;
  std::size_t vertices = 0, mismatched = 0;
  double gl_max = 0, gl_sq = 0, float_max = 0, float_sq = 0;
  for (int j = 0; j < l.height; ++j) {
    for (int i = 0; i < l.width; ++i) {
      const std::size_t k = l.index(i, j);
      if (!staged.valid[k] || !gl.valid[k]) {
        mismatched += staged.valid[k] != gl.valid[k];
        continue;
      }
      ++vertices;
      INFO(what << ": vertex (" << i << ", " << j << ")");
      // Stage 2: the footprint's one division (2.5 ULP) and its product: 4 units.
      const double d = std::hypot(double(staged.dx[k]), double(staged.dz[k]));
      CHECK(std::abs(double(gl.dx[k]) - staged.dx[k]) <= domain_units * kUnit * d);
      CHECK(std::abs(double(gl.dz[k]) - staged.dz[k]) <= domain_units * kUnit * d);
      if (planet) {
        const double bx = staged.bent_x[k], by = staged.bent_y[k], bz = staged.bent_z[k];
        const double size = std::sqrt(bx * bx + by * by + bz * bz);
        CHECK(std::abs(double(gl.bent_x[k]) - bx) <= 8 * kUnit * size);
        CHECK(std::abs(double(gl.bent_y[k]) - by) <= 8 * kUnit * size);
        CHECK(std::abs(double(gl.bent_z[k]) - bz) <= 8 * kUnit * size);
        CHECK(std::abs(double(gl.bent_drop[k]) - staged.bent_drop[k]) <= 8 * kUnit * size);
      }
      // sigma: two footprints 4 units each, at most 3 max(|d|, sigma) away, and the square
      // root (GLSL: inherited from 1 / inversesqrt) and its squares: 32 units of that.
      const double m = std::max(d, double(staged.sigma[k]));
      CHECK(std::abs(double(gl.sigma[k]) - staged.sigma[k]) <= 32 * kUnit * m);
      // nu = c0 - c1 log2(sigma^2): the relative error of sigma^2 through the log, plus the
      // log's own division and the final roundings.
      if (staged.sigma[k] > 0) {
        const double relative_sq = 2 * 32 * kUnit * m / staged.sigma[k];
        CHECK(std::abs(double(gl.nu[k]) - staged.nu[k]) <=
              c1 * relative_sq / std::log(2.0) + 8 * kUnit * (std::abs(staged.nu[k]) + c1 * 128));
      }
      // Stage 3: + - * and floor only, but for the warp's division and square root.
      const double gl_error = std::abs(double(gl.height[k]) - staged.height[k]);
      if (!warp) {
        CHECK(gl_error <= (sketch_bound > 0 ? sketch_bound + float_ulp(staged.height[k]) : 0.0));
      }
      gl_max = std::max(gl_max, gl_error);
      gl_sq += gl_error * gl_error;
      const double float_error = std::abs(double(staged.height[k]) - exact[k]);
      float_max = std::max(float_max, float_error);
      float_sq += float_error * float_error;
      // Stage 4: the divisions and square roots of the normal, through the condition number
      // 1 / sin(angle between the tangents).
      const double bound = 32 * kUnit / tangent_sine(gl, i, j) + (planet ? 8 * kUnit : 0.0);
      CHECK(angle(staged, gl, k) <= bound);
      const double slope = staged.slope[k];
      CHECK(std::abs(double(gl.slope[k]) - slope) <= bound * (1 + slope) * (1 + slope));
      CHECK(gl.water_depth[k] == staged.water_depth[k]);  // one subtraction of equal inputs
    }
  }
  INFO(what << ": stage 3 GL - CPU max " << gl_max << ", rms "
            << std::sqrt(gl_sq / double(vertices)) << "; CPU float - double max " << float_max
            << ", rms " << std::sqrt(float_sq / double(vertices)));
  // With the warp, no closer to the float reference than the float reference is to the
  // function it rounds (docs/gl-backend.md).
  CHECK(gl_max <= float_max);
  CHECK(gl_sq <= float_sq);
  // A footprint's validity flips only within 4 units of the farthest distance.
  CHECK(double(mismatched) <= 1e-3 * double(vertices));
}

}  // namespace

bool gl_is_exact() {
  const GlArithmetic& a = gl_arithmetic();
  return a.exact() && a.basic_as_cpu && a.precise_unfused;
}

GlTerrainRun run_cpu_and_gl(const std::string& preset, std::vector<std::string> overrides,
                            int width, int height) {
  gl_context();  // opened here when this test runs alone
  overrides.push_back("grid.width=" + std::to_string(width));
  overrides.push_back("grid.height=" + std::to_string(height));
  const Scene scene = resolve_scene(preset, overrides);
  // Stage 3's grid: terrain.basis's composed images, or the noise lattice.
  std::optional<NoiseLattice> basis = load_basis_grid(scene);
  auto lattice = std::make_unique<NoiseLattice>(
      basis ? std::move(*basis)
            : make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size));
  std::optional<HeightSketch> loaded = load_height_sketch(scene);
  auto sketch = loaded ? std::make_unique<HeightSketch>(std::move(*loaded)) : nullptr;
  const FramePlan plan = make_frame_plan(scene, *lattice, sketch.get());
  GlTerrainRun run{std::move(lattice),
                   std::move(sketch),
                   plan,
                   GridBuffers<float>(plan.layout),
                   GridBuffers<float>(plan.layout),
                   {},
                   {},
                   {}};
  run_terrain_stages(plan, run.cpu);
  run.cpu_fbm = make_fbm_params<float>(plan.terrain);
  choose_coordinate_forms(plan.terrain,
                          octave_reach<float>(IndexRange{0, plan.layout.size()}, run.cpu.dx,
                                              run.cpu.dz, run.cpu.nu, run.cpu.valid),
                          run.cpu_fbm);
  gpu::GlTerrain terrain(plan.layout, *run.lattice, run.sketch.get());
  terrain.run(make_terrain_params<float>(plan));
  terrain.read_all(run.gl);
  run.gl_fbm = terrain.fbm_params();
  run.differences = gpu::terrain_differences(run.cpu, run.gl);
  return run;
}

void check_gl_terrain(const GlTerrainRun& run, bool exact, const std::string& what) {
  const gpu::TerrainDifferences& d = run.differences;
  const double a = run.plan.terrain.amplitude;
  INFO(what << ": " << d.vertices << " vertices, " << d.identical << " bit-identical, "
            << d.valid_mismatches << " valid differences; end to end: nu " << d.nu_max_abs
            << ", height max " << d.height_max_abs / a << " A, rms " << d.height_rms_abs / a
            << " A, normal " << d.normal_max_angle << " rad, bent " << d.bent_max_rel);
  REQUIRE(d.vertices > 0);
  CHECK(d.default_mismatches == 0);
  for (int n = 0; n < run.cpu_fbm.count; ++n) {
    INFO("octave " << n);
    CHECK(run.gl_fbm.exact_coordinates[n] == run.cpu_fbm.exact_coordinates[n]);
  }
  if (exact) {
    CHECK(d.valid_mismatches == 0);
    CHECK(d.identical == d.vertices);
  }
  check_stages(run, exact, what);
}

}  // namespace relief::test
