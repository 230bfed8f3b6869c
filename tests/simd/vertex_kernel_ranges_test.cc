// The per-vertex Highway kernels of stages 5 and 6 (simd/vertex_transform.h: the transform and
// gradient shading's vertex light; simd/vertex_snap.h) over ranges of every awkward length
// (tests/simd/kernel_ranges.h) on every
// target this CPU runs: every value inside the range is the scalar one (core/vertex_transform.h,
// raster's portable per-vertex loops) bit for bit, and no element outside the range is written.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/stage_params.h"
#include "core/vertex_transform.h"
#include "raster/raster_types.h"
#include "raster/triangle_setup.h"
#include "simd/targets.h"
#include "simd/vertex_snap.h"
#include "simd/vertex_transform.h"
#include "tests/simd/clip_cloud.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// Every buffer is this long: the largest start, the longest range and the guard.
constexpr std::size_t kCapacity = 5 + 53 + test::kGuardElements;

// Stage 5's four outputs, all holding the sentinel.
struct ClipOutputs {
  std::vector<float> x, y, z, w;

  ClipOutputs()
      : x(kCapacity, test::sentinel<float>()),
        y(kCapacity, test::sentinel<float>()),
        z(kCapacity, test::sentinel<float>()),
        w(kCapacity, test::sentinel<float>()) {}
  ClipSpans<float> spans() { return {x, y, z, w}; }
};

TEST_CASE("simdVertexLightingAtAwkwardLengthsIsTheScalarOneAndWritesOnlyItsRange", "[simd]") {
  const EachTarget targets;
  test::TestRandom random(67);
  TransformParams<float> params;
  params.gouraud = 1;
  params.sun_x = 0.48f;
  params.sun_y = 0.6f;
  params.sun_z = -0.64f;
  std::vector<float> nx(kCapacity), ny(kCapacity), nz(kCapacity);
  std::vector<std::uint8_t> need(kCapacity);
  for (std::size_t k = 0; k < kCapacity; ++k) {
    // Unit normals and exact edge cases: facing away (clamped), -0, and NaN (0, as the
    // scalar ndl > 0 decides).
    nx[k] = float(random.uniform(-1, 1));
    ny[k] = float(random.uniform(-1, 1));
    nz[k] = float(random.uniform(-1, 1));
    need[k] = static_cast<std::uint8_t>(random.uniform(0, 4));
  }
  nx[7] = ny[7] = nz[7] = -0.0f;
  ny[11] = std::numeric_limits<float>::quiet_NaN();
  for (const std::span<const std::uint8_t> mask :
       {std::span<const std::uint8_t>(), std::span<const std::uint8_t>(need)}) {
    for (const std::size_t start : test::kRangeStarts) {
      for (const std::size_t length : test::awkward_lengths()) {
        const IndexRange range{start, start + length};
        std::vector<float> expected(kCapacity, test::sentinel<float>());
        light_vertices<float>(params, range, nx, ny, nz, mask, expected);
        INFO("mask " << mask.size() << ", start " << start << ", length " << length);
        REQUIRE(test::untouched_outside(expected, range.begin, range.end));
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          std::vector<float> got(kCapacity, test::sentinel<float>());
          simd::light_vertices(params, range, nx, ny, nz, mask, got);
          INFO(target);
          CHECK(test::same_bits(got, expected));
        }
      }
    }
  }
}

TEST_CASE("simdVertexTransformAtAwkwardLengthsIsTheScalarTransformAndWritesOnlyItsRange",
          "[simd]") {
  const EachTarget targets;
  test::TestRandom random(61);
  TransformParams<float> params;
  for (int c = 0; c < 3; ++c) {
    params.row_x[c] = float(random.uniform(-2, 2));
    params.row_y[c] = float(random.uniform(-2, 2));
    params.row_w[c] = float(random.uniform(-1, 1));
  }
  params.z_clip = 0.5f;
  std::vector<float> dx(kCapacity), dz(kCapacity), height(kCapacity);
  std::vector<std::uint8_t> need(kCapacity);
  for (std::size_t k = 0; k < kCapacity; ++k) {
    dx[k] = float(random.uniform(-1e4, 1e4));
    dz[k] = float(random.uniform(-1e4, 1e4));
    height[k] = float(random.uniform(-500, 500));
    need[k] = static_cast<std::uint8_t>(random.uniform(0, 4));  // kEvaluate | kDraw bits
  }
  for (const std::span<const std::uint8_t> mask :
       {std::span<const std::uint8_t>(), std::span<const std::uint8_t>(need)}) {
    for (const std::size_t start : test::kRangeStarts) {
      for (const std::size_t length : test::awkward_lengths()) {
        const IndexRange range{start, start + length};
        ClipOutputs expected;
        transform_vertices<float>(params, range, dx, dz, height, mask, expected.spans());
        INFO("mask " << mask.size() << ", start " << start << ", length " << length);
        REQUIRE(test::untouched_outside(expected.w, range.begin, range.end));
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          ClipOutputs got;
          simd::transform_vertices(params, range, dx, dz, height, mask, got.spans());
          INFO(target);
          CHECK(test::same_bits(got.x, expected.x));
          CHECK(test::same_bits(got.y, expected.y));
          CHECK(test::same_bits(got.z, expected.z));
          CHECK(test::same_bits(got.w, expected.w));
        }
      }
    }
  }
}

// The snap kernels as raster's set-up calls them (raster::SnapKernels), each run on outputs
// that start `guard_start` elements into buffers holding the sentinel, with kGuardElements
// after them: the values go on to the set-up, and the elements around them are checked here.
// (SnapKernels are plain function pointers, hence the state at namespace scope.)
std::size_t guard_start = 0;
int writes_outside = 0;

template <class T>
struct GuardedOutput {
  T* caller;
  std::size_t n;
  std::vector<T> buffer;

  GuardedOutput(T* out, std::size_t count)
      : caller(out), n(count), buffer(test::sentinel_buffer<T>(guard_start, count)) {}
  T* data() { return buffer.data() + guard_start; }
  ~GuardedOutput() {
    writes_outside += !test::untouched_outside(buffer, guard_start, guard_start + n);
    std::copy_n(buffer.begin() + std::ptrdiff_t(guard_start), n, caller);
  }
};

void guarded_window(const raster::SnapConstants& c, const float* x, const float* y, const float* z,
                    const float* w, const std::uint8_t* valid, const std::uint8_t* need,
                    std::size_t n, float* window_x, float* window_y, float* window_z,
                    std::uint32_t* bits) {
  const simd::SnapConstants constants{c.guard_x, c.guard_y,     c.scale_x,
                                      c.scale_y, c.translate_x, c.translate_y};
  GuardedOutput<float> gx(window_x, n), gy(window_y, n), gz(window_z, n);
  GuardedOutput<std::uint32_t> gbits(bits, n);
  simd::window_vertices(constants, x, y, z, w, valid, need, n, gx.data(), gy.data(), gz.data(),
                        gbits.data());
}

void guarded_snap(std::size_t n, const std::uint32_t* bits, const float* window_x,
                  const float* window_y, std::uint8_t* flags, std::uint8_t* outcode, float* floor_x,
                  float* floor_y, std::int32_t* fx, std::int32_t* fy) {
  GuardedOutput<std::uint8_t> gflags(flags, n), goutcode(outcode, n);
  GuardedOutput<float> gfloor_x(floor_x, n), gfloor_y(floor_y, n);
  GuardedOutput<std::int32_t> gfx(fx, n), gfy(fy, n);
  simd::snap_vertices(n, bits, window_x, window_y, gflags.data(), goutcode.data(), gfloor_x.data(),
                      gfloor_y.data(), gfx.data(), gfy.data());
}

constexpr raster::SnapKernels kGuardedSnapKernels{guarded_window, guarded_snap};

TEST_CASE("simdVertexSnapAtAwkwardLengthsIsThePortableSnapAndWritesOnlyItsRange", "[simd]") {
  const EachTarget targets;
  raster::RasterState state;
  state.width = 1280;
  state.height = 1024;
  state.viewport = {0, 0, 1280, 1024};
  const raster::TriangleSetup portable(state);
  raster::TriangleSetup kernels(state);
  kernels.set_snap_kernels(&kGuardedSnapKernels);
  const test::ClipCloud cloud = test::clip_cloud(kCapacity, portable.snap_constants());
  const raster::ClipVertices vertices{cloud.x, cloud.y, cloud.z, cloud.w};
  const std::span<const std::uint8_t> none;
  for (const bool flagged : {false, true}) {
    const std::span<const std::uint8_t> valid = flagged ? std::span(cloud.valid) : none;
    const std::span<const std::uint8_t> need = flagged ? std::span(cloud.need) : none;
    // The vertices' own start (the kernels' inputs) and the outputs' start in their buffers.
    for (const std::size_t start : test::kRangeStarts) {
      guard_start = start;
      for (const std::size_t length : test::awkward_lengths()) {
        raster::PreparedVertices expected;
        portable.prepare_vertices(vertices, start, start + length, valid, need, expected);
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          writes_outside = 0;
          raster::PreparedVertices got;
          kernels.prepare_vertices(vertices, start, start + length, valid, need, got);
          INFO(target << ", flags " << flagged << ", start " << start << ", length " << length);
          CHECK(writes_outside == 0);
          test::check_prepared(got, expected);
        }
      }
    }
  }
}

}  // namespace
}  // namespace relief
