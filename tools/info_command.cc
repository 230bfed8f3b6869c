#include <ostream>

#include "pipeline/build_info.h"
#include "pipeline/cpu_kernels.h"
#include "pipeline/gl_backend.h"
#include "tools/cli.h"
#include "tools/commands.h"
#include "tools/render_report.h"

namespace relief {

int run_info_command(std::ostream& out) {
  const BuildInfo info = build_info();
  out << "relief " << info.version << "\n"
      << "compiler: " << info.compiler << ", " << info.build_type << " build\n"
      << "flags: " << info.flags << "\n"
      << "Highway " << info.highway_version << ", SIMD targets compiled in (best first):\n";
  for (const SimdTargetInfo& t : info.simd_targets) {
    out << "  " << t.name << (t.supported ? "" : "  (this CPU cannot run it)") << "\n";
  }
  out << "simd backend target: " << info.simd_target << "\n";
  // The simd backend's kernel table (cpu_kernels.h), with the reason of each fallback.
  for (const bool planet : {false, true}) {
    out << "simd backend on a " << (planet ? "planet" : "plane") << " frame:\n";
    print_kernel_table(out, kernel_reports(cpu_kernels<float>(Backend::kSimd, planet).choices,
                                           /*double_precision=*/false));
  }
  // The GL backend's context: opening it is the only way to know what it runs on.
  if (!gl_backend_built()) {
    out << "GL backend: not built (RELIEF_WITH_GL=OFF)\n";
  } else {
    try {
      out << "GL backend: " << gl_renderer() << "\n";
    } catch (const GlBackendError& e) {
      out << "GL backend: unavailable: " << e.what() << "\n";
    }
  }
  out.flush();
  return out ? kExitOk : kExitOutputError;
}

}  // namespace relief
