#include "core/heightfield/subdivision.h"

#include "core/counter_hash.h"
#include "core/det_math.h"

namespace relief {

namespace {

// sqrt(3): four uniforms on (0, 1) sum to variance 4/12 = 1/3.
constexpr double kSqrt3 = 1.7320508075688772;

// The deviation at spacing 2^e of the coarse spacing: amplitude 2^(e H) (exp2_det: the same
// bits everywhere; e H lies far inside its domain for e >= -16 and H <= 2).
double deviation(const SubdivisionSettings& s, double e, int level) {
  return level > s.random_levels ? 0.0 : s.amplitude * exp2_det(e * s.roughness);
}

struct Displacement {
  const SubdivisionSettings& s;
  int level;
  double sigma;
  float operator()(double mean, std::uint64_t index) const {
    return static_cast<float>(mean + sigma * subdivision_gaussian(s.seed, s.method, level, index));
  }
};

// Triangle-edge and diamond-square refine in place: the control points sit at multiples of
// 2^levels, and level l fills the points at odd multiples of half = 2^(levels - l).
void triangle_edge_level(PeriodicGrid& g, int step, const Displacement& d) {
  const int half = step / 2;
  for (int z = 0; z < g.side; z += step) {
    for (int x = 0; x < g.side; x += step) {
      const double here = g.at(x, z);
      // The cell's lower edge, left edge and diagonal (x, z) - (x + step, z + step): each
      // midpoint from its edge's two ends alone.
      g.at(x + half, z) = d(0.5 * (here + g.at(x + step, z)), g.index(x + half, z));
      g.at(x, z + half) = d(0.5 * (here + g.at(x, z + step)), g.index(x, z + half));
      g.at(x + half, z + half) =
          d(0.5 * (here + g.at(x + step, z + step)), g.index(x + half, z + half));
    }
  }
}

void diamond_square_level(PeriodicGrid& g, int step, const Displacement& square,
                          const Displacement& diamond) {
  const int half = step / 2;
  for (int z = 0; z < g.side; z += step) {  // squares: centre from the four corners
    for (int x = 0; x < g.side; x += step) {
      const double sum = (double(g.at(x, z)) + g.at(x + step, z)) +
                         (double(g.at(x, z + step)) + g.at(x + step, z + step));
      g.at(x + half, z + half) = square(0.25 * sum, g.index(x + half, z + half));
    }
  }
  for (int z = 0; z < g.side; z += half) {  // diamonds: edge midpoints from the four tips
    for (int x = (z / half) % 2 == 0 ? half : 0; x < g.side; x += step) {
      const double sum = (double(g.at(x - half, z)) + g.at(x + half, z)) +
                         (double(g.at(x, z - half)) + g.at(x, z + half));
      g.at(x, z) = diamond(0.25 * sum, g.index(x, z));
    }
  }
}

// Square-square: value (i, j) spawns (2i + a, 2j + b), a, b in {0, 1}, towards (dx, dz) =
// (2a - 1, 2b - 1): (9 v(i, j) + 3 v(i + dx, j) + 3 v(i, j + dz) + v(i + dx, j + dz)) / 16.
PeriodicGrid square_square_level(const PeriodicGrid& g, const Displacement& d) {
  PeriodicGrid out(2 * g.side);
  for (int j = 0; j < g.side; ++j) {
    for (int i = 0; i < g.side; ++i) {
      const double here = g.at(i, j);
      for (int b = 0; b < 2; ++b) {
        for (int a = 0; a < 2; ++a) {
          const int dx = 2 * a - 1, dz = 2 * b - 1;
          const double mix = (9.0 * here + 3.0 * g.at(i + dx, j)) +
                             (3.0 * g.at(i, j + dz) + double(g.at(i + dx, j + dz)));
          const std::size_t at = out.index(2 * i + a, 2 * j + b);
          out.heights[at] = d(mix * (1.0 / 16.0), at);
        }
      }
    }
  }
  return out;
}

}  // namespace

std::string_view subdivision_name(Subdivision method) {
  switch (method) {
    case Subdivision::kTriangleEdge:
      return "triangle-edge";
    case Subdivision::kDiamondSquare:
      return "diamond-square";
    case Subdivision::kSquareSquare:
      return "square-square";
  }
  return "";
}

double subdivision_gaussian(std::uint64_t seed, Subdivision method, int level,
                            std::uint64_t index) {
  const std::uint64_t bits = counter_hash(
      seed, HashStream::kHeightField, (std::uint64_t(method) << 8) | std::uint64_t(level), index);
  double sum = 0;
  for (int k = 0; k < 4; ++k) {  // four 16-bit uniforms on (0, 1), exact in double
    sum += (double((bits >> (16 * k)) & 0xFFFF) + 0.5) * (1.0 / 65536.0);
  }
  return (sum - 2.0) * kSqrt3;
}

PeriodicGrid subdivide(const PeriodicGrid& coarse, const SubdivisionSettings& s,
                       const std::function<void(int, int)>& progress) {
  if (s.method == Subdivision::kSquareSquare) {
    PeriodicGrid g = coarse;
    for (int level = 1; level <= s.levels; ++level) {
      g = square_square_level(g, {s, level, deviation(s, -level, level)});
      if (progress) {
        progress(level, s.levels);
      }
    }
    return g;
  }
  const int scale = 1 << s.levels;
  PeriodicGrid g(coarse.side * scale);
  for (int z = 0; z < coarse.side; ++z) {
    for (int x = 0; x < coarse.side; ++x) {
      g.at(x * scale, z * scale) = coarse.at(x, z);
    }
  }
  for (int level = 1; level <= s.levels; ++level) {
    const int step = scale >> (level - 1);
    if (s.method == Subdivision::kTriangleEdge) {
      triangle_edge_level(g, step, {s, level, deviation(s, -level, level)});
    } else {
      // The square's centre lies 1/sqrt(2) of the step from its parents, the diamond's 1/2.
      diamond_square_level(g, step, {s, level, deviation(s, -(level - 1) - 0.5, level)},
                           {s, level, deviation(s, -level, level)});
    }
    if (progress) {
      progress(level, s.levels);
    }
  }
  return g;
}

}  // namespace relief
