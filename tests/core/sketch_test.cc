// §3's low-frequency base (core/height_sketch.h): the scene field's strict checks, the B-spline's
// properties, the region bound, and the simd kernel against the scalar one on every target.
// Whole frames: tests/pipeline/sketch_frame_test.cc.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <stb_image_write.h>
#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/height_bound_pyramid.h"
#include "core/height_sketch.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "eval/height_error.h"
#include "pipeline/scene_resources.h"
#include "simd/sketch.h"
#include "tests/support/cli_support.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::concat;
using test::require_refused;
using test::run;

// A width x height grey PNG (8 bits, `channels` equal channels) written to `path`.
std::string write_png(const std::filesystem::path& path, int width, int height, int channels,
                      const std::vector<unsigned char>& grey) {
  std::vector<unsigned char> pixels;
  for (const unsigned char g : grey) {
    pixels.insert(pixels.end(), std::size_t(channels), g);
  }
  REQUIRE(stbi_write_png(path.string().c_str(), width, height, channels, pixels.data(),
                         width * channels) != 0);
  return path.string();
}

SketchSettings settings_of(double lo, double hi) {
  SketchSettings s;
  s.image = "test";
  s.extent = {-100.0, -50.0, 100.0, 50.0};
  s.height = {lo, hi};
  return s;
}

HeightSketch sketch_of(int width, int height, const std::vector<std::uint16_t>& grey) {
  return make_height_sketch(settings_of(-200.0, 800.0), width, height, grey, 65535);
}

std::vector<std::uint16_t> random_grey(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint16_t> grey(static_cast<std::size_t>(count));
  for (std::uint16_t& g : grey) {
    g = static_cast<std::uint16_t>(rng() & 0xffff);
  }
  return grey;
}

TEST_CASE("sketchFieldsAreCheckedAndBadSketchesAreRefusedNamingTheField", "[sketch]") {
  test::TempDir dir("sketch");
  const std::filesystem::path out = dir.path() / "out.png";
  const auto refused = [&](const std::vector<std::string>& sets, const std::string& message) {
    INFO(message);
    require_refused(test::render_preset("island", sets, out), message, out);
  };
  refused({"terrain.sketch.extent=[0,0,0,10]"}, "terrain.sketch.extent = [0,0,0,10] is empty");
  refused({"terrain.sketch.extent=[0,0,10,-5]"}, "terrain.sketch.extent");
  refused({"terrain.sketch.extent=[0,0,2e12,10]"}, "terrain.sketch.extent[2] = 2e+12 is out");
  refused({"terrain.sketch.extent=[0,0,10]"}, "terrain.sketch.extent = [0,0,10] must be an array");
  refused({"terrain.sketch.height=[5,5]"}, "terrain.sketch.height = [5,5] is empty");
  refused({"terrain.sketch.height=[0,1e8]"}, "terrain.sketch.height[1]");
  refused({"terrain.sketch.scale=2"}, "unknown key 'terrain.sketch.scale'");
  refused({"terrain.sketch=3"}, "terrain.sketch");
  refused({"terrain.sketch.image=\"builtin:nowhere\""}, "names no built-in sketch");
  refused({concat({"terrain.sketch.image=\"", (dir.path() / "missing.png").string(), "\""})},
          "terrain.sketch.image");
  refused({concat({"terrain.sketch.image=\"", dir.path().string(), "\""})}, "terrain.sketch.image");
  // A new sketch must name its image (the default scene has none).
  require_refused(
      run({"render", "--set", "terrain.sketch={\"extent\":[0,0,1,1]}", "-o", out.string()}),
      "terrain.sketch must be null or an object with at least an \"image\"", out);
  // Files: colour, depth and size are read from the header.
  const std::vector<unsigned char> grey(16, 128);
  const std::string rgb = write_png(dir.path() / "rgb.png", 4, 4, 3, grey);
  const std::string rgba = write_png(dir.path() / "rgba.png", 4, 4, 4, grey);
  const std::string one = write_png(dir.path() / "one.png", 1, 1, 1, {7});
  refused({concat({"terrain.sketch.image=\"", rgb, "\""})},
          "has colour type 2 (RGB); allowed: a grey PNG with one channel");
  refused({concat({"terrain.sketch.image=\"", rgba, "\""})}, "has colour type 6 (RGBA)");
  refused({concat({"terrain.sketch.image=\"", one, "\""})},
          "is 1x1 texels; allowed 2 to 4096 on each side");
  std::string header("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\x20\0\0\0\0\x10\x10\0\0\0\0\0\0\0\0", 33);
  refused(
      {concat({"terrain.sketch.image=\"", test::write_file(dir.path() / "big.png", header), "\""})},
      "is 8192x16 texels");
  header[24] = 4;  // 4-bit grey
  header[17] = 0, header[18] = 0x10;
  refused({concat({"terrain.sketch.image=\"", test::write_file(dir.path() / "four.png", header),
                   "\""})},
          "has 4 bits per channel; allowed: 8 or 16");
  header[24] = 8;
  refused(
      {concat({"terrain.sketch.image=\"", test::write_file(dir.path() / "cut.png", header), "\""})},
      "could not be decoded");
  // The layer textures' file checks hold for sketches too (png_checks.h): a chunk whose
  // length runs past the file, and image data that inflates past the header's size.
  std::vector<unsigned char> good_bytes =
      test::read_bytes(write_png(dir.path() / "g.png", 4, 4, 1, grey));
  std::vector<unsigned char> long_chunk = good_bytes;
  long_chunk[33] = 0x4e;  // the chunk after IHDR claims 1.3 GB
  refused({concat({"terrain.sketch.image=\"",
                   test::write_file(dir.path() / "long.png",
                                    std::string(long_chunk.begin(), long_chunk.end())),
                   "\""})},
          "could not be decoded");
  const std::vector<unsigned char> wide(64 * 64, 200);
  std::vector<unsigned char> inflating =
      test::read_bytes(write_png(dir.path() / "wide.png", 64, 64, 1, wide));
  inflating[19] = 2, inflating[23] = 2;  // the header now says 2x2 (the CRC is not checked)
  refused({concat({"terrain.sketch.image=\"",
                   test::write_file(dir.path() / "inflating.png",
                                    std::string(inflating.begin(), inflating.end())),
                   "\""})},
          "inflates to more than");
  // A good 8-bit grey file, relative to the scene file, renders; null removes the sketch.
  const std::string good = write_png(dir.path() / "good.png", 4, 4, 1, grey);
  const std::string scene = test::write_file(
      dir.path() / "scene.json",
      R"({"grid": {"width": 64, "height": 64}, "viewport": {"width": 64, "height": 48},
          "terrain": {"sketch": {"image": "good.png", "extent": [-1000, -1000, 1000, 1000]}}})");
  CHECK(run({"render", scene, "-o", out.string()}).code == 0);
  const Scene loaded = resolve_scene(scene, {});
  REQUIRE(loaded.terrain.sketch);
  CHECK(loaded.terrain.sketch->image ==
        std::filesystem::absolute(good).lexically_normal().string());
  CHECK_FALSE(resolve_scene("island", {"terrain.sketch=null"}).terrain.sketch);
}

TEST_CASE("sketchTexelsMapGreyToTheHeightRangeAndTheBuiltinIslandLoads", "[sketch]") {
  const std::vector<std::uint16_t> grey = {0, 65535, 32768, 1};
  const HeightSketch s = make_height_sketch(settings_of(-200, 800), 2, 2, grey, 65535);
  CHECK(s.heights[0] == -200.0f);
  CHECK(s.heights[1] == 800.0f);
  CHECK(s.min_height == -200.0f);
  CHECK(s.max_height == 800.0f);
  const std::optional<HeightSketch> island = load_height_sketch(resolve_scene("island", {}));
  REQUIRE(island);
  CHECK(island->width == 128);
  CHECK(island->height == 128);
  const Scene scene = resolve_scene("island", {});
  CHECK(island->min_height == float(scene.terrain.sketch->height[0]));  // the sea floor is black
  CHECK(island->max_height < float(scene.terrain.sketch->height[1]));   // nothing clipped white
}

template <class Real>
Real sample_at(const HeightSketch& s, Real sx, Real sz) {
  SketchPlan plan;
  plan.enabled = true;
  const SketchParams<Real> p = make_sketch_params<Real>(plan, &s);
  return sample_sketch<Real>(p, s.heights, sx, sz);
}

TEST_CASE("sketchBsplineReproducesRampsNeverOvershootsIsC2AndClampsOutside", "[sketch]") {
  constexpr int kW = 9, kH = 7;
  // A linear ramp in both axes (grey exact): reproduced exactly inside (B-splines reproduce
  // linear functions), so a sloping sketch has a uniform slope, no terraces.
  std::vector<std::uint16_t> ramp;
  for (int j = 0; j < kH; ++j) {
    for (int i = 0; i < kW; ++i) {
      ramp.push_back(static_cast<std::uint16_t>(1000 * i + 3000 * j));
    }
  }
  const HeightSketch r = sketch_of(kW, kH, ramp);
  const auto ramp_at = [](double sx, double sz) {
    return -200.0 + 1000.0 * (1000.0 * sx + 3000.0 * sz) / 65535.0;
  };
  for (double sx = 1.0; sx <= kW - 2; sx += 0.37) {
    for (double sz = 1.0; sz <= kH - 2; sz += 0.29) {
      CHECK(std::abs(sample_at<double>(r, sx, sz) - ramp_at(sx, sz)) < 1e-4);  // float texels
      CHECK(std::abs(sample_at<float>(r, float(sx), float(sz)) - ramp_at(sx, sz)) < 1e-3);
    }
  }
  // Random texels: within the texels' extremes everywhere, far outside and at infinity too.
  const HeightSketch s = sketch_of(kW, kH, random_grey(kW * kH, 5));
  test::TestRandom rng(11);
  const auto coordinate = [&](test::TestRandom& random) { return random.uniform(-6.0, kW + 5.0); };
  for (int k = 0; k < 20000; ++k) {
    const double sx = coordinate(rng), sz = coordinate(rng);
    const float f = sample_at<float>(s, float(sx), float(sz));
    CHECK(f >= s.min_height - 1e-4f);
    CHECK(f <= s.max_height + 1e-4f);
    CHECK(std::abs(double(f) - sample_at<double>(s, sx, sz)) < 1e-3);
  }
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(std::isfinite(sample_at<float>(s, inf, -inf)));
  // Clamped outside: from one texel beyond the edge centres on, constant outwards.
  for (const double sz : {0.3, 2.5, 5.9}) {
    CHECK(sample_at<double>(s, -1.0, sz) == sample_at<double>(s, -40.0, sz));
    CHECK(sample_at<double>(s, kW, sz) == sample_at<double>(s, 1e30, sz));
    CHECK(sample_at<float>(s, -1.0f, float(sz)) == sample_at<float>(s, -inf, float(sz)));
  }
  // C1 and C2 across texel borders (and at the edge), from one-sided differences in double.
  const double h = 1e-4;
  for (int i = -1; i <= kW; ++i) {
    for (const double sz : {0.5, 3.25}) {
      const auto f = [&](double sx) { return sample_at<double>(s, sx, sz); };
      const double x = i;
      const double left = (f(x) - f(x - h)) / h, right = (f(x + h) - f(x)) / h;
      const double left2 = (f(x) - 2 * f(x - h) + f(x - 2 * h)) / (h * h);
      const double right2 = (f(x + 2 * h) - 2 * f(x + h) + f(x)) / (h * h);
      INFO("texel border " << i);
      CHECK(std::abs(left - right) < 1e-3 * 1000.0);    // slopes up to ~1000 units / texel
      CHECK(std::abs(left2 - right2) < 0.05 * 1000.0);  // second differences' noise ~h
    }
  }
}

TEST_CASE("sketchRangeBoundsEveryValueItsRegionCanTake", "[sketch]") {
  constexpr int kW = 40, kH = 30;
  const HeightSketch s = sketch_of(kW, kH, random_grey(kW * kH, 17));
  const SketchSettings settings = settings_of(-200, 800);
  const SketchPlan plan = make_sketch_plan(settings, s, 12.5, -7.0);
  const SketchParams<float> p = make_sketch_params<float>(plan, &s);
  test::TestRandom rng(3);
  const auto corner = [](test::TestRandom& r) { return r.uniform(-160.0, 160.0); };
  const auto size = [](test::TestRandom& r) { return r.uniform(0.0, 30.0); };
  for (int box = 0; box < 300; ++box) {
    const double x0 = corner(rng), z0 = corner(rng), x1 = x0 + size(rng), z1 = z0 + size(rng);
    const SketchRange range = sketch_range(plan, s, x0, x1, z0, z1);
    CHECK(range.lo >= s.min_height);
    CHECK(range.hi <= s.max_height);
    for (int k = 0; k < 40; ++k) {
      const float dx = float(x0 + (x1 - x0) * (k % 7) / 6.0);
      const float dz = float(z0 + (z1 - z0) * (k / 7) / 5.0);
      const float v = sample_sketch<float>(p, s.heights, p.offset_x + dx * p.inv_cell_x,
                                           p.offset_z + dz * p.inv_cell_z);
      CHECK(v >= range.lo - 1e-3);
      CHECK(v <= range.hi + 1e-3);
    }
  }
}

TEST_CASE("simdSketchIsBitIdenticalToTheReferenceOnEveryTarget", "[sketch][simd]") {
  constexpr int kW = 33, kH = 21;
  const HeightSketch s = sketch_of(kW, kH, random_grey(kW * kH, 23));
  const SketchPlan plan = make_sketch_plan(settings_of(-200, 800), s, 1e6 + 3.25, -2e5);
  const SketchParams<float> p = make_sketch_params<float>(plan, &s);
  // Points inside, outside and far outside the extent; a mask; odd counts for the tails.
  test::TestRandom rng(29);
  const auto near_x = [](test::TestRandom& r) {
    return float(r.uniform(-1e6 - 150.0, -1e6 + 150.0));
  };
  const auto near_z = [](test::TestRandom& r) { return float(r.uniform(2e5 - 80.0, 2e5 + 80.0)); };
  constexpr std::size_t kCount = 1003;
  std::vector<float> dx(kCount), dz(kCount), base(kCount);
  std::vector<std::uint8_t> mask(kCount);
  for (std::size_t k = 0; k < kCount; ++k) {
    dx[k] = k % 13 == 0 ? 1e9f : near_x(rng);
    dz[k] = k % 17 == 0 ? -3e8f : near_z(rng);
    base[k] = float(k) * 0.37f - 100.0f;
    mask[k] = static_cast<std::uint8_t>(k % 5 != 0);
  }
  const EachTarget targets;
  for (const std::span<const std::uint8_t> m :
       {std::span<const std::uint8_t>(), std::span<const std::uint8_t>(mask)}) {
    for (const IndexRange range : {IndexRange{0, kCount}, IndexRange{3, kCount - 2}}) {
      std::vector<float> reference = base;
      add_sketch<float>(p, s.heights, range, dx, dz, {}, m, reference);
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        std::vector<float> vector = base;
        simd::add_sketch(p, s.heights, range, dx, dz, {}, m, vector);
        INFO(target);
        CHECK(std::memcmp(vector.data(), reference.data(), kCount * sizeof(float)) == 0);
      }
    }
  }
  INFO("targets compiled in but not run here: " << targets.skipped());
}

}  // namespace
}  // namespace relief
