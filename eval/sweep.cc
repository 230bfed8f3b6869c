#include "eval/sweep.h"
#include "pipeline/basis_resources.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <numeric>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "eval/box_filter.h"
#include "eval/height_error.h"
#include "eval/image_error.h"
#include "eval/pareto.h"
#include "pipeline/basis_resources.h"
#include "pipeline/job_memory.h"

namespace relief {

namespace {

using Clock = std::chrono::steady_clock;

struct HeightFigures {
  double max = 0, rms = 0;
};

// The float height error depends on the terrain, the grid and the camera (the configured scene
// at its own viewport) and on the backend's arithmetic: reference and simd give the same bits,
// GL its own, reference-double none. Cached, since most rows share the default's terrain.
class HeightErrors {
 public:
  HeightFigures get(const Scene& configured, Backend backend) {
    if (backend == Backend::kReferenceDouble) {
      return {};  // the double heights are what the others are measured against
    }
    const Backend arithmetic = backend == Backend::kGl ? Backend::kGl : Backend::kSimd;
    std::string key = scene_json_text(configured) + std::string(backend_name(arithmetic));
    const auto found = cache_.find(key);
    if (found != cache_.end()) {
      return found->second;
    }
    const std::optional<NoiseLattice> basis = load_basis_grid(configured);
    const NoiseLattice lattice =
        basis ? *basis
              : make_noise_lattice(configured.terrain.seed, configured.terrain.lattice_size);
    const VertexHeightError e = vertex_height_error(configured, lattice, arithmetic);
    return cache_.emplace(std::move(key), HeightFigures{e.max, e.rms}).first->second;
  }

 private:
  std::map<std::string, HeightFigures> cache_;
};

// The resources (lattice, proto-textures) of a configuration's scene, built once: no knob of
// the sweep changes them today, and their build is not part of a frame's time.
class ResourceCache {
 public:
  const SceneResources& get(const Scene& rendered) {
    const nlohmann::json scene = scene_to_json(rendered);
    std::string key = scene["shading"].dump() + " " + scene["terrain"]["seed"].dump() + " " +
                      scene["terrain"]["lattice_size"].dump();
    const auto found = cache_.find(key);
    if (found != cache_.end()) {
      return found->second;
    }
    return cache_.emplace(std::move(key), load_scene_resources(rendered)).first->second;
  }

 private:
  std::map<std::string, SceneResources> cache_;
};

struct TimedFrame {
  std::vector<float> linear;  // the scene's viewport, box-filtered when supersampled
  double ms = 0;              // the frame and, when supersampled, its reduction
};

// What the frame costs is timed as a user renders it: the sRGB image alone (a supersampling
// renderer needs the linear radiance it reduces, so supersampled frames ask for it). The
// error is measured on a frame that also returns its linear radiance (`for_error`), untimed:
// the same pixels (the image is encoded from them), 12 more bytes a pixel to write.
TimedFrame render_configuration(const Scene& scene, const SweepConfiguration& c,
                                ResourceCache& resources, std::uint64_t max_bin_bytes,
                                bool for_error) {
  const Scene rendered = rendered_scene(scene, c);
  const SceneResources& loaded = resources.get(rendered);
  FrameRequest request;
  request.backend = c.backend;
  request.outputs.linear = for_error || c.supersample > 1;
  request.max_bin_bytes = max_bin_bytes;
  const Clock::time_point start = Clock::now();
  std::vector<float> linear = render_frame(rendered, loaded, request).image.linear;
  if (c.supersample > 1) {
    // Part of the configuration's cost: the reduction a supersampling renderer does.
    linear =
        box_filter_rgb(linear, rendered.viewport.width, rendered.viewport.height, c.supersample);
  }
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  return {std::move(linear), ms};
}

void measure_error(const Scene& scene, std::span<const float> linear,
                   std::span<const float> reference, HeightErrors& heights, SweepRow& row) {
  const ImageError e = image_error(linear, reference, scene.viewport.width, scene.viewport.height);
  row.psnr_db = e.psnr_db;
  row.rmse = e.rmse;
  row.max_error = e.max_error;
  row.mean_flip = e.mean_flip;
  const HeightFigures h =
      heights.get(configured_scene(scene, row.configuration), row.configuration.backend);
  row.height_max = h.max;
  row.height_rms = h.rms;
}

// The order of a round: the plan's in round 0, then a different shuffle in each round (by a
// fixed hash, the same on every run), so that no configuration always follows the same one
// (a large frame before a small one can leave it slower: freed memory, cold caches).
std::vector<int> round_order(int n, int round) {
  std::vector<int> order(std::size_t(n), 0);
  std::iota(order.begin(), order.end(), 0);
  if (round > 0) {
    const auto key = [round](int k) {
      // SplitMix64's finaliser of (round, k).
      std::uint64_t z = (std::uint64_t(round) << 32 | std::uint64_t(k)) + 0x9e3779b97f4a7c15u;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
      return z ^ (z >> 31);
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  }
  return order;
}

}  // namespace

// Rounds, not runs: each round renders every configuration once, so that the machine's load,
// which drifts over a sweep of minutes, weighs on every configuration alike instead of on the
// few that ran while it was high. Frames are deterministic: the error is measured on round 0's.
std::vector<SweepRow> run_sweep(const Scene& scene,
                                std::span<const SweepConfiguration> configurations,
                                std::span<const float> reference, int repeat,
                                std::uint64_t max_bin_bytes, const SweepProgress& progress) {
  const int n = int(configurations.size());
  repeat = std::max(repeat, 1);
  std::vector<SweepRow> rows(configurations.size());
  std::vector<std::vector<double>> times(configurations.size());
  HeightErrors heights;
  ResourceCache resources;
  if (n > 0) {
    // Untimed: the first frame of a process pays for starting the worker threads.
    render_configuration(scene, configurations[0], resources, max_bin_bytes, false);
  }
  for (int round = 0; round < repeat; ++round) {
    int done_in_round = 0;
    for (int k : round_order(n, round)) {
      if (progress) {
        progress(round * n + done_in_round++, repeat * n,
                 configurations[k].name + (repeat > 1 ? " (round " + std::to_string(round + 1) +
                                                            " of " + std::to_string(repeat) + ")"
                                                      : std::string()));
      }
      if (round == 0) {
        const TimedFrame frame =
            render_configuration(scene, configurations[k], resources, max_bin_bytes, true);
        rows[k].configuration = configurations[k];
        measure_error(scene, frame.linear, reference, heights, rows[k]);
      }
      times[k].push_back(
          render_configuration(scene, configurations[k], resources, max_bin_bytes, false).ms);
    }
  }
  if (progress) {
    progress(repeat * n, repeat * n, "");
  }
  for (int k = 0; k < n; ++k) {
    std::sort(times[k].begin(), times[k].end());
    rows[k].median_ms = times[k][times[k].size() / 2];  // the upper median for an even count
  }
  std::vector<ParetoPoint> points;
  for (const SweepRow& row : rows) {
    points.push_back({row.median_ms, row.mean_flip});
  }
  const std::vector<bool> front = pareto_front(points);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    rows[k].on_pareto_front = front[k];
  }
  return rows;
}

MemoryEstimate sweep_memory(const Scene& scene,
                            std::span<const SweepConfiguration> configurations) {
  MemoryEstimate largest;
  for (const SweepConfiguration& c : configurations) {
    const Scene rendered = rendered_scene(scene, c);
    FrameOutputs outputs;
    outputs.linear = true;
    MemoryEstimate render = estimate_render_memory(rendered, c.backend, outputs);
    const int width = scene.viewport.width, height = scene.viewport.height;
    render.add("box-filtered copy", c.supersample > 1 ? 12 * std::uintmax_t(width) * height : 0);
    render.add("error figures", image_error_bytes(width, height));
    // The height check runs after the frame is dropped: the float stages and a double grid.
    const Scene configured = configured_scene(scene, c);
    MemoryEstimate heights = estimate_stages_memory(configured, Backend::kSimd);
    for (const auto& part : estimate_stages_memory(configured, Backend::kReferenceDouble).parts) {
      heights.add("double " + part.first, part.second);
    }
    for (const MemoryEstimate* e : {&render, &heights}) {
      if (e->total() > largest.total()) {
        largest = *e;
      }
    }
  }
  return largest;
}

}  // namespace relief
