#include "pipeline/build_info.h"

#include "simd/targets.h"

namespace relief {

BuildInfo build_info() {
  BuildInfo info;
  info.version = RELIEF_BUILD_VERSION;
  info.compiler = RELIEF_BUILD_COMPILER;
  info.build_type = RELIEF_BUILD_TYPE;
  info.flags = RELIEF_BUILD_FLAGS;
  info.highway_version = simd::highway_version();
  for (const simd::Target& t : simd::compiled_targets()) {
    info.simd_targets.push_back({t.name, t.supported});
  }
  info.simd_target = simd::current_target();
  return info;
}

std::string_view relief_version() {
  return RELIEF_BUILD_VERSION;
}

std::string backend_label(Backend backend) {
  std::string label(backend_name(backend));
  if (backend == Backend::kSimd) {
    label += " (" + simd::current_target() + ")";
  }
  return label;
}

void force_simd_target(std::string_view name) {
  try {
    simd::force_target(name);
  } catch (const simd::TargetError& e) {
    throw SimdTargetError(e.what());
  }
}

}  // namespace relief
