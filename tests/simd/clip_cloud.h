// Hostile floats and clip-space vertex clouds for the tests of the set-up's per-vertex kernels
// (tests/simd/simd_setup_test.cc, tests/simd/vertex_kernel_ranges_test.cc), and how their
// prepared vertices are compared with the portable loops'.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "raster/triangle_setup.h"
#include "tests/support/test_support.h"

namespace relief::test {

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  // Empty vectors may hold null pointers, which memcmp may not be given even for 0 bytes.
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// A float from a pool of hostile values, or uniform in [-range, range].
inline float hostile(TestRandom& random, double range) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float specials[] = {0.0f,
                            -0.0f,
                            std::numeric_limits<float>::quiet_NaN(),
                            kInf,
                            -kInf,
                            std::numeric_limits<float>::denorm_min(),
                            -std::numeric_limits<float>::min(),
                            std::numeric_limits<float>::max(),
                            1.0f,
                            -1.0f,
                            0.5f,
                            1e-30f};
  const double pick = random.uniform(0, 1);
  if (pick < 0.15) {
    return specials[static_cast<int>(random.uniform(0, 12)) % 12];
  }
  return static_cast<float>(random.uniform(-range, range));
}

// Clip-space vertices for the per-vertex passes: a mix of ordinary ones in the frustum, ones
// at the guard band, at window coordinates halfway between 16.8 steps (ties), and hostile ones.
struct ClipCloud {
  std::vector<float> x, y, z, w;
  std::vector<std::uint8_t> valid, need;
};

inline ClipCloud clip_cloud(std::size_t count, const raster::SnapConstants& c) {
  TestRandom random(29);
  ClipCloud cloud;
  for (std::size_t k = 0; k < count; ++k) {
    float x, y, z, w;
    const double kind = random.uniform(0, 1);
    if (kind < 0.4) {  // inside the frustum
      w = float(random.uniform(0.1, 1e3));
      x = float(random.uniform(-1, 1)) * w;
      y = float(random.uniform(-1, 1)) * w;
      z = float(random.uniform(0, 1)) * w;
    } else if (kind < 0.55) {  // window x, y on a snapping tie (w = 1: exact)
      w = 1.0f;
      const float wx = float(std::floor(random.uniform(0, 1280))) + 0.5f + 1.0f / 512.0f;
      x = (wx - c.translate_x) / c.scale_x;
      y = float(random.uniform(-1, 1));
      z = 0.5f;
    } else if (kind < 0.7) {  // at or just beyond the guard band
      w = float(random.uniform(0.5, 4));
      const float g = c.guard_x * w;
      x = random.uniform(0, 1) < 0.5 ? g : std::nextafter(g, 1e30f);
      x = random.uniform(0, 1) < 0.5 ? x : -x;
      y = float(random.uniform(-1, 1)) * c.guard_y * w;
      z = float(random.uniform(0, 1)) * w;
    } else {
      x = hostile(random, 1e6);
      y = hostile(random, 1e6);
      z = hostile(random, 1e3);
      w = hostile(random, 1e3);
    }
    cloud.x.push_back(x);
    cloud.y.push_back(y);
    cloud.z.push_back(z);
    cloud.w.push_back(w);
    cloud.valid.push_back(random.uniform(0, 1) < 0.9 ? 1 : 0);
    cloud.need.push_back(static_cast<std::uint8_t>(random.uniform(0, 4)));
  }
  return cloud;
}

// A kernel's prepared vertices are the portable loops': every field bit for bit, and the window
// depth where it is read.
inline void check_prepared(const raster::PreparedVertices& got,
                           const raster::PreparedVertices& want) {
  CHECK(got.begin == want.begin);
  CHECK(same_bytes(got.flags, want.flags));
  CHECK(same_bytes(got.outcode, want.outcode));
  CHECK(same_bytes(got.floor_x, want.floor_x));
  CHECK(same_bytes(got.floor_y, want.floor_y));
  CHECK(same_bytes(got.fx, want.fx));
  CHECK(same_bytes(got.fy, want.fy));
  // The window depth is read where a vertex is snapped; there it must agree.
  for (std::size_t k = 0; k < want.flags.size(); ++k) {
    if (want.flags[k] & raster::PreparedVertices::kSnapped) {
      CHECK(std::memcmp(&got.z[k], &want.z[k], sizeof(float)) == 0);
    }
  }
}

}  // namespace relief::test
