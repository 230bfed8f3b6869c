// What this build of Relief is, for relief info: the version, the compiler and its flags, and
// the SIMD targets its kernels were compiled for (simd/targets.h) with those this CPU runs.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/frame.h"

namespace relief {

struct SimdTargetInfo {
  std::string name;
  bool supported = false;  // this CPU runs it
};

struct BuildInfo {
  std::string version;
  std::string compiler;
  std::string build_type;
  std::string flags;  // the compile options every file of the library gets
  std::string highway_version;
  std::vector<SimdTargetInfo> simd_targets;  // compiled in, best first
  std::string simd_target;                   // the one the simd backend uses now
};

BuildInfo build_info();

// The project's version, "MAJOR.MINOR.PATCH" (CMakeLists.txt).
std::string_view relief_version();

// The backend's name as reports print it: "simd (AVX3)" names the target it runs on.
std::string backend_label(Backend backend);

class SimdTargetError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Makes the simd backend use target `name` (case-insensitive; "best" undoes it) from now on.
// Throws SimdTargetError naming the targets compiled in when `name` is not one of them or
// this CPU cannot run it.
void force_simd_target(std::string_view name);

}  // namespace relief
