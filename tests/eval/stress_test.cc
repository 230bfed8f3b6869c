// The stability stress suite (docs/stress.md): the very case list of
// relief stress at a small size on the CPU backends, every buffer finite, peaks within the
// estimate, refusals where expected; and the allocator fix the suite found.
#include <algorithm>
#include <cstring>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include <tbb/global_control.h>
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
    // The narrow grids fit or not by the machine's thread count (the test below).
    const bool narrow = row.name == "2x8192, margin 0" || row.name == "8192x2, margin 0";
    refused_by_memory += !narrow && row.message.find("needs about") != std::string::npos;
    largest +=
        row.name.rfind("largest within the budget", 0) == 0 && row.status == StressStatus::kOk;
  }
  CHECK(refused_by_memory == 6);  // 8192^2 grid and 16384^2 viewport on three backends
  CHECK(largest == 6);
}

// Set-up's scratch grows with the threads (1.1 MiB a thread on a 2 x 8192 grid): at 16 threads
// the narrow grids exceed the tests' 32 MiB, and the case list must expect the estimate's
// refusal naming the grid, not a render (seen on a 16-core machine, where the case expected a
// render and the estimate refused it).
TEST_CASE("narrowGridsAreRefusedByNameWhereTheThreadsScratchExceedsTheBudget", "[stress]") {
  const Scene base = test::stress_base();
  const StressSettings settings = test::stress_settings({Backend::kReferenceDouble});
  for (const int threads : {1, 16}) {
    const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                          std::size_t(threads));
    INFO(threads << " threads");
    for (const StressCase& c : make_stress_cases(base, settings.budget.bytes, settings.backends)) {
      if (c.name != "2x8192, margin 0" && c.name != "8192x2, margin 0") {
        continue;
      }
      INFO(c.name);
      // 2 x 8192: 16 threads x 1.1 MiB beside a 16 MiB grid exceed 32 MiB; one thread's does
      // not. 8192 x 2: a chunk spans the grid's two rows, 0.5 MiB a thread: fits either way.
      const bool refused = threads == 16 && c.name == "2x8192, margin 0";
      CHECK(c.refused_on("reference-double") == refused);
      for (const StressRow& row : run_stress_case(base, c, settings)) {
        INFO(row.message);
        if (!refused) {
          CHECK(row.status == StressStatus::kOk);
        } else {
          CHECK(row.status == StressStatus::kRefused);
          CHECK_THAT(row.message, Catch::Contains("grid 2x8192"));
        }
      }
    }
  }
}

// GL sets up no triangles: its estimate of the narrow grid has no scratch, so at 16 threads the
// case is refused on the CPU backends and rendered on GL (seen on a 16-core GPU machine, where
// the GL row was expected to be refused).
TEST_CASE("narrowGridsAreRefusedOnlyByTheBackendsWhoseEstimateExceedsTheBudget", "[stress]") {
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 16);
  const Scene base = test::stress_base();
  for (const StressCase& c : make_stress_cases(base, std::uintmax_t{32} << 20,
                                               {Backend::kReferenceDouble, Backend::kGl})) {
    if (c.name == "2x8192, margin 0") {
      CHECK(c.refused_on("reference-double"));
      CHECK_FALSE(c.refused_on("gl"));
      CHECK(c.refused_naming == "grid 2x8192");
    }
  }
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

TEST_CASE("mebibyteFrameBuffersShareHugePagesWithoutDoublingTheirMemory", "[stress][memory]") {
  // A 512 x 512 grid's planes are 1 MiB each: two share a 2 MiB huge page (core/frame_memory.cc),
  // so eleven of them keep at most the eleven MiB they hold and the last huge page's free half
  // resident, not twice that as one huge page each would; every byte reads back as written.
  if (!peak_memory_measurable()) {
    SUCCEED("no /proc peak measurement here (sanitizer build or not Linux)");
    return;
  }
  release_free_memory();
  constexpr std::size_t kBytes = std::size_t{1} << 20;
  constexpr int kBlocks = 11;
  const std::optional<std::uintmax_t> before = start_peak_measurement();
  REQUIRE(before.has_value());
  unsigned char* blocks[kBlocks];
  for (int b = 0; b < kBlocks; ++b) {
    blocks[b] = static_cast<unsigned char*>(allocate_frame_buffer(kBytes, 64));
    std::memset(blocks[b], b + 1, kBytes);
  }
  const std::optional<std::uintmax_t> peak = peak_resident_bytes();
  bool intact = true;
  for (int b = 0; b < kBlocks; ++b) {
    intact = intact && blocks[b][0] == b + 1 && blocks[b][kBytes - 1] == b + 1;
  }
  for (int b = 0; b < kBlocks; ++b) {
    free_frame_buffer(blocks[b], kBytes, 64);
  }
  release_free_memory();
  CHECK(intact);
  REQUIRE(peak.has_value());
  CHECK(*peak - *before <= kBlocks * kBytes + kBytes + (std::size_t{256} << 10));
}

TEST_CASE("aFrameBufferTooLargeToMapIsRefusedAsOutOfMemory", "[stress][memory]") {
  // Sizes whose rounding to whole pages (and the mapping's alignment padding) would wrap
  // around: refused with std::bad_alloc, which every command reports as out of memory, never
  // a null or wrapped block. Only where frames are mapped (a sanitizer's operator new reports
  // such a request itself).
#ifdef RELIEF_FRAME_MAPPINGS
  for (const std::size_t bytes :
       {std::numeric_limits<std::size_t>::max(), std::numeric_limits<std::size_t>::max() - 100,
        std::numeric_limits<std::size_t>::max() - (std::size_t{1} << 20)}) {
    CHECK_THROWS_AS(allocate_frame_buffer(bytes, 64), std::bad_alloc);
  }
#else
  SUCCEED("frames are not mapped in this build");
#endif
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
