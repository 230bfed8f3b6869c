// The terrain on a regular grid (pipeline/terrain_samples.h).
#include "pipeline/terrain_samples.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_sketch.h"
#include "core/layer_weights.h"
#include "core/limits.h"
#include "core/lod_rule.h"
#include "core/octave_coordinates.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"

namespace relief {

namespace {

constexpr int kBandRows = 32;  // output rows a task evaluates (plus a margin row each side)

struct Grid {
  double x0, z0, cell_x, cell_z;  // sample (i, j) at x0 + (i + 1/2) cell_x, z0 + (j + 1/2) cell_z
  double camera_x, camera_z;      // the plan's origin: the region's centre
  double x(int i) const { return x0 + (double(i) + 0.5) * cell_x; }
  double z(int j) const { return z0 + (double(j) + 0.5) * cell_z; }
};

// Largest-remainder bytes of weights summing to 1: floor(255 w) each, the remaining units to
// the largest fractional parts (the first layer first among equals), so they sum to 255.
void weight_bytes(const double* w, int layers, std::uint8_t* out) {
  int units[limits::kMaxMaterialLayers];
  double rest[limits::kMaxMaterialLayers];
  int total = 0;
  for (int l = 0; l < layers; ++l) {
    const double scaled = std::clamp(w[l], 0.0, 1.0) * 255.0;
    units[l] = int(std::floor(scaled));
    rest[l] = scaled - units[l];
    total += units[l];
  }
  for (; total < 255; ++total) {
    int best = 0;
    for (int l = 1; l < layers; ++l) {
      best = rest[l] > rest[best] ? l : best;
    }
    ++units[best];
    rest[best] = -1.0;  // each layer takes at most one of the remainder's units
  }
  for (int l = 0; l < layers; ++l) {
    out[l] = static_cast<std::uint8_t>(std::min(units[l], 255));
  }
}

}  // namespace

std::uintmax_t terrain_samples_bytes(const Scene& scene, const SampleRegion& region,
                                     const TerrainSampleRequest& request) {
  const std::uintmax_t samples = std::uintmax_t(region.width) * std::uintmax_t(region.height);
  const std::uintmax_t per_sample =
      4 + (request.normals ? 12 : 0) + (request.weights ? scene.shading.layers.size() : 0);
  // A band's four double rows per sample (dx, dz, nu, height) on each thread at once (at most
  // one band each, and no more than there are bands).
  const std::uintmax_t bands = std::uintmax_t((region.height + kBandRows - 1) / kBandRows);
  const std::uintmax_t threads =
      std::min<std::uintmax_t>(std::uintmax_t(tbb::this_task_arena::max_concurrency()), bands);
  const std::uintmax_t band =
      4 * 8 * std::uintmax_t(region.width + 2) * std::uintmax_t(kBandRows + 2) * threads;
  return samples * per_sample + band;
}

TerrainSamples sample_terrain(const Scene& scene, const SceneResources& resources,
                              const SampleRegion& region, const TerrainSampleRequest& request,
                              const std::function<void(int, int)>& progress) {
  const auto& r = region.rect;
  const Grid grid{r[0],
                  r[1],
                  (r[2] - r[0]) / region.width,  // width >= 2, x1 > x0: a positive cell
                  (r[3] - r[1]) / region.height,
                  0.5 * r[0] + 0.5 * r[2],
                  0.5 * r[1] + 0.5 * r[3]};
  Scene centred = scene;
  centred.camera.position = {grid.camera_x, scene.camera.position[1], grid.camera_z};
  const FramePlan plan =
      make_frame_plan(centred, resources.terrain_values(), resources.sketch_or_null());
  TerrainParams<double> params = make_terrain_params<double>(plan);
  const double camera_y = centred.camera.position[1];

  // §4.1's octave count (or a field's level) for a vertex of the samples' spacing.
  const double spacing = std::max(grid.cell_x, grid.cell_z);
  double nu = lod_octave_count(plan.lod.c0, plan.lod.c1, plan.lod.nu_max, limits::kMinSpacingSq,
                               spacing * spacing);
  if (plan.lod.whole_octaves) {
    nu = std::ceil(nu);
  }
  // The octaves' coordinate forms, once for the region: its margin's corners reach farthest.
  {
    const double cx[4] = {grid.x(-1), grid.x(region.width), grid.x(-1), grid.x(region.width)};
    const double cz[4] = {grid.z(-1), grid.z(-1), grid.z(region.height), grid.z(region.height)};
    double dx[4], dz[4];
    for (int k = 0; k < 4; ++k) {
      dx[k] = cx[k] - grid.camera_x;
      dz[k] = cz[k] - grid.camera_z;
    }
    const double nus[4] = {nu, nu, nu, nu};
    const std::uint8_t valid[4] = {1, 1, 1, 1};
    choose_coordinate_forms(plan.terrain,
                            octave_reach<double>(IndexRange{0, 4}, dx, dz, nus, valid), params.fbm);
  }

  const ShadingPlan shading = make_shading_plan(centred, plan, resources.lattice.size);
  const ShadeParams<double> shade = make_shade_params<double>(shading);

  TerrainSamples out;
  out.bound_low = plan.bounds.world_min;
  out.bound_high = plan.bounds.world_max;
  out.width = region.width;
  out.height = region.height;
  out.layers = int(scene.shading.layers.size());
  const std::size_t count = std::size_t(region.width) * std::size_t(region.height);
  out.heights.resize(count);
  if (request.normals) {
    out.normals.resize(3 * count);
  }
  if (request.weights) {
    out.weights.resize(std::size_t(out.layers) * count);
  }

  const int bands = (region.height + kBandRows - 1) / kBandRows;
  std::atomic<int> rows_done{0};
  std::mutex progress_mutex;
  int reported = 0;  // under progress_mutex: the count shown only grows
  const HeightSketch* sketch = resources.sketch_or_null();
  tbb::parallel_for(0, bands, [&](int band) {
    const int j0 = band * kBandRows;
    const int j1 = std::min(j0 + kBandRows, region.height);
    const int w = region.width + 2, h = j1 - j0 + 2;  // with the margin: i = -1 .. width
    const std::size_t n = std::size_t(w) * std::size_t(h);
    std::vector<double> dx(n), dz(n), nus(n, nu), height(n, 0.0);
    for (int jj = 0; jj < h; ++jj) {
      const double z = grid.z(j0 - 1 + jj) - grid.camera_z;
      for (int ii = 0; ii < w; ++ii) {
        dx[std::size_t(jj) * w + ii] = grid.x(ii - 1) - grid.camera_x;
        dz[std::size_t(jj) * w + ii] = z;
      }
    }
    const IndexRange all{0, n};
    evaluate_fbm<double>(params.fbm, *plan.terrain.lattice, all, dx, dz, nus, {}, height);
    if (params.sketch.enabled != 0 && sketch != nullptr) {
      add_sketch<double>(params.sketch, sketch->heights, all, dx, dz, nus, {}, height);
    }
    const auto at = [&](int i, int jj) { return height[std::size_t(jj) * w + std::size_t(i + 1)]; };
    for (int j = j0; j < j1; ++j) {
      const int jj = j - j0 + 1;
      for (int i = 0; i < region.width; ++i) {
        const std::size_t k = std::size_t(j) * std::size_t(region.width) + std::size_t(i);
        const double relative = at(i, jj);
        out.heights[k] = static_cast<float>(relative + camera_y);
        if (!request.normals && !request.weights) {
          continue;
        }
        // Central differences over two cells (> 0), the normal scaled by its largest
        // component before it is normalised, so no square overflows.
        const double gx = (at(i + 1, jj) - at(i - 1, jj)) / (2.0 * grid.cell_x);
        const double gz = (at(i, jj + 1) - at(i, jj - 1)) / (2.0 * grid.cell_z);
        const double largest = std::max({std::abs(gx), 1.0, std::abs(gz)});
        const double nx = -gx / largest, ny = 1.0 / largest, nz = -gz / largest;
        const double length = std::sqrt(nx * nx + ny * ny + nz * nz);  // >= 1
        if (request.normals) {
          out.normals[3 * k] = static_cast<float>(nx / length + 0.0);  // -0 as 0
          out.normals[3 * k + 1] = static_cast<float>(ny / length);
          out.normals[3 * k + 2] = static_cast<float>(nz / length + 0.0);
        }
        if (request.weights) {
          const double slope = std::min(std::hypot(gx, gz), limits::kMaxSlope);
          double weights[limits::kMaxMaterialLayers] = {};
          layer_weights<double>(shade, relative, slope, 0.0, weights);
          weight_bytes(weights, out.layers, &out.weights[std::size_t(out.layers) * k]);
        }
      }
    }
    const int done = rows_done.fetch_add(j1 - j0) + (j1 - j0);
    if (progress) {
      const std::lock_guard lock(progress_mutex);
      reported = std::max(reported, done);
      progress(reported, region.height);
    }
  });
  const auto [low, high] = std::minmax_element(out.heights.begin(), out.heights.end());
  out.low = *low;
  out.high = *high;
  return out;
}

}  // namespace relief
