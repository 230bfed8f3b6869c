#include "tools/render_report.h"

#include <iomanip>

#include "pipeline/build_info.h"
#include "pipeline/statistics.h"

namespace relief {

namespace {

// The median over the runs of stage `s`'s time.
double median_ms(const std::vector<std::vector<StageTime>>& runs, std::size_t s) {
  std::vector<double> values;
  for (const std::vector<StageTime>& run : runs) {
    values.push_back(run[s].ms);
  }
  return median(values);
}

// The median over the runs of the GL pass `p` of the last run, over the runs that had it (every
// run of one scene has the same passes).
double median_pass_ms(const RenderRuns& runs, std::size_t p) {
  const std::string& name = runs.last.gpu_passes[p].name;
  std::vector<double> values;
  for (const std::vector<StageTime>& run : runs.gpu_passes) {
    if (p < run.size() && run[p].name == name) {
      values.push_back(run[p].ms);
    }
  }
  return values.empty() ? runs.last.gpu_passes[p].ms : median(values);
}

void print_medians(std::ostream& out, const std::vector<std::vector<StageTime>>& runs,
                   const char* indent) {
  for (std::size_t s = 0; s < runs.front().size(); ++s) {
    out << indent << std::left << std::setw(40) << runs.front()[s].name << std::right
        << std::setw(10) << median_ms(runs, s) << " ms\n";
  }
}

}  // namespace

void RenderRuns::add(const FrameStats& stats) {
  stages.push_back(stats.stages);
  parts.push_back(stats.tile_parts);
  gpu_passes.push_back(stats.gpu_passes);
  totals.push_back(stats.total_ms);
  last = stats;
}

void print_stage_times(std::ostream& out, const RenderRuns& runs) {
  print_medians(out, runs.stages, "  ");
  out << "    of which, CPU time summed over the threads:\n";
  print_medians(out, runs.parts, "    ");
  out << "  " << std::left << std::setw(40) << "frame" << std::right << std::setw(10)
      << median(runs.totals) << " ms\n";
}

void print_stage_stats(std::ostream& out, const RenderRuns& runs) {
  out << "  " << std::left << std::setw(40) << "stage" << std::setw(9) << "ran" << std::right
      << std::setw(10) << "ms"
      << "\n";
  for (std::size_t s = 0; s < runs.last.stages.size(); ++s) {
    const StageTime& stage = runs.last.stages[s];
    out << "  " << std::left << std::setw(40) << stage.name << std::setw(9)
        << (stage.ran ? "ran" : "skipped") << std::right << std::setw(10)
        << median_ms(runs.stages, s) << "\n";
    for (const WorkCounter& counter : stage.counters) {
      out << "      " << std::left << std::setw(43) << counter.name << std::right << std::setw(14)
          << counter.value << "\n";
    }
  }
  out << "  " << std::left << std::setw(49) << "frame" << std::right << std::setw(10)
      << median(runs.totals) << "\n";
  if (!runs.last.gpu_passes.empty()) {
    // The GL backend's passes: GPU time from timer queries, the read-back's CPU wall time.
    out << "  GL passes (GPU time from timer queries; ms):\n";
    for (std::size_t p = 0; p < runs.last.gpu_passes.size(); ++p) {
      out << "    " << std::left << std::setw(45) << runs.last.gpu_passes[p].name << std::right
          << std::setw(10) << median_pass_ms(runs, p) << "\n";
    }
  }
  print_kernel_table(out, runs.last.kernels);
}

void print_kernel_table(std::ostream& out, const std::vector<KernelReport>& kernels) {
  if (kernels.empty()) {
    return;  // the GL backend: its own stages (docs/gl-backend.md)
  }
  out << "  kernels:\n";
  for (const KernelReport& k : kernels) {
    out << "    " << k.stage << " / " << k.kernel << ": " << k.implementation;
    if (!k.reason.empty()) {
      out << ", because " << k.reason;
    }
    out << "\n";
  }
}

nlohmann::json stage_stats_json(const Scene& scene, Backend backend, const RenderRuns& runs) {
  nlohmann::json stages = nlohmann::json::array();
  for (std::size_t s = 0; s < runs.last.stages.size(); ++s) {
    const StageTime& stage = runs.last.stages[s];
    nlohmann::json counters = nlohmann::json::object();
    for (const WorkCounter& counter : stage.counters) {
      counters[counter.name] = counter.value;
    }
    stages.push_back({{"name", stage.name},
                      {"ran", stage.ran},
                      {"ms", median_ms(runs.stages, s)},
                      {"counters", std::move(counters)}});
  }
  nlohmann::json parts = nlohmann::json::array();
  for (std::size_t s = 0; s < runs.last.tile_parts.size(); ++s) {
    parts.push_back({{"name", runs.last.tile_parts[s].name}, {"ms", median_ms(runs.parts, s)}});
  }
  nlohmann::json passes = nlohmann::json::array();
  for (std::size_t p = 0; p < runs.last.gpu_passes.size(); ++p) {
    passes.push_back({{"name", runs.last.gpu_passes[p].name}, {"ms", median_pass_ms(runs, p)}});
  }
  nlohmann::json kernels = nlohmann::json::array();
  for (const KernelReport& k : runs.last.kernels) {
    kernels.push_back({{"stage", k.stage},
                       {"kernel", k.kernel},
                       {"implementation", k.implementation},
                       {"reason", k.reason}});
  }
  const raster::RasterStats& r = runs.last.raster;
  return {{"image", {{"width", scene.viewport.width}, {"height", scene.viewport.height}}},
          {"grid", {{"width", scene.grid.width}, {"height", scene.grid.height}}},
          {"backend", std::string(backend_name(backend))},
          {"simd_target", backend == Backend::kSimd ? build_info().simd_target : std::string()},
          {"runs", runs.totals.size()},
          {"frame_ms", median(runs.totals)},
          {"setup_ms", runs.setup_ms},
          {"stages", std::move(stages)},
          {"tile_parts", std::move(parts)},
          {"gpu_passes", std::move(passes)},
          {"kernels", std::move(kernels)},
          {"raster", backend == Backend::kGl
                         // GL's own rasteriser: no software set-up pieces or bins (null).
                         ? nlohmann::json{{"triangles", r.triangles},
                                          {"set_up", nullptr},
                                          {"bin_entries", nullptr},
                                          {"bin_bytes", nullptr}}
                         : nlohmann::json{{"triangles", r.triangles},
                                          {"set_up", r.setup},
                                          {"bin_entries", r.bin_entries},
                                          {"bin_bytes", r.bin_bytes}}}};
}

}  // namespace relief
