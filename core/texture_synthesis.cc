#include "core/texture_synthesis.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/counter_hash.h"
#include "core/interpolant.h"
#include "core/lattice.h"
#include "core/tiling_noise.h"

namespace relief {

namespace {

struct Color {
  double r, g, b;
};

Color mix(const Color& a, const Color& b, double t) {
  return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)};
}

Color scale(const Color& c, double k) {
  return {c.r * k, c.g * k, c.b * k};
}

double smooth01(double lo, double hi, double x) {
  const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

std::uint64_t name_seed(std::string_view name) {
  return fnv1a64(reinterpret_cast<const unsigned char*>(name.data()), name.size());
}

// The material's albedo at texel (i, j) from its noises.
struct Material {
  Color low, high, accent;
  int first_cells;       // coarsest pattern: cells across the texture
  double detail;         // amplitude of the fine grain
  double accent_amount;  // how much of the accent colour the patches get
  bool ridged;           // cracks (rock, basalt)
};

Material material_for(std::string_view name) {
  if (name == "sand")
    return {{0.50, 0.41, 0.28}, {0.68, 0.58, 0.41}, {0.58, 0.52, 0.42}, 4, 0.10, 0.3, false};
  if (name == "grass")
    return {{0.045, 0.09, 0.025}, {0.12, 0.19, 0.05}, {0.21, 0.20, 0.08}, 4, 0.18, 0.5, false};
  if (name == "rock")
    return {{0.085, 0.08, 0.075}, {0.25, 0.23, 0.20}, {0.21, 0.16, 0.11}, 4, 0.16, 0.35, true};
  if (name == "snow")
    return {{0.78, 0.81, 0.87}, {0.93, 0.95, 0.98}, {0.85, 0.88, 0.95}, 2, 0.03, 0.2, false};
  if (name == "bed")
    return {{0.14, 0.13, 0.08}, {0.27, 0.24, 0.15}, {0.20, 0.22, 0.12}, 4, 0.12, 0.4, false};
  if (name == "basalt")
    return {{0.035, 0.032, 0.032}, {0.15, 0.12, 0.11}, {0.30, 0.09, 0.04}, 4, 0.14, 0.25, true};
  return {
      {0.58, 0.36, 0.18}, {0.76, 0.53, 0.29}, {0.70, 0.45, 0.24}, 2, 0.06, 0.25, false};  // dune
}

}  // namespace

RgbImage synthesize_texture(std::string_view name, int size) {
  const Material m = material_for(name);
  const std::uint64_t seed = name_seed(name);
  const TilingNoise shape(seed, size, m.first_cells, 4, 0.55);
  const TilingNoise patches(seed + 1, size, m.first_cells * 2, 3, 0.6);
  const TilingNoise grain(seed + 2, size, std::min(size / 4, 64), 2, 0.5);
  RgbImage image;
  image.size = size;
  image.rgb.resize(3 * std::size_t(size) * size);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      Color c = mix(m.low, m.high, smooth01(-1.6, 1.6, shape(i, j)));
      c = mix(c, m.accent, m.accent_amount * smooth01(0.3, 1.4, patches(i, j)));
      if (m.ridged) {
        // Cracks along the zero lines of a second noise: 1 - |n| peaks there.
        const double ridge = 1.0 - std::min(1.0, std::abs(patches(j, i)) * 4.0);
        c = scale(c, 1.0 - 0.55 * ridge * ridge);
      }
      c = scale(c, std::max(0.0, 1.0 + m.detail * grain(i, j)));
      float* out = &image.rgb[3 * (std::size_t(j) * size + i)];
      out[0] = static_cast<float>(c.r);
      out[1] = static_cast<float>(c.g);
      out[2] = static_cast<float>(c.b);
    }
  }
  return image;
}

}  // namespace relief
