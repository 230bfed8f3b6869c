#include "eval/convergence.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/srgb.h"
#include "eval/image_error.h"

namespace relief {

GroundTruthSettings doubled_settings(const GroundTruthSettings& settings) {
  GroundTruthSettings out = settings;
  out.supersample = 2 * settings.supersample;
  out.grid_scale = 2 * settings.grid_scale;
  out.octave_epsilon = 0.5 * settings.octave_epsilon;
  out.band_rows = 0;
  out.distances = false;
  return out;
}

void validate_convergence(const Scene& scene, const GroundTruthSettings& s) {
  validate_ground_truth(scene, s);
  const auto refuse = [](const std::string& option, const std::string& value,
                         const std::string& allowed) {
    throw GroundTruthError(option + " " + value + " leaves no room for --converge, which renders " +
                           "at twice it; allowed " + allowed + " with --converge");
  };
  // side, grid >= 1: the scene's validation bounds the viewport and grid below.
  const int side = std::max(scene.viewport.width, scene.viewport.height);
  const int max_supersample = std::min(kMaxSupersample, limits::kMaxViewportSide / side);
  if (max_supersample < 2) {
    throw GroundTruthError("--converge renders at twice --supersample, and this " +
                           std::to_string(scene.viewport.width) + "x" +
                           std::to_string(scene.viewport.height) +
                           " viewport leaves no room: its side times 2 exceeds " +
                           std::to_string(limits::kMaxViewportSide) +
                           "; lower viewport.width and viewport.height to " +
                           std::to_string(limits::kMaxViewportSide / 2) + " or less");
  }
  if (2 * s.supersample > max_supersample) {
    refuse("--supersample", std::to_string(s.supersample),
           "1..." + std::to_string(max_supersample / 2) + " for this " +
               std::to_string(scene.viewport.width) + "x" + std::to_string(scene.viewport.height) +
               " viewport");
  }
  const int grid = std::max(scene.grid.width, scene.grid.height);
  const int max_scale = std::min(kMaxGridScale, limits::kMaxGridSide / grid);
  if (max_scale < 2) {
    throw GroundTruthError(
        "--converge renders at twice --grid-scale, and this " + std::to_string(scene.grid.width) +
        "x" + std::to_string(scene.grid.height) +
        " grid leaves no room: its side times 2 exceeds " + std::to_string(limits::kMaxGridSide) +
        "; lower grid.width and grid.height to " + std::to_string(limits::kMaxGridSide / 2) +
        " or less");
  }
  if (2 * s.grid_scale > max_scale) {
    refuse("--grid-scale", std::to_string(s.grid_scale),
           "1..." + std::to_string(max_scale / 2) + " for this " +
               std::to_string(scene.grid.width) + "x" + std::to_string(scene.grid.height) +
               " grid");
  }
  if (0.5 * s.octave_epsilon < kMinOctaveEpsilon) {
    refuse("--octave-epsilon", format_number(s.octave_epsilon),
           format_number(2 * kMinOctaveEpsilon) + "..." + format_number(kMaxOctaveEpsilon));
  }
  validate_ground_truth(scene, doubled_settings(s));  // what is left: none, by the above
}

std::vector<int> distance_bands(const GroundTruthImage& image) {
  const std::size_t pixels = image.distance.size();
  std::vector<int> band(pixels, 0);
  std::vector<std::size_t> terrain;
  for (std::size_t k = 0; k < pixels; ++k) {
    if (image.distance[k] > 0.0f) {
      terrain.push_back(k);
    }
  }
  // Nearest first; equal distances in index order (a total order: the same bands every run).
  std::sort(terrain.begin(), terrain.end(), [&](std::size_t a, std::size_t b) {
    return image.distance[a] < image.distance[b] ||
           (image.distance[a] == image.distance[b] && a < b);
  });
  const std::size_t third = terrain.size() / 3;
  const std::size_t near_count = terrain.size() - 2 * third;
  for (std::size_t r = 0; r < terrain.size(); ++r) {
    band[terrain[r]] = r < near_count ? 1 : (r < near_count + third ? 2 : 3);
  }
  return band;
}

BandedError banded_error(std::span<const float> test, std::span<const float> reference,
                         const GroundTruthImage& banded_by, double pixels_per_degree) {
  const ImageError error =
      image_error(test, reference, banded_by.width, banded_by.height, pixels_per_degree);
  const std::vector<int> bands = distance_bands(banded_by);
  std::vector<double> flip_sum(kDistanceBands, 0.0), squares(kDistanceBands, 0.0);
  std::vector<std::size_t> count(kDistanceBands, 0);
  std::vector<double> farthest(kDistanceBands, 0.0);
  double all_flip = 0, all_squares = 0;
  for (std::size_t k = 0; k < bands.size(); ++k) {
    const int b = bands[k];
    double sq = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = display_value(test[3 * k + c]) - display_value(reference[3 * k + c]);
      sq += d * d;
    }
    flip_sum[b] += error.flip_map[k];
    squares[b] += sq;
    ++count[b];
    farthest[b] = std::max(farthest[b], double(banded_by.distance[k]));
    all_flip += error.flip_map[k];
    all_squares += sq;
  }
  // PSNR = 20 log10(1 / RMSE), peak 1; log's domain: RMSE > 0, else +infinity.
  const auto psnr = [](double sum_sq, std::size_t pixels) {
    const double rmse = pixels > 0 ? std::sqrt(sum_sq / (3.0 * double(pixels))) : 0.0;
    return rmse > 0 ? -20.0 * std::log10(rmse) : INFINITY;
  };
  BandedError out;
  const std::size_t pixels = bands.size();
  out.all = {"all", pixels, pixels > 0 ? all_flip / double(pixels) : 0.0, psnr(all_squares, pixels),
             *std::max_element(farthest.begin(), farthest.end())};
  for (int b = 0; b < kDistanceBands; ++b) {
    out.bands.push_back({kDistanceBandNames[b], count[b],
                         count[b] > 0 ? flip_sum[b] / double(count[b]) : 0.0,
                         psnr(squares[b], count[b]), farthest[b]});
  }
  return out;
}

std::vector<double> banded_change(std::span<const float> before, std::span<const float> after,
                                  const GroundTruthImage& banded_by) {
  const std::vector<int> bands = distance_bands(banded_by);
  std::vector<double> sum(kDistanceBands + 1, 0.0);
  std::vector<std::size_t> count(kDistanceBands + 1, 0);
  for (std::size_t k = 0; k < bands.size(); ++k) {
    double change = 0;
    for (int c = 0; c < 3; ++c) {
      change += std::abs(display_value(after[3 * k + c]) - display_value(before[3 * k + c]));
    }
    change *= 255.0 / 3.0;  // sRGB codes, the mean of the three channels
    sum[std::size_t(bands[k])] += change;
    ++count[std::size_t(bands[k])];
    sum[kDistanceBands] += change;
    ++count[kDistanceBands];
  }
  std::vector<double> out(kDistanceBands + 1, 0.0);
  for (std::size_t b = 0; b < out.size(); ++b) {
    out[b] = count[b] > 0 ? sum[b] / double(count[b]) : 0.0;  // the division's domain
  }
  return out;
}

ConvergenceReport compare_truths(const GroundTruthImage& base, const GroundTruthImage& doubled,
                                 const GroundTruthSettings& settings, double pixels_per_degree) {
  ConvergenceReport report;
  report.settings = settings;
  report.doubled = doubled_settings(settings);
  BandedError error = banded_error(base.linear, doubled.linear, base, pixels_per_degree);
  report.all = std::move(error.all);
  report.bands = std::move(error.bands);
  return report;
}

}  // namespace relief
