#include "eval/ground_truth.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/frame_plan.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/srgb.h"
#include "eval/distance_lod.h"
#include "pipeline/job_memory.h"
#include "raster/bins.h"

namespace relief {

namespace {

[[noreturn]] void refuse(const std::string& option, double value, const std::string& allowed) {
  // The shortest text that reads back as the value: 1.0000000000000002 is not "1".
  throw GroundTruthError(option + " " + format_number(value) + " is out of range; allowed " +
                         allowed);
}

// Bands hold whole tiles (render_frame_bands) and whole output pixels.
int band_granule(int supersample) {
  return std::lcm(raster::kTileSize, supersample);
}

}  // namespace

void validate_ground_truth(const Scene& scene, const GroundTruthSettings& s) {
  if (s.supersample < 1 || s.supersample > kMaxSupersample) {
    refuse("--supersample", s.supersample, "1..." + std::to_string(kMaxSupersample));
  }
  if (s.grid_scale < 1 || s.grid_scale > kMaxGridScale) {
    refuse("--grid-scale", s.grid_scale, "1..." + std::to_string(kMaxGridScale));
  }
  // NaN fails both comparisons' negation: !(x >= lo) catches it.
  if (!(s.octave_epsilon >= kMinOctaveEpsilon) || !(s.octave_epsilon <= kMaxOctaveEpsilon)) {
    refuse("--octave-epsilon", s.octave_epsilon, "1e-06...1 (of a pixel's footprint)");
  }
  const int side = std::max(scene.viewport.width, scene.viewport.height);
  if (std::int64_t(side) * s.supersample > limits::kMaxViewportSide) {
    refuse("--supersample", s.supersample,
           "1..." + std::to_string(limits::kMaxViewportSide / side) + " for this " +
               std::to_string(scene.viewport.width) + "x" + std::to_string(scene.viewport.height) +
               " viewport (the supersampled viewport's side is at most " +
               std::to_string(limits::kMaxViewportSide) + ")");
  }
  const int grid = std::max(scene.grid.width, scene.grid.height);
  if (std::int64_t(grid) * s.grid_scale > limits::kMaxGridSide) {
    refuse("--grid-scale", s.grid_scale,
           "1..." + std::to_string(limits::kMaxGridSide / grid) + " for this " +
               std::to_string(scene.grid.width) + "x" + std::to_string(scene.grid.height) +
               " grid (the finer grid's side is at most " + std::to_string(limits::kMaxGridSide) +
               ")");
  }
  const int granule = band_granule(s.supersample);
  if (s.band_rows < 0 || s.band_rows % granule != 0) {
    refuse("band rows", s.band_rows,
           "0 (automatic) or a multiple of " + std::to_string(granule) + " (the tile size " +
               std::to_string(raster::kTileSize) + " and the supersampling factor)");
  }
}

Scene supersampled_scene(const Scene& scene, const GroundTruthSettings& settings) {
  Scene out = scene;
  out.viewport.width *= settings.supersample;
  out.viewport.height *= settings.supersample;
  out.grid.width *= settings.grid_scale;
  out.grid.height *= settings.grid_scale;
  // A GeoMipMap draws a height field's surface within its tiles' errors: the truth is the
  // surface itself, on the finer grid.
  if (out.terrain.heightfield) {
    out.terrain.heightfield->geomipmap.reset();
  }
  // Cast shadows' and sky light's horizon cache as many times finer as the grid, at most its limit,
  // rounded down to a power of two as the field must be (grid scale 3 takes 2x;
  // docs/ground-truth.md, "Cast shadows").
  out.lighting.shadow_resolution = int(std::bit_floor(std::uint64_t(
      std::min<std::int64_t>(std::int64_t(scene.lighting.shadow_resolution) * settings.grid_scale,
                             limits::kMaxShadowResolution))));
  return out;
}

int ground_truth_band_rows(const Scene& scene, const GroundTruthSettings& settings) {
  if (settings.band_rows > 0) {
    return settings.band_rows;
  }
  const int granule = band_granule(settings.supersample);
  const std::uintmax_t row_bytes =
      std::uintmax_t(scene.viewport.width) * settings.supersample * (3 + 12);
  const std::uintmax_t rows = kGroundTruthBandBytes / row_bytes;  // row_bytes >= 15
  const int height = scene.viewport.height * settings.supersample;
  // At most the whole frame, rounded up to a granule; at least one granule.
  const int whole = (height + granule - 1) / granule * granule;
  return std::clamp(int(std::min<std::uintmax_t>(rows, whole)) / granule * granule, granule, whole);
}

GroundTruthLod ground_truth_lod(const Scene& scene, const SceneResources& resources,
                                double octave_epsilon) {
  const TerrainSettings& t = scene.terrain;
  // The smallest angle a pixel subtends: on the image plane at distance 1 a pixel is
  // p = 2 tan(fov_y / 2) / height wide; at image point (u, v) it subtends p / (1 + u^2 + v^2)
  // along the radial direction, least at the corner (u, v) = (tan(fov_x / 2), tan(fov_y / 2)).
  const double tan_y = std::tan(scene.camera.fov_y_deg * std::numbers::pi / 360.0);
  const double tan_x = tan_y * scene.viewport.width / scene.viewport.height;
  const double pixel = 2.0 * tan_y / scene.viewport.height;
  const double pixel_min = pixel / (1.0 + tan_x * tan_x + tan_y * tan_y);  // > 0
  // A lower bound of a vertex's distance besides its horizontal one: the camera's height above
  // (or depth below) the slab of every possible terrain height.
  const HeightBounds bounds =
      make_frame_plan(scene, resources.terrain_values(), resources.sketch_or_null()).bounds;
  const double camera_y = scene.camera.position[1];
  const double gap = std::max({0.0, camera_y - bounds.world_max, bounds.world_min - camera_y});
  // amplitude r^(-kappa H) = epsilon pixel_min d:
  //   kappa = (log2 amplitude - log2(epsilon pixel_min) - log2(d^2) / 2) / (H log2 r),
  // and kappa = k0 is one whole octave (frame_plan.cc, make_lod_plan). Logs of positive
  // values: amplitude >= 1e-25, epsilon >= 1e-6, pixel_min > 0, H log2 r >= 2^-10.
  const double h_log2_r = t.H * std::log2(t.r);
  GroundTruthLod out;
  out.lod.c1 = 0.5 / h_log2_r;
  out.lod.c0 = (std::log2(t.amplitude) - std::log2(octave_epsilon * pixel_min)) / h_log2_r -
               t.first_octave + 1.0;
  out.lod.nu_max = t.last_octave - t.first_octave + 1;
  out.lod.gap_sq = gap * gap;
  // c0 - c1 log2(d^2) = nu_max  <=>  d = 2^((c0 - nu_max) / (2 c1)).
  out.cap_distance = std::exp2((out.lod.c0 - out.lod.nu_max) / (2.0 * out.lod.c1));
  const HeightSketch* field = resources.sketch_or_null();
  if (field != nullptr && field->levels() > 1 && !fractal_enabled(t)) {
    // A height field without the fractal: the truth is its samples themselves, level 0
    // everywhere (nu = levels, height_sketch.h), whatever the distance.
    out.lod.c1 = 0.0;
    out.lod.c0 = out.lod.nu_max = field->levels();
    out.cap_distance = std::numeric_limits<double>::infinity();  // the cap holds everywhere
  }
  return out;
}

int ground_truth_shard_unit(int supersample) {
  return band_granule(supersample) / supersample;  // supersample >= 1, and divides the lcm
}

MemoryEstimate ground_truth_memory(const Scene& scene, const GroundTruthSettings& settings,
                                   FrameRows output_rows) {
  const Scene big = supersampled_scene(scene, settings);
  const int height = scene.viewport.height;
  const int rows = std::min(output_rows.end, height) - std::clamp(output_rows.begin, 0, height);
  MemoryEstimate estimate = estimate_ground_truth_memory(
      big, ground_truth_band_rows(scene, settings), scene.viewport.width, std::max(rows, 0));
  if (settings.distances) {  // a float of depth per sample of a band, and per output pixel
    const std::uintmax_t band_samples =
        std::uintmax_t(big.viewport.width) *
        std::uintmax_t(std::min(ground_truth_band_rows(scene, settings), big.viewport.height));
    estimate.add("depths of a band and the distances",
                 4 * band_samples +
                     4 * std::uintmax_t(scene.viewport.width) * std::uintmax_t(std::max(rows, 0)));
  }
  return estimate;
}

GroundTruthImage render_ground_truth(const Scene& scene, const SceneResources& resources,
                                     const GroundTruthSettings& settings,
                                     std::uint64_t max_bin_bytes, const BandProgress& progress,
                                     FrameRows output_rows) {
  const int n = settings.supersample;
  const Scene big = supersampled_scene(scene, settings);
  const int height = scene.viewport.height;
  const int unit = ground_truth_shard_unit(n);
  if (!whole_steps(output_rows, height, unit)) {
    throw std::invalid_argument(
        "render_ground_truth: output rows [" + std::to_string(output_rows.begin) + ", " +
        std::to_string(output_rows.end) + ") are not whole steps of " + std::to_string(unit) +
        " rows of the " + std::to_string(height) + " rows");
  }
  GroundTruthImage out;
  out.width = scene.viewport.width;
  out.first_row = output_rows.begin;
  out.height = std::min(output_rows.end, height) - output_rows.begin;
  out.lod = ground_truth_lod(scene, resources, settings.octave_epsilon);
  const std::size_t pixels = std::size_t(out.width) * out.height;
  out.linear.assign(3 * pixels, 0.0f);
  out.srgb.assign(3 * pixels, 0);
  if (settings.distances) {
    out.distance.assign(pixels, 0.0f);
  }

  FrameRequest request;
  request.backend = Backend::kReferenceDouble;
  request.outputs.linear = true;
  request.outputs.depth = settings.distances;
  request.octave_count_rule = distance_lod_rule(out.lod.lod);
  // The cloud layer's density integrated along each path rather than read at its middle
  // (core/clouds.h; docs/ground-truth.md, "Clouds").
  request.cloud_steps = kGroundTruthCloudSteps;
  request.max_bin_bytes = max_bin_bytes;
  const int band_rows = ground_truth_band_rows(scene, settings);
  // Supersampled rows [first, end): whole granules (a multiple of the tile size and of N).
  const FrameRows rows{out.first_row * n, (out.first_row + out.height) * n};
  out.bands = (rows.end - rows.begin + band_rows - 1) / band_rows;
  int done = 0;
  // The mean view-axis distance of pixel (x, y)'s samples that see terrain: near / depth for
  // depth > 0 (reverse-Z, vertex_transform.h; the division's domain), or 0 where fewer than
  // half of them do.
  const double near = scene.camera.near;
  const auto mean_distance = [&](const FrameImage& band, int first_row, int x, int y) {
    double sum = 0;
    int terrain = 0;
    for (int sy = 0; sy < n; ++sy) {
      const std::size_t row = std::size_t(y * n + sy - first_row) * band.width;
      for (int sx = 0; sx < n; ++sx) {
        const float depth = band.depth[row + std::size_t(x * n + sx)];
        if (depth > 0.0f) {
          sum += near / double(depth);
          ++terrain;
        }
      }
    }
    return 2 * terrain >= n * n ? static_cast<float>(sum / terrain) : 0.0f;
  };
  // Each output pixel's N x N samples lie in one band (bands are whole multiples of N): the
  // box filter sums them in double in a fixed order, row by row, and divides by N^2.
  const auto reduce = [&](const FrameImage& band, int first_row) {
    const double inv_samples = 1.0 / (double(n) * n);
    for (int y = first_row / n; y < (first_row + band.height) / n; ++y) {
      for (int x = 0; x < out.width; ++x) {
        double sum[3] = {0, 0, 0};
        for (int sy = 0; sy < n; ++sy) {
          const std::size_t row = std::size_t(y * n + sy - first_row) * band.width;
          for (int sx = 0; sx < n; ++sx) {
            const float* sample = &band.linear[3 * (row + std::size_t(x * n + sx))];
            for (int c = 0; c < 3; ++c) {
              sum[c] += double(sample[c]);
            }
          }
        }
        const std::size_t k = 3 * (std::size_t(y - out.first_row) * out.width + x);
        for (int c = 0; c < 3; ++c) {
          out.linear[k + c] = static_cast<float>(sum[c] * inv_samples);
          out.srgb[k + c] = srgb_byte(out.linear[k + c]);
        }
        if (settings.distances) {
          out.distance[k / 3] = mean_distance(band, first_row, x, y);
        }
      }
    }
    ++done;
    if (progress) {
      progress(done, out.bands);
    }
  };
  out.stats = render_frame_bands(big, resources, request, band_rows, reduce, rows);
  return out;
}

}  // namespace relief
