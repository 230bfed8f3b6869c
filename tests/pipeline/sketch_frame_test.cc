// §3's low-frequency base in whole frames: heights that follow the sketch at low frequency with
// the fractal's detail unchanged, the projector's regional bounds, and float accuracy far from
// the origin (core/height_sketch.h, docs/terrain-spec.md section 11).
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/height_bound_pyramid.h"
#include "core/height_sketch.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "eval/height_error.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// The island from straight above, its grid over the whole sketch.
Scene island_from_above(std::vector<std::string> more = {}) {
  std::vector<std::string> sets = {"camera.position=[0,26000,0]",
                                   "camera.pitch_deg=-89",
                                   "camera.yaw_deg=0",
                                   "grid.width=192",
                                   "grid.height=192",
                                   "camera.far=80000"};
  sets.insert(sets.end(), more.begin(), more.end());
  return resolve_scene("island", sets);
}

struct Heights {
  std::vector<double> x, z, height;  // world coordinates of the valid vertices
};

Heights world_heights(const Scene& scene) {
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const std::optional<HeightSketch> sketch = load_height_sketch(scene);
  const FramePlan plan = make_frame_plan(scene, lattice, sketch ? &*sketch : nullptr);
  GridBuffers<float> grid(plan.layout);
  run_terrain_stages(plan, grid);
  Heights out;
  const Vec3d& c = scene.camera.position;
  std::size_t outside = 0;  // heights outside the slab, which must hold every one
  for (std::size_t k = 0; k < plan.layout.size(); ++k) {
    if (grid.valid[k]) {
      const double h = grid.height[k] + c[1];
      outside += h < plan.bounds.world_min || h > plan.bounds.world_max;
      out.x.push_back(grid.dx[k] + c[0]);
      out.z.push_back(grid.dz[k] + c[2]);
      out.height.push_back(h);
    }
  }
  CHECK(outside == 0);
  return out;
}

// Low-pass: the mean height of the vertices in each cell of a kCells x kCells partition of
// [-14000, 14000]^2 (1750 units: the fractal's octave 0 spans 1200).
constexpr int kCells = 16;
int cell_of(double x, double z) {
  const int i = std::clamp(int(std::floor((x + 14000.0) / 1750.0)), 0, kCells - 1);
  const int j = std::clamp(int(std::floor((z + 14000.0) / 1750.0)), 0, kCells - 1);
  return j * kCells + i;
}

std::vector<double> cell_means(const Heights& h, const std::vector<double>& values) {
  std::vector<double> sum(kCells * kCells, 0.0), count(kCells * kCells, 0.0);
  for (std::size_t k = 0; k < values.size(); ++k) {
    sum[cell_of(h.x[k], h.z[k])] += values[k];
    count[cell_of(h.x[k], h.z[k])] += 1;
  }
  for (std::size_t c = 0; c < sum.size(); ++c) {
    sum[c] = count[c] > 0 ? sum[c] / count[c] : std::nan("");
  }
  return sum;
}

// High-pass: each value less its cell's mean.
double high_pass_rms(const Heights& h, const std::vector<double>& values) {
  const std::vector<double> mean = cell_means(h, values);
  double sq = 0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double r = values[k] - mean[cell_of(h.x[k], h.z[k])];
    sq += r * r;
  }
  return std::sqrt(sq / double(values.size()));
}

TEST_CASE("renderedHeightsFollowTheSketchAndKeepTheFractalsDetail", "[sketch]") {
  const Scene scene = island_from_above();
  const Heights with = world_heights(scene);
  const Heights without = world_heights(island_from_above({"terrain.sketch=null"}));
  REQUIRE(with.height.size() > 20000);
  // The sketch itself at the same points, in double.
  const std::optional<HeightSketch> sketch = load_height_sketch(scene);
  const SketchPlan plan = make_sketch_plan(*scene.terrain.sketch, *sketch, 0.0, 0.0);
  const SketchParams<double> p = make_sketch_params<double>(plan, &*sketch);
  std::vector<double> sketched;
  for (std::size_t k = 0; k < with.x.size(); ++k) {
    sketched.push_back(sample_sketch<double>(p, sketch->heights,
                                             p.offset_x + with.x[k] * p.inv_cell_x,
                                             p.offset_z + with.z[k] * p.inv_cell_z));
  }
  const std::vector<double> a = cell_means(with, with.height), b = cell_means(with, sketched);
  double ma = 0, mb = 0, n = 0;
  for (std::size_t c = 0; c < a.size(); ++c) {
    if (!std::isnan(a[c])) {
      ma += a[c], mb += b[c], n += 1;
    }
  }
  ma /= n, mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t c = 0; c < a.size(); ++c) {
    if (!std::isnan(a[c])) {
      sab += (a[c] - ma) * (b[c] - mb), saa += (a[c] - ma) * (a[c] - ma);
      sbb += (b[c] - mb) * (b[c] - mb);
    }
  }
  const double correlation = sab / std::sqrt(saa * sbb);
  // The detail on top: the heights less the sketch, high-passed, against the fractal alone.
  std::vector<double> detail;
  for (std::size_t k = 0; k < with.height.size(); ++k) {
    detail.push_back(with.height[k] - sketched[k]);
  }
  const double rms_with = high_pass_rms(with, detail);
  const double rms_without = high_pass_rms(without, without.height);
  INFO("cells " << n << ", low-pass correlation " << correlation
                << ", high-pass rms of the detail on top " << rms_with << ", of the fractal alone "
                << rms_without);
  CHECK(n >= 200);
  CHECK(correlation > 0.95);
  CHECK(std::abs(rms_with / rms_without - 1.0) < 0.10);
}

TEST_CASE("regionalHeightBoundsHoldTheSketchedHeightsOfTheirRegions", "[sketch]") {
  // The projector's per-region bound (core/height_bound_pyramid.h) with the sketch: every
  // vertex of the island seen from above lies within the bound of any box that holds it.
  const Scene scene = island_from_above();
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const std::optional<HeightSketch> sketch = load_height_sketch(scene);
  const FramePlan plan = make_frame_plan(scene, lattice, &*sketch);
  GridBuffers<float> grid(plan.layout);
  run_terrain_stages(plan, grid);
  const LatticeRangePyramid pyramid = make_lattice_range_pyramid(lattice);
  const RegionalHeightBound regional(plan.terrain, pyramid);
  const ValueRange global = regional.global();
  test::TestRandom rng(41);
  const auto corner = [](test::TestRandom& r) { return r.uniform(-16000.0, 16000.0); };
  const auto size = [](test::TestRandom& r) { return r.uniform(10.0, 6000.0); };
  std::size_t checked = 0, outside = 0;
  double narrowest = 1e300;
  for (int box = 0; box < 200; ++box) {
    const double x0 = corner(rng), z0 = corner(rng), x1 = x0 + size(rng), z1 = z0 + size(rng);
    const ValueRange bound = regional.bound(x0, x1, z0, z1);
    CHECK(bound.lo >= global.lo);
    CHECK(bound.hi <= global.hi);
    narrowest = std::min(narrowest, bound.hi - bound.lo);
    for (std::size_t k = 0; k < plan.layout.size(); ++k) {
      if (grid.valid[k] && grid.dx[k] >= x0 && grid.dx[k] <= x1 && grid.dz[k] >= z0 &&
          grid.dz[k] <= z1) {
        ++checked;
        outside += grid.height[k] < bound.lo || grid.height[k] > bound.hi;
      }
    }
  }
  INFO(checked << " vertices in boxes; narrowest bound " << narrowest << ", global "
               << global.hi - global.lo);
  CHECK(checked > 10000);
  CHECK(outside == 0);
  CHECK(narrowest < 0.8 * (global.hi - global.lo));  // regional, not the global slab
}

TEST_CASE("sketchFloatErrorFarFromTheOriginIsNoWorseThanWithout", "[sketch]") {
  // The island and its camera a million units out: float heights against double at the same
  // domain points (eval/height_error.h), with and without the sketch, and at the origin.
  const std::vector<std::string> far = {"camera.position=[1004000,1400,1014500]",
                                        "terrain.sketch.extent=[986000,986000,1014000,1014000]",
                                        "grid.width=128", "grid.height=128"};
  const auto error = [](const Scene& scene) {
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const std::optional<HeightSketch> sketch = load_height_sketch(scene);
    return vertex_height_error(scene, lattice, Backend::kReference, sketch ? &*sketch : nullptr);
  };
  std::vector<std::string> without = far;
  without.push_back("terrain.sketch=null");
  const VertexHeightError e_far = error(resolve_scene("island", far));
  const VertexHeightError e_plain = error(resolve_scene("island", without));
  const VertexHeightError e_origin =
      error(resolve_scene("island", {"grid.width=128", "grid.height=128"}));
  INFO("max |float - double|: far " << e_far.max << ", far without sketch " << e_plain.max
                                    << ", at the origin " << e_origin.max << "; rms " << e_far.rms
                                    << ", " << e_plain.rms << ", " << e_origin.rms);
  REQUIRE(e_far.vertices > 1000);
  CHECK(e_far.max <= 1.5 * e_plain.max + 1e-3);
  CHECK(e_far.max <= 1.5 * e_origin.max + 1e-3);
  CHECK(e_far.rms <= 1.5 * e_origin.rms + 1e-4);
}

}  // namespace
}  // namespace relief

namespace relief {
namespace {

// The memory estimate checked before a render counts the sketch: its file, 16-bit texels and
// float heights (pipeline/job_memory.h).
TEST_CASE("theRenderMemoryEstimateCountsTheSketch", "[sketch]") {
  const auto sketch_part = [](const Scene& scene) -> std::uintmax_t {
    for (const auto& [name, bytes] : estimate_render_memory(scene, Backend::kSimd, {}).parts) {
      if (name == "height sketch") {
        return bytes;
      }
    }
    return 0;
  };
  const Scene island = resolve_scene("island", {});
  const std::optional<HeightSketch> sketch = load_height_sketch(island);
  REQUIRE(sketch);
  const std::uintmax_t texels = std::uintmax_t(sketch->width) * std::uintmax_t(sketch->height);
  CHECK(sketch_part(island) >= texels * (sizeof(std::uint16_t) + sizeof(float)));
  CHECK(sketch_part(resolve_scene("default", {})) == 0);
}

}  // namespace
}  // namespace relief
