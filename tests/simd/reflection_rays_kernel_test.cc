// The reflected rays' set-up as a Highway kernel (simd/reflection_rays.h) against the scalar
// reflection_ray<float> (core/water_reflection.h) on every target this CPU runs: rows of every
// awkward length, a third of the pixels uncovered, ground above and below the water, depths
// from none to deep, and hostile attributes (NaN, infinities, the camera's own position, a
// point straight below it): every ray with weight > 0 bit for bit, weight 0 where the scalar
// ray has none, and nothing past the row written.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/scene/scene_json.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "core/water_reflection.h"
#include "pipeline/scene_resources.h"
#include "simd/reflection_rays.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/hashed_draws.h"
#include "tests/support/simd_targets.h"

namespace relief {
namespace {

bool same(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

TEST_CASE("theReflectionRayKernelIsTheScalarSetUpOnEveryTarget", "[simd][reflections]") {
  for (const char* waves : {"water.wave_strength=0.04", "water.wave_strength=3"}) {
    const Scene scene = resolve_scene("mirror", {waves});
    const SceneResources resources = load_scene_resources(scene);
    const FramePlan frame = make_frame_plan(scene, resources.terrain_values());
    const ShadeParams<float> p =
        make_shade_params<float>(make_shading_plan(scene, frame, resources.lattice.size));
    REQUIRE(p.water_level < 0.0f);
    test::HashedDraws draws(11);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const EachTarget targets;
    int marched = 0;
    for (const std::size_t n : test::awkward_lengths()) {
      std::vector<std::uint32_t> primitive(n);
      std::vector<float> dx(n), height(n), dz(n), depth(n);
      for (std::size_t i = 0; i < n; ++i) {
        primitive[i] = draws.uniform(0, 3) < 1 ? 0xffffffffu : std::uint32_t(i);
        dx[i] = float(draws.uniform(-3000, 3000));
        dz[i] = float(draws.uniform(-3000, 3000));
        height[i] = float(draws.uniform(p.water_level - 200.0, p.water_level + 50.0));
        depth[i] = float(draws.uniform(-1, 40));
        switch (i % 11) {  // hostile attributes among the others
          case 3:
            dx[i] = nan;
            break;
          case 5:
            height[i] = -inf;
            break;
          case 7:
            dx[i] = dz[i] = 0.0f;
            break;  // straight below the camera
          case 9:
            dx[i] = height[i] = dz[i] = 0.0f;
            break;  // the camera's own position
          case 10:
            depth[i] = nan;
            break;
          default:
            break;
        }
      }
      std::vector<ReflectionRay<float>> expected(n);
      for (std::size_t i = 0; i < n; ++i) {
        if (primitive[i] != 0xffffffffu && height[i] < p.water_level) {
          expected[i] = reflection_ray(p, resources.lattice, dx[i], height[i], dz[i], depth[i]);
          marched += expected[i].weight > 0.0f;
        }
      }
      targets.each_with_threads({1}, [&](const std::string& target, int) {
        constexpr float kGuard = 12345.0f;
        std::vector<float> out[7];
        for (std::vector<float>& o : out) {
          o.assign(n + test::kGuardElements, kGuard);
        }
        simd::reflection_rays(
            p, resources.lattice, primitive.data(), dx.data(), height.data(), dz.data(),
            depth.data(), int(n),
            simd::ReflectionRayRow{out[0].data(), out[1].data(), out[2].data(), out[3].data(),
                                   out[4].data(), out[5].data(), out[6].data()});
        INFO(target << ", " << waves << ", " << n << " pixels");
        for (std::size_t i = 0; i < n; ++i) {
          INFO("pixel " << i);
          const ReflectionRay<float>& e = expected[i];
          if (!(e.weight > 0.0f)) {
            REQUIRE_FALSE(out[6][i] > 0.0f);
            continue;
          }
          REQUIRE(same(out[6][i], e.weight));
          REQUIRE(same(out[0][i], e.start.x));
          REQUIRE(same(out[1][i], e.start.z));
          REQUIRE(same(out[2][i], e.surface));
          REQUIRE(same(out[3][i], e.direction.x));
          REQUIRE(same(out[4][i], e.direction.y));
          REQUIRE(same(out[5][i], e.direction.z));
        }
        for (const std::vector<float>& o : out) {
          for (std::size_t i = n; i < o.size(); ++i) {
            REQUIRE(o[i] == kGuard);
          }
        }
      });
    }
    CHECK(marched > 100);
  }
}

}  // namespace
}  // namespace relief
