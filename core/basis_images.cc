#include "core/basis_images.h"

#include <algorithm>
#include <cmath>

#include "core/height_sketch.h"
#include "core/periodic_gaussian.h"
#include "core/scene/scene_json.h"

namespace relief {

namespace {

std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

}  // namespace

GreyGrid mirror_grid(const GreyGrid& image) {
  const int w = image.side;
  GreyGrid out;
  out.side = 2 * w;
  out.values.resize(std::size_t(out.side) * std::size_t(out.side));
  for (int y = 0; y < out.side; ++y) {
    const int sy = y < w ? y : 2 * w - 1 - y;
    for (int x = 0; x < out.side; ++x) {
      const int sx = x < w ? x : 2 * w - 1 - x;
      out.values[std::size_t(y) * std::size_t(out.side) + x] = image.at(sx, sy);
    }
  }
  return out;
}

double seam_measure(const GreyGrid& image) {
  const int w = image.side;
  double wrap = 0.0, inside = 0.0;
  for (int a = 0; a < w; ++a) {
    const double dx = image.at(0, a) - image.at(w - 1, a);
    const double dy = image.at(a, 0) - image.at(a, w - 1);
    wrap += dx * dx + dy * dy;
    for (int b = 0; b + 1 < w; ++b) {
      const double ix = image.at(b + 1, a) - image.at(b, a);
      const double iy = image.at(a, b + 1) - image.at(a, b);
      inside += ix * ix + iy * iy;
    }
  }
  const double wrap_rms = std::sqrt(wrap / (2.0 * w));
  const double inside_rms = std::sqrt(inside / (2.0 * w * (w - 1.0)));
  // A constant image has no step anywhere: it tiles.
  return inside_rms > 0.0 ? wrap_rms / inside_rms : 0.0;
}

void filter_basis_image(GreyGrid& image, const BasisImageSettings& settings,
                        const std::string& field) {
  if (settings.low_pass > 0.0) {
    periodic_gaussian_blur(image.values, image.side, settings.low_pass);
  }
  if (settings.high_pass > 0.0) {
    std::vector<double> blurred = image.values;
    periodic_gaussian_blur(blurred, image.side, settings.high_pass);
    for (std::size_t k = 0; k < blurred.size(); ++k) {
      image.values[k] -= blurred[k];
    }
  }
  if (settings.normalize) {
    // Two passes in a fixed order: the mean, then the mean squared deviation.
    const double count = double(image.values.size());
    double sum = 0.0;
    for (double v : image.values) {
      sum += v;
    }
    const double mean = sum / count;
    double squares = 0.0;
    for (double v : image.values) {
      squares += (v - mean) * (v - mean);
    }
    const double deviation = std::sqrt(squares / count);
    if (!(deviation > kMinBasisDeviation)) {
      throw SceneError(field, "scene: " + field +
                                  " cannot be normalized: its variance is 0 (standard deviation " +
                                  number_text(deviation) +
                                  " <= " + number_text(kMinBasisDeviation) +
                                  " after its filters: a constant image); allowed: an image "
                                  "whose values vary, or normalize = false");
    }
    for (double& v : image.values) {
      v = (v - mean) / deviation;
    }
  }
}

GreyGrid bspline_refine(const GreyGrid& grid, int factor) {
  const int side = grid.side;
  const int fine = side * factor;
  // Per fine position X: the first coarse tap floor(X / factor) - 1 and the four weights.
  std::vector<int> first(std::size_t(fine) * 1);
  std::vector<double> weights(std::size_t(fine) * 4);
  for (int x = 0; x < fine; ++x) {
    const int cell = x / factor;
    first[std::size_t(x)] = cell - 1;
    bspline_weights<double>(double(x - cell * factor) / double(factor),
                            &weights[4 * std::size_t(x)]);
  }
  const auto wrap = [side](int i) { return ((i % side) + side) % side; };
  // Along x: side rows of fine values; then along y.
  std::vector<double> rows(std::size_t(side) * std::size_t(fine));
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < fine; ++x) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) {
        sum += weights[4 * std::size_t(x) + k] * grid.at(wrap(first[std::size_t(x)] + k), y);
      }
      rows[std::size_t(y) * std::size_t(fine) + x] = sum;
    }
  }
  GreyGrid out;
  out.side = fine;
  out.values.resize(std::size_t(fine) * std::size_t(fine));
  for (int y = 0; y < fine; ++y) {
    for (int x = 0; x < fine; ++x) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) {
        sum += weights[4 * std::size_t(y) + k] *
               rows[std::size_t(wrap(first[std::size_t(y)] + k)) * std::size_t(fine) + x];
      }
      out.values[std::size_t(y) * std::size_t(fine) + x] = sum;
    }
  }
  return out;
}

NoiseLattice compose_basis(std::span<const BasisTerm> terms, int source_side, int upsample) {
  const int side = terms.front().image->side;
  GreyGrid composed;
  composed.side = side;
  composed.values.resize(std::size_t(side) * std::size_t(side));
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const std::size_t t = std::size_t(y) * std::size_t(side) + x;
      double weighted = 0.0, weights = 0.0;
      for (const BasisTerm& term : terms) {
        const double w = term.weight_image ? term.weight_image->values[t] : term.weight;
        weighted += w * term.image->values[t];
        weights += w;
      }
      if (!(weights > 0.0)) {
        const int sx = x < source_side ? x : 2 * source_side - 1 - x;
        const int sy = y < source_side ? y : 2 * source_side - 1 - y;
        throw SceneError("terrain.basis.images",
                         "scene: terrain.basis.images: the weights sum to 0 at texel (" +
                             std::to_string(sx) + ", " + std::to_string(sy) +
                             "), where Eq. 2's convex combination is undefined; allowed: "
                             "weights (constants or weight images) whose sum is > 0 at every "
                             "texel");
      }
      composed.values[t] = weighted / weights;
    }
  }
  if (upsample > 1) {
    composed = bspline_refine(composed, upsample);
  }
  NoiseLattice grid;
  grid.seed = 0;
  grid.size = composed.side;
  grid.mask = composed.side - 1;
  grid.values.resize(composed.values.size());
  std::transform(composed.values.begin(), composed.values.end(), grid.values.begin(),
                 [](double v) { return static_cast<float>(v); });
  const auto [lo, hi] = std::minmax_element(grid.values.begin(), grid.values.end());
  grid.min_value = *lo;
  grid.max_value = *hi;
  return grid;
}

TerrainSettings stage3_terrain(const TerrainSettings& terrain, int grid_side) {
  TerrainSettings t = terrain;
  if (terrain.basis) {
    t.lattice_size = grid_side;
    t.horizontal_scale = terrain.basis->tile_size / double(grid_side);
  }
  return t;
}

}  // namespace relief
