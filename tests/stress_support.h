// The stability stress suite as the tests run it (tests/stress_test.cc, tests/gl_stress_test.cc):
// relief stress's case list, derived from the default scene at a small size, on given backends.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/stress_run.h"

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

// Runs every case of `axes` and requires every row to pass its checks; returns the rows.
inline std::vector<StressRow> run_stress_axes(const std::vector<std::string>& axes,
                                              const StressSettings& settings) {
  const Scene base = stress_base();
  warm_up_stress_backends(base, settings);
  std::vector<StressRow> rows;
  for (const StressCase& c : make_stress_cases(base, settings.budget.bytes, settings.backends)) {
    if (std::find(axes.begin(), axes.end(), c.axis) == axes.end()) {
      continue;
    }
    for (StressRow& row : run_stress_case(base, c, settings)) {
      // The failures in one message: an INFO inside a loop ends with the loop's body.
      std::string failures;
      for (const std::string& failure : row.failures) {
        failures += "; " + failure;
      }
      INFO(row.axis << ": " << row.name << " on " << row.backend << ": " << row.message
                    << failures);
      CHECK(row.passed());
      if (row.status == StressStatus::kOk) {
        CHECK(row.nonfinite == 0);
        CHECK(row.values > 0);
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

}  // namespace relief::test
