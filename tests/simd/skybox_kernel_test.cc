// The skybox kernel (simd/skybox.h) against skybox_radiance<float> on every target: the
// directions a frame never hands it (exact ties between components, the cube's edges and
// corners, signed zeros, zero, infinities, NaNs) and many ordinary ones, at 0, 1, lanes - 1,
// lanes + 1 and many directions, bit for bit.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/skybox.h"
#include "simd/skybox.h"
#include "simd/targets.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// Texels from the test generator: any values, each texel its own.
Skybox random_box(int n, unsigned seed) {
  test::TestRandom random(seed);
  Skybox box;
  box.size = n;
  box.texels.resize(18 * std::size_t(n) * n);
  for (float& t : box.texels) {
    t = float(random.uniform(0.0, 4.0));
  }
  return box;
}

TEST_CASE("theSkyboxKernelGivesTheScalarBitsForEveryDirectionOnEveryTarget", "[skybox][simd]") {
  const float inf = HUGE_VALF, nan = std::nanf(""), big = 3.4e38f, tiny = 1e-45f;
  std::vector<float> x, y, z;
  const auto add = [&](float a, float b, float c) {
    x.push_back(a);
    y.push_back(b);
    z.push_back(c);
  };
  const float values[] = {0.0f,  -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, tiny,
                          -tiny, big,   -big, inf,   -inf, nan,   0.7071068f};
  for (const float a : values) {
    for (const float b : values) {
      for (const float c : values) {
        add(a, b, c);  // ties, edges, corners, zeros, overflow and every non-finite mix
      }
    }
  }
  test::TestRandom random(3);
  for (int k = 0; k < 3000; ++k) {
    add(float(random.uniform(-1, 1)), float(random.uniform(-1, 1)), float(random.uniform(-1, 1)));
  }
  const EachTarget targets;
  for (const int n : {4, 12, 64}) {  // 12: a side no power of two, as the struct allows
    const Skybox box = random_box(n, unsigned(n));
    std::vector<float> expected(3 * x.size());
    for (std::size_t k = 0; k < x.size(); ++k) {
      const Vec3<float> r = skybox_radiance(box, Vec3<float>{x[k], y[k], z[k]});
      REQUIRE(std::isfinite(r.x));
      REQUIRE(std::isfinite(r.y));
      REQUIRE(std::isfinite(r.z));
      expected[3 * k] = r.x;
      expected[3 * k + 1] = r.y;
      expected[3 * k + 2] = r.z;
    }
    for (const std::string& target : targets.runnable()) {
      simd::force_target(target);
      for (const std::size_t count :
           {std::size_t(0), std::size_t(1), std::size_t(15), std::size_t(17), x.size()}) {
        std::vector<float> got(3 * count, -1.0f);
        simd::skybox_radiances(box, std::span(x).first(count), std::span(y).first(count),
                               std::span(z).first(count), got);
        INFO(target << ", side " << n << ", " << count << " directions");
        // memcmp is not handed the null pointer of an empty vector.
        REQUIRE((got.empty() ||
                 std::memcmp(got.data(), expected.data(), got.size() * sizeof(float)) == 0));
      }
    }
  }
}

TEST_CASE("theSkyboxKernelRefusesSpansAndBoxesThatDoNotFit", "[skybox][simd]") {
  const Skybox box = random_box(4, 1);
  std::vector<float> a(4), rgb(12), short_rgb(11);
  CHECK_THROWS_AS(simd::skybox_radiances(box, a, a, a, short_rgb), std::invalid_argument);
  Skybox torn = box;
  torn.texels.pop_back();
  CHECK_THROWS_AS(simd::skybox_radiances(torn, a, a, a, rgb), std::invalid_argument);
  CHECK_NOTHROW(simd::skybox_radiances(box, a, a, a, rgb));
}

}  // namespace
}  // namespace relief
