#include "eval/image_error.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/srgb.h"

namespace relief {

double display_value(float linear) {
  return srgb_encode(linear > 0.0f ? std::min(double(linear), 1.0) : 0.0);  // NaN -> 0
}

ImageError image_error(std::span<const float> test, std::span<const float> reference, int width,
                       int height, double pixels_per_degree) {
  ImageError out;
  double sum_sq = 0;
  for (std::size_t k = 0; k < test.size(); ++k) {
    const double d = std::abs(display_value(test[k]) - display_value(reference[k]));
    sum_sq += d * d;
    if (d > out.max_error) {
      out.max_error = d;
      out.max_pixel = k / 3;
      out.max_channel = int(k % 3);
    }
  }
  out.rmse = std::sqrt(sum_sq / double(test.size()));  // size >= 3
  // log10's domain: rmse > 0; equal images have no finite PSNR.
  out.psnr_db =
      out.rmse > 0 ? 20.0 * std::log10(1.0 / out.rmse) : std::numeric_limits<double>::infinity();
  out.flip_map = flip_error_map(test, reference, width, height, pixels_per_degree);
  double flip_sum = 0;
  for (const float v : out.flip_map) {
    flip_sum += v;
  }
  out.mean_flip = flip_sum / double(out.flip_map.size());
  return out;
}

std::size_t image_error_bytes(int width, int height) {
  // Per pixel at FLIP's peak: both images' YCxCz (2 x 3 doubles), one image's filtered planes
  // with the pass buffer and its Lab (3 + 2 + 3 doubles), the other's Lab (3), the feature
  // planes of both (2 x 2) and the filter's scratch (3), and the map (a float).
  return std::size_t(width) * std::size_t(height) * ((6 + 8 + 3 + 4 + 3) * 8 + 4);
}

}  // namespace relief
