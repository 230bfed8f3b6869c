#include "eval/stress_run.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <span>

#include <tbb/task_arena.h>

#include "core/scene/scene_json.h"
#include "eval/frame_comparison.h"
#include "eval/process_memory.h"
#include "pipeline/gl_backend.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"

namespace relief {

namespace {

constexpr FrameOutputs kAllOutputs{true, true, true, true, true, true};

template <class T>
void count_nonfinite(std::span<const T> values, StressRow& row) {
  row.values += values.size();
  for (const T v : values) {
    row.nonfinite += !std::isfinite(v);
  }
}

// Every plane of stages 2-4, padding included (it must hold finite values too).
template <class Real>
void count_grid(const GridBuffers<Real>& g, StressRow& row) {
  for (const auto* plane :
       {&g.dx, &g.dz, &g.sigma, &g.nu, &g.height, &g.nx, &g.ny, &g.nz, &g.slope, &g.water_depth}) {
    count_nonfinite<Real>(*plane, row);
  }
}

void count_pixels(const FrameImage& image, StressRow& row) {
  for (const auto* plane :
       {&image.linear, &image.depth, &image.normal, &image.world_height, &image.octaves}) {
    count_nonfinite<float>(*plane, row);
  }
}

// The truth the float backends are compared with: reference-double's grid and frame.
struct Truth {
  std::optional<GridBuffers<double>> grid;
  std::optional<FrameImage> image;
};

void compare_with_truth(const GridBuffers<float>& grid, const FrameImage& image, const Truth& truth,
                        const Scene& scene, StressRow& row) {
  if (!truth.grid || !truth.image) {
    return;
  }
  double height = 0;
  const GridBuffers<double>& d = *truth.grid;
  for (std::size_t k = 0; k < std::min(grid.valid.size(), d.valid.size()); ++k) {
    if (grid.valid[k] && d.valid[k]) {
      height = std::max(height, std::abs(double(grid.height[k]) - d.height[k]));
    }
  }
  row.height_error = height / scene.terrain.amplitude;
  std::size_t differing = 0;
  for (std::size_t k = 0; k < image.srgb.size(); ++k) {
    differing += std::abs(int(image.srgb[k]) - int(truth.image->srgb[k])) > 2;
  }
  row.srgb_share = image.srgb.empty() ? 0.0 : double(differing) / double(image.srgb.size());
  row.psnr_db = compare_pixels(image, *truth.image).srgb_psnr;
}

// Stages 2-4 at every vertex (the grid relief stages writes) and the whole frame.
template <class Real>
void run_backend(const Scene& scene, const StressCase& stress_case, const StressSettings& settings,
                 Backend backend, StressRow& row, Truth& truth) {
  FrameRequest request;
  request.backend = backend;
  request.outputs = kAllOutputs;
  const MemoryEstimate estimate = estimate_render_memory(scene, backend, kAllOutputs);
  row.estimate_bytes = estimate.total();
  check_memory(estimate, settings.budget, "this render", render_memory_advice(scene));
  request.max_bin_bytes = memory_left(estimate, settings.budget);

  const bool measure = settings.measure_memory && peak_memory_measurable();
  if (measure) {
    release_free_memory();
  }
  const std::uintmax_t before = measure ? start_peak_measurement().value_or(0) : 0;
  const SceneResources resources = load_scene_resources(scene);
  Frame frame = render_frame(scene, resources, request);
  const std::optional<std::uintmax_t> peak = peak_resident_bytes();
  if (before > 0 && peak) {
    row.measured_bytes = *peak > before ? *peak - before : 0;
  }
  // The set-up triangles and bins are counted by the frame, not estimated up front
  // (job_memory.h).
  row.estimate_bytes += frame.stats.raster.setup_bytes + frame.stats.raster.bin_bytes;
  row.frame_ms = frame.stats.total_ms;
  if (settings.keep_images) {
    row.width = frame.image.width;
    row.height = frame.image.height;
    row.srgb = frame.image.srgb;
  }
  TerrainRun<Real> terrain = run_terrain_stages<Real>(scene, resources.terrain_values(), backend,
                                                      resources.sketch_or_null());
  count_grid(terrain.grid, row);
  count_pixels(frame.image, row);

  if (row.nonfinite > 0) {
    row.failures.push_back(std::to_string(row.nonfinite) + " NaN or infinite values");
  }
  if (row.measured_bytes &&
      *row.measured_bytes > row.estimate_bytes + stress_memory_allowance(backend)) {
    row.failures.push_back("peak memory above the estimate and its allowance");
  }
  if constexpr (std::is_same_v<Real, double>) {
    truth.grid.emplace(std::move(terrain.grid));
    truth.image.emplace(std::move(frame.image));
  } else {
    compare_with_truth(terrain.grid, frame.image, truth, scene, row);
    if (stress_case.error_bounded && row.height_error) {
      if (*row.height_error > kStressHeightErrorBound) {
        row.failures.push_back("height error above the bound");
      }
      if (*row.srgb_share > kStressSrgbShareBound) {
        row.failures.push_back("image difference above the bound");
      }
    }
  }
}

void check_refusal(const StressCase& stress_case, StressRow& row) {
  const bool refused = row.status == StressStatus::kRefused;
  const bool must_refuse = stress_case.refused_on(row.backend);
  if (must_refuse && !refused && row.status != StressStatus::kSkipped) {
    row.failures.push_back("accepted, but must be refused naming " + stress_case.refused_naming);
  } else if (refused && !must_refuse) {
    row.failures.push_back("refused unexpectedly");
  } else if (refused && row.message.find(stress_case.refused_naming) == std::string::npos) {
    row.failures.push_back("the refusal does not name " + stress_case.refused_naming);
  }
}

}  // namespace

std::uintmax_t stress_memory_allowance(Backend backend) {
  const auto threads = std::uintmax_t(tbb::this_task_arena::max_concurrency());
  return kStressFixedAllowanceBytes + threads * kStressThreadAllowanceBytes +
         (backend == Backend::kGl ? kStressGlAllowanceBytes : 0);
}

std::vector<StressRow> run_stress_case(const Scene& base, const StressCase& stress_case,
                                       const StressSettings& settings) {
  StressRow blank;
  blank.axis = stress_case.axis;
  blank.name = stress_case.name;
  Scene scene = base;
  try {
    for (const std::string& assignment : stress_case.overrides) {
      apply_scene_layer(scene, parse_override(assignment), "--set " + assignment);
    }
    validate_scene(scene);
  } catch (const SceneError& e) {
    StressRow row = blank;
    row.backend = "all";
    row.status = StressStatus::kRefused;
    row.message = e.what();
    check_refusal(stress_case, row);
    return {row};
  }
  std::vector<Backend> order = settings.backends;
  std::stable_partition(order.begin(), order.end(),
                        [](Backend b) { return b == Backend::kReferenceDouble; });
  Truth truth;
  std::vector<StressRow> rows;
  for (Backend backend : order) {
    StressRow row = blank;
    row.backend = std::string(backend_name(backend));
    if (backend == Backend::kGl && !settings.gl_unavailable.empty()) {
      row.status = StressStatus::kSkipped;
      row.message = settings.gl_unavailable;
    } else if (backend == Backend::kGl && !gl_missing_feature(scene).empty()) {
      row.status = StressStatus::kSkipped;
      row.message = gl_missing_feature(scene);
    } else {
      try {
        if (backend == Backend::kReferenceDouble) {
          run_backend<double>(scene, stress_case, settings, backend, row, truth);
        } else {
          run_backend<float>(scene, stress_case, settings, backend, row, truth);
        }
      } catch (const MemoryLimitError& e) {
        row.status = StressStatus::kRefused;
        row.message = e.what();
      } catch (const GlBackendError& e) {
        row.status = StressStatus::kRefused;
        row.message = e.what();
      } catch (const std::bad_alloc&) {
        row.failures.push_back("out of memory although the estimate fitted");
      }
    }
    check_refusal(stress_case, row);
    rows.push_back(std::move(row));
  }
  return rows;
}

void warm_up_stress_backends(const Scene& base, const StressSettings& settings) {
  Scene scene = base;
  scene.viewport.width = scene.viewport.height = 16;
  scene.grid.width = scene.grid.height = 16;
  const SceneResources resources = load_scene_resources(scene);
  for (Backend backend : settings.backends) {
    if (backend == Backend::kGl && !settings.gl_unavailable.empty()) {
      continue;
    }
    FrameRequest request;
    request.backend = backend;
    request.outputs = kAllOutputs;
    try {
      render_frame(scene, resources, request);
    } catch (const std::exception&) {
      // The cases report what goes wrong.
    }
  }
}

std::vector<Backend> stress_backends(std::string& gl_unavailable) {
  std::vector<Backend> backends = {Backend::kReferenceDouble, Backend::kReference, Backend::kSimd,
                                   Backend::kGl};
  gl_unavailable.clear();
  if (!gl_backend_built()) {
    gl_unavailable = "this build has no GL side (RELIEF_WITH_GL=OFF)";
  } else {
    try {
      gl_renderer();
    } catch (const GlBackendError& e) {
      gl_unavailable = std::string("no GL context: ") + e.what();
    }
  }
  return backends;
}

}  // namespace relief
