#include <algorithm>
#include <iomanip>
#include <ostream>
#include <vector>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "pipeline/build_info.h"
#include "pipeline/frame.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "pipeline/statistics.h"
#include "tools/cli.h"
#include "tools/commands.h"
#include "tools/stage_outputs.h"

namespace relief {

namespace {

// The double backend's buffers for the PFM files, each value rounded once to float.
GridBuffers<float> rounded(const GridBuffers<double>& d) {
  GridBuffers<float> f(d.layout);
  const auto copy = [](const AlignedVector<double>& from, AlignedVector<float>& to) {
    std::transform(from.begin(), from.end(), to.begin(),
                   [](double v) { return static_cast<float>(v); });
  };
  copy(d.dx, f.dx);
  copy(d.dz, f.dz);
  copy(d.sigma, f.sigma);
  copy(d.nu, f.nu);
  f.valid = d.valid;
  copy(d.height, f.height);
  copy(d.nx, f.nx);
  copy(d.ny, f.ny);
  copy(d.nz, f.nz);
  copy(d.slope, f.slope);
  copy(d.water_depth, f.water_depth);
  if (!d.bent_x.empty()) {  // a planet frame's bend (docs/planet.md)
    f.allocate_bent();
    copy(d.bent_x, f.bent_x);
    copy(d.bent_y, f.bent_y);
    copy(d.bent_z, f.bent_z);
    copy(d.bent_drop, f.bent_drop);
  }
  return f;
}

// Runs stages 1-4 `repeat` times; returns the plan and the last run's buffers in float.
template <class Real>
std::pair<FramePlan, GridBuffers<float>> run(const Scene& scene, const NoiseLattice& lattice,
                                             const HeightSketch* sketch, Backend backend,
                                             int repeat,
                                             std::vector<std::vector<StageTime>>& times) {
  for (int k = 0;; ++k) {
    TerrainRun<Real> terrain = run_terrain_stages<Real>(scene, lattice, backend, sketch);
    times.push_back(std::move(terrain.stages));
    if (k + 1 == repeat) {
      if constexpr (std::is_same_v<Real, float>) {
        return {std::move(terrain.plan), std::move(terrain.grid)};
      } else {
        return {std::move(terrain.plan), rounded(terrain.grid)};
      }
    }
  }
}

}  // namespace

int run_stages_command(const Scene& scene, const StagesOptions& options, std::ostream& out,
                       std::ostream& err) {
  check_memory(estimate_stages_memory(scene, options.backend), options.budget, "relief stages",
               "Lower grid.width/height");
  // Stage 3's grid: terrain.basis's composed images, or the noise lattice.
  std::vector<std::string> notes;
  std::optional<NoiseLattice> basis = load_basis_grid(scene, &notes);
  print_scene_notes(notes, err);
  const NoiseLattice lattice =
      basis ? std::move(*basis)
            : make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const std::optional<HeightSketch> sketch_texels = load_height_sketch(scene);  // checked here
  const HeightSketch* sketch = sketch_texels ? &*sketch_texels : nullptr;
  std::vector<std::vector<StageTime>> times;
  const Backend backend = options.backend;
  const auto [plan, buffers] =
      backend == Backend::kReferenceDouble
          ? run<double>(scene, lattice, sketch, backend, options.repeat, times)
          : run<float>(scene, lattice, sketch, backend, options.repeat, times);
  const std::string dir = options.out_dir.empty() ? scene.output.stages_dir : options.out_dir;
  write_stage_outputs(dir, scene, plan, buffers, options.raw_format);
  out << std::fixed << std::setprecision(3) << "grid " << plan.layout.width << "x"
      << plan.layout.height << ", " << plan.terrain.octaves.count << " octaves, backend "
      << backend_label(options.backend) << ", median of " << options.repeat << " run(s):\n";
  for (std::size_t s = 0; s < times.front().size(); ++s) {
    std::vector<double> values;
    for (const std::vector<StageTime>& run_times : times) {
      values.push_back(run_times[s].ms);
    }
    out << "  " << std::left << std::setw(28) << times.front()[s].name << std::right
        << std::setw(10) << median(values) << " ms\n";
  }
  out << "wrote " << dir << "/stages.json and one PNG + "
      << (options.raw_format == FloatFormat::kExr ? "EXR" : "PFM") << " per field\n";
  return kExitOk;
}

}  // namespace relief
