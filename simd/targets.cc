#include "simd/targets.h"

#include <algorithm>
#include <cctype>

#include <hwy/highway.h>
#include <hwy/targets.h>

namespace relief::simd {

namespace {

// The targets this library's kernels are compiled for: every kernel file defines
// HWY_COMPILE_ALL_ATTAINABLE (simd/CMakeLists.txt), so they all generate the same set.
constexpr std::int64_t kCompiled = HWY_TARGETS;

std::string upper(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return out;
}

}  // namespace

std::vector<Target> compiled_targets() {
  std::vector<Target> targets;
  const std::int64_t supported = hwy::SupportedTargets();
  // Lower bits are better targets in Highway's encoding.
  for (std::int64_t remaining = kCompiled; remaining != 0; remaining &= remaining - 1) {
    const std::int64_t bit = remaining & ~(remaining - 1);
    targets.push_back({bit, hwy::TargetName(bit), (supported & bit) != 0});
  }
  return targets;
}

std::string current_target() {
  const std::int64_t supported = hwy::SupportedTargets() & kCompiled;
  return supported == 0 ? "none" : hwy::TargetName(supported & ~(supported - 1));
}

std::string highway_version() {
  return std::to_string(HWY_MAJOR) + "." + std::to_string(HWY_MINOR) + "." +
         std::to_string(HWY_PATCH);
}

void force_target(std::string_view name) {
  const std::string wanted = upper(name);
  hwy::SetSupportedTargetsForTest(0);  // what the CPU runs, not what an earlier call forced
  if (wanted == "BEST") {
    return;
  }
  std::string names;
  for (const Target& t : compiled_targets()) {
    names += (names.empty() ? "" : ", ") + t.name;
    if (upper(t.name) != wanted) {
      continue;
    }
    if (!t.supported) {
      throw TargetError("this CPU cannot run SIMD target " + t.name + "; it runs " +
                        current_target() + " and below");
    }
    hwy::SetSupportedTargetsForTest(t.bit);
    return;
  }
  throw TargetError("unknown SIMD target \"" + std::string(name) + "\"; compiled in: " + names +
                    ", or best");
}

}  // namespace relief::simd
