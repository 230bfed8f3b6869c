// The stability stress suite as the tests run it (tests/eval/stress_test.cc,
// tests/gl/gl_stress_test.cc): relief stress's case list, derived from the default scene at a small
// size, on given backends.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <tbb/task_arena.h>
#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "eval/stress_run.h"

namespace relief::test {

// The default scene at 64 x 48 with a 32 x 32 grid and the smallest built-in textures (their
// synthesis would take most of the time); the largest cases fit 32 MiB.
inline Scene stress_base() {
  return resolve_scene("default", {"viewport.width=64", "viewport.height=48", "grid.width=32",
                                   "grid.height=32", "shading.texture_size=16"});
}

inline StressSettings stress_settings(std::vector<Backend> backends) {
  StressSettings settings;
  settings.backends = std::move(backends);
  settings.budget.bytes = std::uintmax_t{32} << 20;
  settings.budget.source = "the tests' budget";
  std::string gl_unavailable;
  stress_backends(gl_unavailable);
  settings.gl_unavailable = gl_unavailable;
  return settings;
}

// The tests' own bounds, stated here rather than taken from the suite under test
// (eval/stress_run.h), so that a loosened suite fails these tests:
// - heights: float stage 3 lies within 1e-4 of the amplitude of double at the same inputs
//   (docs/scene-limits.md), and stage 2's rounding of the vertex positions moves the inputs by
//   as much again: 2e-4 of the amplitude;
// - image: only silhouettes move when a vertex's rounding moves coverage; at the tests' 64 x 48
//   frame a silhouette crosses some 100 of 3072 pixels, and a rounding moves a fraction of
//   them: 2% of the sRGB bytes more than two codes apart;
// - memory: the estimate plus what it leaves out on purpose (docs/stress.md, "Stability stress
//   suite"): 2 MiB (the first triangle slab's huge page), 1 MiB a worker thread (a tile's
//   scratch) and, for GL, 16 MiB of driver state.
inline constexpr double kTestHeightErrorBound = 2e-4;
inline constexpr double kTestSrgbShareBound = 0.02;
inline std::uintmax_t test_memory_allowance(const std::string& backend, std::size_t threads) {
  return (std::uintmax_t{2} << 20) + threads * (std::uintmax_t{1} << 20) +
         (backend == "gl" ? std::uintmax_t{16} << 20 : 0);
}

// Runs every case of `axes` and checks every row against the case's expectation and the tests'
// own bounds above (never the suite's verdict, row.passed()); returns the rows. A gl row
// skipped for want of a context fails, as every other GL test does.
inline std::vector<StressRow> run_stress_axes(const std::vector<std::string>& axes,
                                              const StressSettings& settings) {
  const Scene base = stress_base();
  warm_up_stress_backends(base, settings);
  const std::size_t threads = std::size_t(tbb::this_task_arena::max_concurrency());
  std::vector<StressRow> rows;
  for (const StressCase& c : make_stress_cases(base, settings.budget.bytes, settings.backends)) {
    if (std::find(axes.begin(), axes.end(), c.axis) == axes.end()) {
      continue;
    }
    for (StressRow& row : run_stress_case(base, c, settings)) {
      INFO(row.axis << ": " << row.name << " on " << row.backend << ": " << row.message);
      CHECK(row.status != StressStatus::kSkipped);
      if (c.refused_on(row.backend)) {
        // Refused by the scene's validation or the memory estimate, naming what is too large.
        CHECK(row.status == StressStatus::kRefused);
        CHECK_THAT(row.message, Catch::Contains(c.refused_naming));
      } else {
        CHECK(row.status == StressStatus::kOk);
      }
      if (row.status == StressStatus::kOk) {
        CHECK(row.nonfinite == 0);
        CHECK(row.values > 0);
        if (row.measured_bytes) {
          CHECK(*row.measured_bytes <=
                row.estimate_bytes + test_memory_allowance(row.backend, threads));
        }
        if (c.error_bounded && row.backend != "reference-double") {
          REQUIRE(row.height_error.has_value());
          REQUIRE(row.srgb_share.has_value());
          CHECK(*row.height_error <= kTestHeightErrorBound);
          CHECK(*row.srgb_share <= kTestSrgbShareBound);
        }
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

}  // namespace relief::test
