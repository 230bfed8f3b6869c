#include "eval/box_filter.h"

#include <cstddef>

namespace relief {

std::vector<float> box_filter_rgb(std::span<const float> samples, int sample_width,
                                  int sample_height, int n) {
  const int width = sample_width / n, height = sample_height / n;
  std::vector<float> out(3 * std::size_t(width) * std::size_t(height));
  const double inv_samples = 1.0 / (double(n) * n);  // n >= 1
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double sum[3] = {0, 0, 0};
      for (int sy = 0; sy < n; ++sy) {
        const std::size_t row = std::size_t(y * n + sy) * std::size_t(sample_width);
        for (int sx = 0; sx < n; ++sx) {
          const float* sample = &samples[3 * (row + std::size_t(x * n + sx))];
          for (int c = 0; c < 3; ++c) {
            sum[c] += double(sample[c]);
          }
        }
      }
      const std::size_t k = 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
      for (int c = 0; c < 3; ++c) {
        out[k + c] = static_cast<float>(sum[c] * inv_samples);
      }
    }
  }
  return out;
}

}  // namespace relief
