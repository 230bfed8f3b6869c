// The cases of the stability stress suite (docs/stress.md): a base scene
// pushed to the ends of each axis the float pipeline is sensitive to, one field at a time.
// relief stress prints them as a table and tests/eval/stress_test.cc runs the same list at a
// smaller size; stress_run.h runs one case on every backend and checks it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "pipeline/frame.h"

namespace relief {

struct StressCase {
  std::string axis;                    // "distance", "altitude", "pitch", "warp", "H", ...
  std::string name;                    // what this case sets, briefly: "x + 1e9"
  std::vector<std::string> overrides;  // --set assignments applied to the base scene
  // Non-empty: the case must be refused (a scene error or a memory estimate over the budget)
  // with a message containing this text, the field it names.
  std::string refused_naming;
  // Where only some backends' estimates exceed the budget (set-up's scratch is the CPU
  // rasteriser's alone): the backends (backend_name) that must refuse; empty: every backend.
  std::vector<std::string> refused_backends;
  // The float error against the reference-double backend must stay within the bounds of
  // stress_run.h (the distance axis: the error must not grow with the distance).
  bool error_bounded = false;

  // Whether `backend` (backend_name) must refuse this case.
  bool refused_on(const std::string& backend) const {
    if (refused_naming.empty()) {
      return false;
    }
    for (const std::string& b : refused_backends) {
      if (b == backend) {
        return true;
      }
    }
    return refused_backends.empty();
  }
};

// The cases for `base` (validated), in axis order. Heights relative to the terrain (just
// above it, inside it, under water) are computed from the base scene's terrain under its
// camera; the largest grid and viewport are the largest whose render estimate
// (job_memory.h, every per-pixel output requested) fits 90% of `budget_bytes` (the rest is
// left to the rasteriser's bins) for every backend in `backends`.
std::vector<StressCase> make_stress_cases(const Scene& base, std::uintmax_t budget_bytes,
                                          const std::vector<Backend>& backends);

// The axes in the order make_stress_cases lists them.
std::vector<std::string> stress_axes();

}  // namespace relief
