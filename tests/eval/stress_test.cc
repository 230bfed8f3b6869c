// The stability stress suite (docs/stress.md): the very case list of
// relief stress at a small size on the CPU backends, every buffer finite, peaks within the
// estimate, refusals where expected; and the allocator fix the suite found.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_memory.h"
#include "eval/process_memory.h"
#include "tests/support/cli_support.h"
#include "tests/support/stress_support.h"

namespace relief {
namespace {

const std::vector<Backend> kCpuBackends = {Backend::kReferenceDouble, Backend::kReference,
                                           Backend::kSimd};

TEST_CASE("stressCameraAxesRenderFiniteFramesOnEveryCpuBackend", "[stress]") {
  const std::vector<StressRow> rows = test::run_stress_axes(
      {"distance", "altitude", "pitch", "position"}, test::stress_settings(kCpuBackends));
  CHECK(std::count_if(rows.begin(), rows.end(),
                      [](const StressRow& r) { return r.status == StressStatus::kOk; }) > 50);
}

TEST_CASE("stressTerrainAxesRenderFiniteFramesOnEveryCpuBackend", "[stress]") {
  test::run_stress_axes({"warp", "H", "r", "octaves"}, test::stress_settings(kCpuBackends));
}

TEST_CASE("stressSizeAxesRefuseTheMaximumByTheEstimateAndRenderTheLargestThatFits",
          "[stress][heavy]") {
  const std::vector<StressRow> rows =
      test::run_stress_axes({"grid", "viewport"}, test::stress_settings(kCpuBackends));
  int refused_by_memory = 0, largest = 0;
  for (const StressRow& row : rows) {
    refused_by_memory += row.message.find("needs about") != std::string::npos;
    largest +=
        row.name.rfind("largest within the budget", 0) == 0 && row.status == StressStatus::kOk;
  }
  CHECK(refused_by_memory == 6);  // 8192^2 grid and 16384^2 viewport on three backends
  CHECK(largest == 6);
}

TEST_CASE("floatErrorDoesNotGrowWithTheCameraDistanceUpTo1e12", "[stress]") {
  // Moved by whole periods of the terrain (P lattice cells), the camera sees the same terrain
  // at every distance: the float error must be the one at the origin, within the bounds.
  const std::vector<StressRow> rows = test::run_stress_axes(
      {"distance"}, test::stress_settings({Backend::kReferenceDouble, Backend::kSimd}));
  const auto origin = std::find_if(rows.begin(), rows.end(), [](const StressRow& r) {
    return r.name == "x + 0" && r.backend == "simd";
  });
  REQUIRE(origin != rows.end());
  REQUIRE(origin->height_error.has_value());
  int far_rows = 0;
  for (const StressRow& row : rows) {
    if (row.backend != "simd") {
      continue;
    }
    INFO(row.name);
    REQUIRE(row.height_error.has_value());
    CHECK(*row.height_error <= test::kTestHeightErrorBound);
    CHECK(*row.srgb_share <= test::kTestSrgbShareBound);
    if (row.name != "x + 1000") {  // 1000 is less than a period: other terrain
      CHECK(*row.height_error <= 1.5 * *origin->height_error + 1e-6);
      ++far_rows;
    }
  }
  CHECK(far_rows == 4);
}

TEST_CASE("aFrameBufferJustOverAMebibyteKeepsNoMoreResidentThanItHolds", "[stress][memory]") {
  // The stress suite's first finding: frame buffers were mapped in whole 2 MiB huge pages, so a
  // 1 MiB + 4 KiB plane (a 512 x 512 grid's, padded) became 2 MiB resident, twice the memory
  // estimate. Mappings are whole 4 KiB pages now.
  if (!peak_memory_measurable()) {
    SUCCEED("no /proc peak measurement here (sanitizer build or not Linux)");
    return;
  }
  release_free_memory();
  const std::size_t bytes = (std::size_t{1} << 20) + 4096;
  const std::optional<std::uintmax_t> before = start_peak_measurement();
  REQUIRE(before.has_value());
  void* const block = allocate_frame_buffer(bytes, 64);
  std::memset(block, 1, bytes);
  const std::optional<std::uintmax_t> peak = peak_resident_bytes();
  free_frame_buffer(block, bytes, 64);
  release_free_memory();
  REQUIRE(peak.has_value());
  CHECK(*peak - *before <= bytes + (std::size_t{256} << 10));
}

TEST_CASE("reliefStressPrintsTheTableAndExitsZeroWhenEveryCheckHolds", "[stress][cli]") {
  const test::CliResult r = test::run(
      {"stress", "--axis", "pitch", "--backend", "simd", "--viewport", "32", "24", "--grid", "16"});
  INFO(r.out << r.err);
  CHECK(r.code == 0);
  CHECK(r.out.find("NaN/inf") != std::string::npos);
  CHECK(r.out.find("pitch -90 ") != std::string::npos);
  CHECK(r.out.find("refused [1]") != std::string::npos);  // pitch -90.01
  CHECK(r.out.find("camera.pitch_deg = -90.01 is out of range") != std::string::npos);
  CHECK(r.out.find("every check holds") != std::string::npos);

  const test::CliResult bad = test::run({"stress", "--axis", "tilt"});
  CHECK(bad.code == 2);
}

}  // namespace
}  // namespace relief
