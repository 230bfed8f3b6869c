// Choosing the kernel table of a CPU frame (cpu_kernels.h) and naming it for the reports.
#include "pipeline/cpu_kernels.h"

#include <stdexcept>
#include <type_traits>

#include "simd/targets.h"

namespace relief {

template <class Real>
CpuKernels<Real> cpu_kernels(Backend backend, bool planet) {
  if constexpr (std::is_same_v<Real, double>) {
    if (backend != Backend::kReferenceDouble) {
      throw std::invalid_argument("cpu_kernels<double>: only reference-double runs in double");
    }
    return portable_kernels<double>(planet);
  } else {
    switch (backend) {
      case Backend::kReference:
        return portable_kernels<float>(planet);
      case Backend::kSimd:
        return highway_kernels(planet);
      default:
        throw std::invalid_argument("cpu_kernels<float>: not a float CPU backend");
    }
  }
}

template CpuKernels<float> cpu_kernels<float>(Backend backend, bool planet);
template CpuKernels<double> cpu_kernels<double>(Backend backend, bool planet);

std::string kernel_kind_label(KernelKind kind, bool double_precision) {
  if (kind == KernelKind::kHighway) {
    return "Highway (" + simd::current_target() + ")";
  }
  return double_precision ? "portable loop (double)" : "portable loop (float)";
}

std::vector<KernelReport> kernel_reports(std::span<const KernelChoice> choices,
                                         bool double_precision) {
  std::vector<KernelReport> reports;
  reports.reserve(choices.size());
  for (const KernelChoice& c : choices) {
    const char* stage = "";
    for (const StageInfo& info : kFrameStages) {
      if (info.id == c.stage) {
        stage = info.name;
      }
    }
    reports.push_back({stage, c.kernel, kernel_kind_label(c.kind, double_precision), c.reason});
  }
  return reports;
}

}  // namespace relief
