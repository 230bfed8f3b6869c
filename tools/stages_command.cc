#include <algorithm>
#include <iomanip>
#include <ostream>
#include <vector>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "pipeline/frame_runner.h"
#include "pipeline/job_memory.h"
#include "pipeline/statistics.h"
#include "tools/cli.h"
#include "tools/commands.h"
#include "tools/stage_outputs.h"

namespace relief {

int run_stages_command(const Scene& scene, const StagesOptions& options, std::ostream& out) {
  check_memory(estimate_stages_memory(scene), options.budget, "relief stages",
               "Lower grid.width/height");
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> buffers(plan.layout);
  std::vector<double> domain_ms, fbm_ms, surface_ms;
  for (int run = 0; run < options.repeat; ++run) {
    const StageTimings t = run_terrain_stages_parallel(plan, buffers);
    domain_ms.push_back(t.projected_domain_ms);
    fbm_ms.push_back(t.fbm_ms);
    surface_ms.push_back(t.surface_ms);
  }
  const std::string dir = options.out_dir.empty() ? scene.output.stages_dir : options.out_dir;
  write_stage_outputs(dir, scene, plan, buffers);
  out << std::fixed << std::setprecision(3) << "grid " << plan.layout.width << "x"
      << plan.layout.height << ", " << plan.terrain.octaves.count << " octaves, median of "
      << options.repeat << " run(s):\n"
      << "  stage 1-2 projected domain  " << median(domain_ms) << " ms\n"
      << "  stage 3   fractal           " << median(fbm_ms) << " ms\n"
      << "  stage 4   surface           " << median(surface_ms) << " ms\n"
      << "wrote " << dir << "/stages.json and one PNG + PFM per field\n";
  return kExitOk;
}

}  // namespace relief
