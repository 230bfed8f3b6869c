// terrain.heightfield (pipeline/heightfield_files.h, core/height_sketch.h): every format gives
// the same world heights, hostile files are refused naming the field, the frame's heights are the
// field's B-spline (plus the fractal only when asked), and the regional bound stays tight on a
// large field.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_sketch.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "image/png_encoder.h"
#include "pipeline/heightfield_files.h"
#include "pipeline/scene_resources.h"
#include "tests/support/bspline_oracle.h"
#include "tests/support/cli_support.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::concat;
using test::require_refused;
using test::run;

HeightFieldSettings settings_for(const std::string& file, double lo = -200.0, double hi = 800.0) {
  HeightFieldSettings s;
  s.image = file;
  s.extent = {-1000.0, -1000.0, 1000.0, 1000.0};
  s.height = {lo, hi};
  return s;
}

// A 5 x 3 field whose every level differs, top row first.
constexpr int kW = 5, kH = 3;
std::uint16_t level_at(int i, int j) {
  return static_cast<std::uint16_t>(1000 * i + 7000 * j + 13);
}

TEST_CASE("heightfieldFilesOfEveryFormatGiveTheSameWorldHeights", "[heightfield]") {
  test::TempDir dir("heightfield-formats");
  std::vector<std::uint16_t> levels;
  std::vector<float> unit;
  for (int j = 0; j < kH; ++j) {
    for (int i = 0; i < kW; ++i) {
      levels.push_back(level_at(i, j));
      unit.push_back(float(level_at(i, j)) / 65535.0f);
    }
  }
  const std::vector<unsigned char> png = encode_png_grey16(kW, kH, levels);
  const std::string png_file =
      test::write_file(dir.path() / "f.png", std::string(png.begin(), png.end()));
  const std::string raw_file = test::write_file(dir.path() / "f.R16", test::raw16_bytes(levels));
  const std::string pfm_file =
      test::write_file(dir.path() / "f.pfm", test::pfm_bytes(kW, kH, unit));
  const std::string big_endian =
      test::write_file(dir.path() / "big.pfm", test::pfm_bytes(kW, kH, unit, false));
  HeightFieldSettings raw = settings_for(raw_file);
  raw.raw_width = kW;
  for (const HeightFieldSettings& s : {settings_for(png_file), raw}) {
    INFO(s.image);
    const HeightSketch field = load_height_field(s);
    REQUIRE(field.width == kW);
    REQUIRE(field.height == kH);
    for (int j = 0; j < kH; ++j) {
      for (int i = 0; i < kW; ++i) {
        // Row 0 is the file's first (top) row, at z0.
        CHECK(field.heights[std::size_t(j * kW + i)] ==
              float(-200.0 + 1000.0 * (double(level_at(i, j)) / 65535.0)));
      }
    }
    CHECK(field.min_height == field.heights.front());
    CHECK(field.max_height == field.heights[kW * kH - 1]);
  }
  for (const std::string& file : {pfm_file, big_endian}) {
    INFO(file);
    const HeightSketch field = load_height_field(settings_for(file));
    REQUIRE(field.width == kW);
    for (int j = 0; j < kH; ++j) {
      for (int i = 0; i < kW; ++i) {
        const float v = unit[std::size_t(j * kW + i)];
        CHECK(field.heights[std::size_t(j * kW + i)] == float(-200.0 + 1000.0 * double(v)));
      }
    }
  }
  // [0, 1] keeps a float file's values as world heights.
  const HeightSketch kept = load_height_field(settings_for(pfm_file, 0.0, 1.0));
  CHECK(kept.heights[7] == unit[7]);
}

// The test's own B-spline (core/height_sketch.h's definition: uniform cubic B-spline of the
// samples, centres at x0 + (i + 1/2) cell, taps clamped to the edge), in double, on level `l`
// of the field (its texel i on level 0's texel 2^l i, so its coordinate is level 0's / 2^l).
double bspline_oracle(const HeightSketch& f, const HeightFieldSettings& s, double x, double z,
                      int l = 0) {
  const double scale = std::ldexp(1.0, -l);
  const double sx = ((x - s.extent[0]) * f.width / (s.extent[2] - s.extent[0]) - 0.5) * scale;
  const double sz = ((z - s.extent[1]) * f.height / (s.extent[3] - s.extent[1]) - 0.5) * scale;
  const int w = l == 0 ? f.width : f.level_width[std::size_t(l)];
  const int h = l == 0 ? f.height : f.level_height[std::size_t(l)];
  const float* samples = f.heights.data() + (l == 0 ? 0 : f.level_offset[std::size_t(l)]);
  return test::bspline_at(samples, w, h, sx, sz);
}

// Without the fractal, the level a vertex reads: stage 2's count nu as levels - nu (the field's
// LOD rule, core/frame_plan.h), and the blend of its two levels.
double field_oracle(const HeightSketch& f, const HeightFieldSettings& s, double x, double z,
                    double nu) {
  const int levels = f.levels();
  const double lambda = std::clamp(levels - nu, 0.0, double(levels - 1));
  const int a = int(std::floor(lambda)), b = std::min(a + 1, levels - 1);
  const double fine = bspline_oracle(f, s, x, z, a), coarse = bspline_oracle(f, s, x, z, b);
  return fine + (lambda - a) * (coarse - fine);
}

TEST_CASE("heightfieldFrameHeightsAreTheFieldAloneUnlessTheFractalIsAsked", "[heightfield]") {
  test::TempDir dir("heightfield-frame");
  const std::vector<float> values = test::random_unit_samples(33 * 17, 41);
  const std::string file = test::write_file(dir.path() / "f.pfm", test::pfm_bytes(33, 17, values));
  const std::vector<std::string> view = {
      "camera.position=[100,2500,300]",
      "camera.pitch_deg=-60",
      "grid.width=96",
      "grid.height=96",
      "terrain.base_height=40",
      concat({"terrain.heightfield={\"file\":\"", file,
              "\",\"extent\":[-900,-600,900,600],\"height\":[-500,1500]}"})};
  // The field alone (its samples, then its levels of detail), then with the fractal.
  for (const int mode : {0, 1, 2}) {
    const bool fractal = mode == 2, lod = mode == 1;
    std::vector<std::string> sets = view;
    sets.push_back(fractal ? "terrain.heightfield.fractal=true" : "terrain.water_level=null");
    sets.push_back(lod ? "terrain.heightfield.level_of_detail=true"
                       : "terrain.heightfield.level_of_detail=false");
    const Scene scene = resolve_scene("alpine", sets);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const std::optional<HeightSketch> field = load_height_sketch(scene);
    REQUIRE(field);
    const FramePlan plan = make_frame_plan(scene, lattice, &*field);
    CHECK(plan.terrain.octaves.count ==
          (fractal ? scene.terrain.last_octave - scene.terrain.first_octave + 1 : 0));
    GridBuffers<double> grid(plan.layout);
    run_terrain_stages(plan, grid);
    GridBuffers<double> again = grid;  // stage 3 run once more, for its work counter
    const FbmWork work =
        evaluate_fbm_rows<double>(make_terrain_params<double>(plan).fbm, lattice,
                                  RowRange{0, plan.layout.height}, again, again.valid);
    CHECK((work.octaves == 0) == !fractal);  // the skip: no octave summed without the fractal
    const Vec3d& c = scene.camera.position;
    std::size_t checked = 0, coarser = 0;  // vertices reading a level above 0
    double worst = 0;
    for (std::size_t k = 0; k < plan.layout.size(); ++k) {
      if (!grid.valid[k]) {
        continue;
      }
      const double x = grid.dx[k] + c[0], z = grid.dz[k] + c[2];
      double expected =
          40.0 + (fractal ? bspline_oracle(*field, *scene.terrain.heightfield, x, z)
                          : field_oracle(*field, *scene.terrain.heightfield, x, z, grid.nu[k]));
      coarser += field->levels() > 1 && grid.nu[k] < field->levels();
      if (fractal) {
        expected +=
            fbm_height<double>(plan.terrain, grid.dx[k], grid.dz[k], grid.nu[k]) - (40.0 - c[1]);
      }
      worst = std::max(worst, std::abs(grid.height[k] + c[1] - expected));
      ++checked;
    }
    INFO("mode " << mode << ", worst " << worst);
    CHECK(checked > 5000);
    // Without the fractal the far vertices read coarser levels (the levels exist only then).
    // Levels of detail only where asked (33 x 17, 17 x 9, 9 x 5, 5 x 3, 3 x 2, 2 x 2), and then
    // the far vertices read coarser levels.
    CHECK(field->levels() == (lod ? 6 : 1));
    CHECK((coarser > checked / 10) == lod);
    // Double stages against the double oracle: the camera-relative texel coordinate's rounding
    // moves a sample by under 1e-9 texels, a height by under 1e-6 units at these slopes.
    CHECK(worst < 1e-6);
  }
}

TEST_CASE("heightfieldRegionalBoundStaysTightOnALargeField", "[heightfield]") {
  constexpr int kBigW = 400, kBigH = 300;
  std::vector<std::uint16_t> grey(std::size_t(kBigW) * kBigH);
  test::TestRandom rng(5);
  for (int j = 0; j < kBigH; ++j) {
    for (int i = 0; i < kBigW; ++i) {  // a ramp with noise: regions differ
      grey[std::size_t(j * kBigW + i)] =
          static_cast<std::uint16_t>(std::min(65535.0, 80.0 * (i + j) + rng.uniform(0, 9000)));
    }
  }
  HeightFieldSettings s = settings_for("test", 0.0, 1000.0);
  s.extent = {0.0, 0.0, 4000.0, 3000.0};  // 10 units a texel
  // Without levels of detail (a sketch, or a field with the fractal), then with them.
  for (const bool levels_of_detail : {false, true}) {
    const HeightSketch field = make_height_sketch(s, kBigW, kBigH, grey, 65535, levels_of_detail);
    REQUIRE_FALSE(field.blocks.empty());
    CHECK(field.blocks.back().width == 1);
    CHECK(field.blocks.back().height == 1);
    CHECK(field.levels() == (levels_of_detail ? 10 : 1));          // 400 x 300 down to 2 x 2
    const SketchPlan plan = make_sketch_plan(s, field, 0.0, 0.0);  // camera at the corner
    const SketchParams<double> p = make_sketch_params<double>(plan, &field);
    for (const double side : {100.0, 900.0, 1500.0, 2500.0}) {  // 100 to 62500 texels
      for (const double x0 : {0.0, 700.0, 1400.0}) {
        const double z0 = x0 * 0.4;
        const SketchRange r = sketch_range(plan, field, x0, x0 + side, z0, z0 + side);
        // The bound holds every value the interpolation takes there, at every level ...
        double lo = 1e300, hi = -1e300;
        for (int a = 0; a <= 40; ++a) {
          for (int b = 0; b <= 40; ++b) {
            const double x = x0 + side * a / 40.0, z = z0 + side * b / 40.0;
            for (int l = 0; l < field.levels(); ++l) {
              const double v =
                  sample_field_level<double>(p, field.heights, l, p.offset_x + x * p.inv_cell_x,
                                             p.offset_z + z * p.inv_cell_z);
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
          }
        }
        INFO("levels " << field.levels() << ", side " << side << " at " << x0 << ": [" << r.lo
                       << ", " << r.hi << "] holds [" << lo << ", " << hi << "]");
        CHECK(r.lo <= lo);
        CHECK(r.hi >= hi);
        if (!levels_of_detail) {
          // ... and is not the field's global one: within one block of 4 texels' ramp of the
          // region's own extremes (80 levels a texel, 8 texels of slack, 1000 / 65535 units a
          // level). With levels the coarsest ones' few texels average the whole field: a
          // region's bound then reaches toward the field's mean, as a vertex far enough away
          // reads it.
          const double slack = 8 * 80 * 1000.0 / 65535.0 + 1e-3;
          CHECK(r.hi <= hi + slack + 9000 * 1000.0 / 65535.0);
          CHECK(r.lo >= lo - slack - 9000 * 1000.0 / 65535.0);
        }
      }
    }
  }
}

TEST_CASE("generatedMapsRenderAsHeightfieldsAndTheSimdFrameMatchesTheReference", "[heightfield]") {
  test::TempDir dir("heightfield-generated");
  for (const std::string method : {"diamond-square", "square-square", "triangle-edge", "perlin"}) {
    const std::string map = (dir.path() / (method + ".r16")).string();
    REQUIRE(run({"generate", method, "--size", "65", "--seed", "3", "-o", map}).code == 0);
    const std::string scene = test::write_file(
        dir.path() / "scene.json",
        concat({R"({"grid": {"width": 64, "height": 64}, "viewport": {"width": 80, "height": 64},
                   "camera": {"position": [0, 1800, 2500], "yaw_deg": 0, "pitch_deg": -30},
                   "terrain": {"water_level": 200, "heightfield": {"file": ")",
                map, R"(", "extent": [-3000, -3000, 3000, 3000], "height": [0, 1200]}}})"}));
    const std::string simd = (dir.path() / "simd.png").string();
    const std::string scalar = (dir.path() / "scalar.png").string();
    INFO(method);
    REQUIRE(run({"render", scene, "-o", simd}).code == 0);
    REQUIRE(run({"render", scene, "--backend", "reference", "-o", scalar}).code == 0);
    CHECK(test::read_bytes(simd) == test::read_bytes(scalar));
  }
}

}  // namespace
}  // namespace relief
