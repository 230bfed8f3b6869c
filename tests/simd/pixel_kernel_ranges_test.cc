// The per-pixel Highway kernels of stages 8 and 9 (simd/shade.h, simd/srgb.h) over rows of
// every awkward width (tests/simd/kernel_ranges.h) on every target this CPU runs: the radiance
// and the work counters are the scalar shading's (core/shade.h: terrain_radiance and
// background_radiance times the exposure, as pipeline/tile_pass.cc applies them), the bytes
// srgb_byte's (core/srgb.h), bit for bit, and nothing outside the rectangle or range is
// written.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/scene/scene_json.h"
#include "core/shade.h"
#include "core/shading_plan.h"
#include "core/srgb.h"
#include "core/stage_params.h"
#include "pipeline/scene_resources.h"
#include "simd/shade.h"
#include "simd/srgb.h"
#include "simd/targets.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr int kPixelRows = 2;

// Resolved attributes of plausible terrain (camera-relative positions below the camera,
// normals pointing up, shallow and dry ground) at `count` pixels, a quarter of them uncovered
// (the background). Stage 8's arithmetic is the same for any finite input; these reach its
// branches: water, steep rock, texture levels from the derivatives.
struct ResolvedPixels {
  std::vector<std::uint32_t> primitive;
  std::vector<float> field[14];  // ShadingInputs' order, dx to water_depth

  explicit ResolvedPixels(std::size_t count) {
    test::TestRandom random(73);
    for (std::size_t k = 0; k < count; ++k) {
      primitive.push_back(random.uniform(0, 1) < 0.25 ? 0xffffffffu
                                                      : std::uint32_t(random.uniform(0, 1e6)));
      const double nx = random.uniform(-0.7, 0.7), nz = random.uniform(-0.7, 0.7);
      const double ny = random.uniform(0.3, 1.0);
      const double values[14] = {random.uniform(-1500, 1500),
                                 random.uniform(-1500, 1500),
                                 random.uniform(-800, 100),
                                 random.uniform(-3, 3),
                                 random.uniform(-3, 3),
                                 random.uniform(-3, 3),
                                 random.uniform(-3, 3),
                                 random.uniform(-3, 3),
                                 random.uniform(-3, 3),
                                 nx,
                                 ny,
                                 nz,
                                 std::sqrt(nx * nx + nz * nz) / ny,
                                 std::max(0.0, random.uniform(-10, 30))};
      for (int f = 0; f < 14; ++f) {
        field[f].push_back(float(values[f]));
      }
    }
  }

  // The inputs of the pixels from `start` on.
  ShadingInputs from(std::size_t start) const {
    const auto at = [&](int f) { return std::span<const float>(field[f]).subspan(start); };
    return {std::span<const std::uint32_t>(primitive).subspan(start),
            at(0),
            at(1),
            at(2),
            at(3),
            at(4),
            at(5),
            at(6),
            at(7),
            at(8),
            at(9),
            at(10),
            at(11),
            at(12),
            at(13)};
  }
};

bool same_work(const ShadeWork& a, const ShadeWork& b) {
  return a.terrain_pixels == b.terrain_pixels && a.background_pixels == b.background_pixels &&
         a.texture_fetches == b.texture_fetches && a.water_pixels == b.water_pixels &&
         a.fogged_pixels == b.fogged_pixels && a.dither_samples == b.dither_samples &&
         a.specular_pixels == b.specular_pixels && a.facing_normals == b.facing_normals &&
         a.cloud_view_paths == b.cloud_view_paths && a.cloud_sun_paths == b.cloud_sun_paths &&
         a.cloud_lookups == b.cloud_lookups;
}

TEST_CASE("simdShadingOfAwkwardRectanglesIsTheScalarShadingAndWritesOnlyTheRectangle", "[simd]") {
  const EachTarget targets;
  ShadeWork all;  // of the scalar shading: every branch reached
  // The lake: water, fog and specular; alpine: triplanar texturing and snow.
  for (const char* preset : {"lake", "alpine"}) {
    const Scene scene = resolve_scene(
        preset, {"viewport.width=160", "viewport.height=96", "grid.width=16", "grid.height=16"});
    const SceneResources resources = load_scene_resources(scene);
    const FramePlan plan = make_frame_plan(scene, resources.lattice);
    ShadeParams<float> params =
        make_shade_params<float>(make_shading_plan(scene, plan, resources.lattice.size));
    add_planet_shading(plan, scene.terrain.base_height, params);  // the plane: nothing
    const ShadeResources shade_resources{&resources.lattice, resources.textures};
    for (const std::size_t width : test::awkward_lengths()) {
      // Rows a few pixels longer than the rectangle, so no row starts aligned.
      const int stride = int(width) + 7;
      const std::size_t pixels = std::size_t(kPixelRows) * std::size_t(stride);
      for (const std::size_t start : test::kRangeStarts) {
        const int x0 = 40 + int(start), y0 = 30 + int(start);
        const ResolvedPixels attributes(start + pixels);
        const ShadingInputs in = attributes.from(start);
        // The scalar loop of the tile pass, pixel by pixel.
        std::vector<float> expected = test::sentinel_buffer<float>(3 * start, 3 * pixels);
        ShadeWork expected_work;
        for (int j = 0; j < kPixelRows; ++j) {
          for (int i = 0; i < int(width); ++i) {
            const std::size_t k = std::size_t(j) * std::size_t(stride) + std::size_t(i);
            const Vec3<float> radiance =
                in.primitive[k] != 0xffffffffu
                    ? terrain_radiance<float>(params, shade_resources, in.at<float>(k),
                                              expected_work)
                    : background_radiance<float>(params, shade_resources, x0 + i, y0 + j,
                                                 expected_work);
            float* const rgb = expected.data() + 3 * (start + k);
            rgb[0] = radiance.x * params.exposure;
            rgb[1] = radiance.y * params.exposure;
            rgb[2] = radiance.z * params.exposure;
          }
        }
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          std::vector<float> got = test::sentinel_buffer<float>(3 * start, 3 * pixels);
          ShadeWork work;
          simd::shade_rect(params, shade_resources, in, x0, y0, int(width), kPixelRows, stride,
                           std::span<float>(got).subspan(3 * start), work);
          INFO(preset << " on " << target << ", width " << width << ", start " << start);
          CHECK(test::same_bits(got, expected));
          CHECK(same_work(work, expected_work));
        }
        all += expected_work;
      }
    }
  }
  // Normals facing away from the eye turned (facing_normal), and others not.
  CHECK(all.facing_normals > 0);
  CHECK(all.facing_normals < all.terrain_pixels);
}

TEST_CASE("simdSrgbEncodingOfAwkwardRangesIsSrgbByteAndWritesOnlyItsRange", "[simd]") {
  const EachTarget targets;
  // Specials and values across the sRGB curve's range, spread over every range tried.
  const float specials[] = {0.0f,
                            -0.0f,
                            1.0f,
                            -1.0f,
                            0.5f,
                            1e-45f,
                            3e38f,
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(),
                            std::nanf(""),
                            std::nextafter(1.0f, 0.0f)};
  test::TestRandom random(79);
  std::vector<float> linear;
  for (std::size_t k = 0; k < 5 + 53 + test::kGuardElements; ++k) {
    linear.push_back(k % 4 == 0 ? specials[(k / 4) % std::size(specials)]
                                : float(random.uniform(-0.1, 1.1)));
  }
  for (const std::size_t start : test::kRangeStarts) {
    for (const std::size_t length : test::awkward_lengths()) {
      std::vector<std::uint8_t> expected = test::sentinel_buffer<std::uint8_t>(start, length);
      for (std::size_t k = start; k < start + length; ++k) {
        expected[k] = srgb_byte(linear[k]);
      }
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        std::vector<std::uint8_t> got = test::sentinel_buffer<std::uint8_t>(start, length);
        simd::encode_srgb(std::span<const float>(linear).subspan(start, length),
                          std::span<std::uint8_t>(got).subspan(start, length));
        INFO(target << ", start " << start << ", length " << length);
        CHECK(test::same_bits(got, expected));
      }
    }
  }
}

}  // namespace
}  // namespace relief
