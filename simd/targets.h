// The Highway targets Relief's kernels were compiled for, those this CPU runs, and a switch
// that forces one of them for every later dispatch (relief --simd TARGET, and the tests that
// check every target against the scalar reference on whatever machine runs them).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace relief::simd {

struct Target {
  std::int64_t bit = 0;    // Highway's HWY_* bit
  std::string name;        // "AVX3", "AVX2", "SSE4", "SSSE3", "EMU128", "SCALAR"
  bool supported = false;  // this CPU runs it
};

// Every target compiled in, best first.
std::vector<Target> compiled_targets();

// The target the next dispatch uses (the best supported one, or the forced one).
std::string current_target();

// Highway's version and the flags the kernels were built with, for relief info.
std::string highway_version();

class TargetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Makes every later dispatch use `name` (case-insensitive); "best" undoes it. Throws
// TargetError naming the targets compiled in when `name` is not one of them, or when this
// CPU cannot run it. Not thread-safe: call it before a frame starts.
void force_target(std::string_view name);

}  // namespace relief::simd
