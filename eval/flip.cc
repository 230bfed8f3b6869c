#include "eval/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace relief {

namespace {

using Vec = std::array<double, 3>;
using Plane = std::vector<double>;

constexpr double kPi = std::numbers::pi;

// FLIP's colour constants (§3.1-3.2) and feature constants (§3.3).
constexpr double kQc = 0.7;                 // exponent of the HyAB distance
constexpr double kQf = 0.5;                 // exponent of the feature difference
constexpr double kPc = 0.4;                 // share of cmax mapped to [0, pt]
constexpr double kPt = 0.95;                //
constexpr double kFeatureWidthDeg = 0.082;  // w: peak-to-trough width of an edge, degrees

// linear sRGB (D65) to XYZ and back, the matrices of FLIP's reference implementation.
constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};
constexpr double kXyzToRgb[3][3] = {{3.241003275, -1.537398934, -0.498615861},
                                    {-0.969224334, 1.875930071, 0.041554224},
                                    {0.055639423, -0.204011202, 1.057148933}};

Vec multiply(const double (&m)[3][3], const Vec& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
          m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// The white point: XYZ of linear RGB (1, 1, 1); each component > 0.
const Vec& white() {
  static const Vec w = multiply(kRgbToXyz, Vec{1.0, 1.0, 1.0});
  return w;
}

Vec rgb_to_ycxcz(const Vec& rgb) {
  const Vec xyz = multiply(kRgbToXyz, rgb);
  const Vec& w = white();
  const double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec ycxcz_to_rgb(const Vec& ycxcz) {
  const double y = (ycxcz[0] + 16.0) / 116.0;
  const double x = y + ycxcz[1] / 500.0;
  const double z = y - ycxcz[2] / 200.0;
  const Vec& w = white();
  return multiply(kXyzToRgb, Vec{x * w[0], y * w[1], z * w[2]});
}

// CIELAB's companding, the cube root's domain t >= 0 (above the limit only).
double lab_f(double t) {
  constexpr double kDelta = 6.0 / 29.0;
  return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3.0 * kDelta * kDelta) + 4.0 / 29.0;
}

// Linear RGB to L*a*b*, then the Hunt adjustment: chroma scaled by 0.01 L (§3.1).
Vec hunt_lab(const Vec& rgb) {
  const Vec xyz = multiply(kRgbToXyz, rgb);
  const Vec& w = white();
  const double fx = lab_f(xyz[0] / w[0]), fy = lab_f(xyz[1] / w[1]), fz = lab_f(xyz[2] / w[2]);
  const double l = 116.0 * fy - 16.0;
  return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

double hyab(const Vec& a, const Vec& b) {
  const double da = a[1] - b[1], db = a[2] - b[2];
  return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);  // sqrt of a sum of squares
}

double clamp01(float v) {
  return v > 0.0f ? std::min(double(v), 1.0) : 0.0;
}  // NaN -> 0

// A separable filter term: coefficient * w(i) * w(j) over offsets -r..r.
struct Term {
  double coefficient = 0;
  std::vector<double> x, y;  // 1D weights along x and along y, 2r + 1 each
};

// Correlates `in` (width x height) with the sum of `terms`, borders clamped to the edge.
Plane filter(const Plane& in, int width, int height, const std::vector<Term>& terms) {
  Plane out(in.size(), 0.0), pass(in.size());
  for (const Term& term : terms) {
    const int r = int(term.x.size() / 2);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        double sum = 0;
        for (int i = -r; i <= r; ++i) {
          sum += term.x[i + r] * in[std::size_t(y) * width + std::clamp(x + i, 0, width - 1)];
        }
        pass[std::size_t(y) * width + x] = sum;
      }
    }
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        double sum = 0;
        for (int j = -r; j <= r; ++j) {
          sum += term.y[j + r] * pass[std::size_t(std::clamp(y + j, 0, height - 1)) * width + x];
        }
        out[std::size_t(y) * width + x] += term.coefficient * sum;
      }
    }
  }
  return out;
}

// The contrast sensitivity filter of one opponent channel (§3.1): a1 sqrt(pi / b1)
// exp(-pi^2 d^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 d^2 / b2), d in degrees, over the radius
// of the widest of all three channels' Gaussians, normalised to sum 1 (b > 0: no division by 0).
std::vector<Term> csf_filter(double a1, double b1, double a2, double b2, double ppd) {
  constexpr double kWidestB = 0.04;  // the largest b of the three channels (blue-yellow)
  const int r = int(std::ceil(3.0 * std::sqrt(kWidestB / (2.0 * kPi * kPi)) * ppd));
  std::vector<Term> terms;
  double total = 0;
  for (const auto [a, b] : {std::array<double, 2>{a1, b1}, std::array<double, 2>{a2, b2}}) {
    if (a == 0) {
      continue;
    }
    Term term;
    term.coefficient = a * std::sqrt(kPi / b);
    double sum = 0;
    for (int i = -r; i <= r; ++i) {
      const double d = i / ppd;
      term.x.push_back(std::exp(-kPi * kPi * d * d / b));
      sum += term.x.back();
    }
    term.y = term.x;
    total += term.coefficient * sum * sum;
    terms.push_back(std::move(term));
  }
  for (Term& term : terms) {
    term.coefficient /= total;  // total > 0: a1 > 0 in every channel
  }
  return terms;
}

// The edge (first derivative) or point (second derivative) detector along x and along y
// (§3.3): Gaussian sd = 0.5 w ppd, radius ceil(3 sd), positive weights normalised to sum 1
// and negative ones to -1. Returns the x-direction and the y-direction filters.
std::array<std::vector<Term>, 2> feature_filters(bool points, double ppd) {
  const double sd = 0.5 * kFeatureWidthDeg * ppd;  // > 0
  const int r = int(std::ceil(3.0 * sd));
  std::vector<double> g, f;
  double g_sum = 0, positive = 0, negative = 0;
  for (int i = -r; i <= r; ++i) {
    const double x = i;
    g.push_back(std::exp(-x * x / (2.0 * sd * sd)));
    f.push_back(points ? (x * x / (sd * sd) - 1.0) * g.back() : -x * g.back());
    g_sum += g.back();
    (f.back() > 0 ? positive : negative) += f.back();
  }
  // The 2D kernel f(x) g(y) has the signs of f: its positive weights sum to positive * g_sum.
  // Both sums are non-zero for r >= 1 (sd >= 0.041 at ppd >= 1).
  for (double& v : f) {
    v = v > 0 ? v / positive : v / -negative;
  }
  for (double& v : g) {
    v /= g_sum;
  }
  return {std::vector<Term>{Term{1.0, f, g}}, std::vector<Term>{Term{1.0, g, f}}};
}

// The colour pipeline's input for the HyAB distance: CSF-filtered, clamped, Hunt-adjusted Lab.
std::vector<Vec> filtered_lab(const std::array<Plane, 3>& ycxcz, int width, int height,
                              double ppd) {
  const std::array<std::vector<Term>, 3> csf = {csf_filter(1.0, 0.0047, 0.0, 1e-5, ppd),
                                                csf_filter(1.0, 0.0053, 0.0, 1e-5, ppd),
                                                csf_filter(34.1, 0.04, 13.5, 0.025, ppd)};
  std::array<Plane, 3> filtered;
  for (int c = 0; c < 3; ++c) {
    filtered[c] = filter(ycxcz[c], width, height, csf[c]);
  }
  std::vector<Vec> lab(ycxcz[0].size());
  for (std::size_t k = 0; k < lab.size(); ++k) {
    Vec rgb = ycxcz_to_rgb({filtered[0][k], filtered[1][k], filtered[2][k]});
    for (double& v : rgb) {
      v = std::clamp(v, 0.0, 1.0);
    }
    lab[k] = hunt_lab(rgb);
  }
  return lab;
}

// Magnitudes of the edge and point responses of Y / Y_white = (y + 16) / 116.
std::array<Plane, 2> features(const Plane& ycxcz_y, int width, int height, double ppd) {
  Plane y(ycxcz_y.size());
  for (std::size_t k = 0; k < y.size(); ++k) {
    y[k] = (ycxcz_y[k] + 16.0) / 116.0;
  }
  std::array<Plane, 2> out;
  for (int kind = 0; kind < 2; ++kind) {
    const auto [along_x, along_y] = feature_filters(kind == 1, ppd);
    const Plane fx = filter(y, width, height, along_x);
    const Plane fy = filter(y, width, height, along_y);
    out[kind].resize(y.size());
    for (std::size_t k = 0; k < y.size(); ++k) {
      out[kind][k] = std::sqrt(fx[k] * fx[k] + fy[k] * fy[k]);
    }
  }
  return out;
}

std::array<Plane, 3> to_ycxcz(std::span<const float> rgb, std::size_t pixels) {
  std::array<Plane, 3> out;
  for (Plane& p : out) {
    p.resize(pixels);
  }
  for (std::size_t k = 0; k < pixels; ++k) {
    const Vec v =
        rgb_to_ycxcz({clamp01(rgb[3 * k]), clamp01(rgb[3 * k + 1]), clamp01(rgb[3 * k + 2])});
    for (int c = 0; c < 3; ++c) {
      out[c][k] = v[c];
    }
  }
  return out;
}

}  // namespace

double pixels_per_degree(double distance_m, double width_m, int width_px) {
  return distance_m * (width_px / width_m) * kPi / 180.0;
}

std::vector<float> flip_error_map(std::span<const float> test, std::span<const float> reference,
                                  int width, int height, double ppd) {
  const std::size_t pixels = std::size_t(width) * height;
  const std::array<Plane, 3> test_ycxcz = to_ycxcz(test, pixels);
  const std::array<Plane, 3> reference_ycxcz = to_ycxcz(reference, pixels);

  const std::vector<Vec> test_lab = filtered_lab(test_ycxcz, width, height, ppd);
  const std::vector<Vec> reference_lab = filtered_lab(reference_ycxcz, width, height, ppd);
  // cmax: the largest colour difference, Hunt-adjusted green against blue, raised to qc.
  const double cmax =
      std::pow(hyab(hunt_lab({0.0, 1.0, 0.0}), hunt_lab({0.0, 0.0, 1.0})), kQc);  // > 0
  const double pccmax = kPc * cmax;

  const std::array<Plane, 2> test_features = features(test_ycxcz[0], width, height, ppd);
  const std::array<Plane, 2> reference_features = features(reference_ycxcz[0], width, height, ppd);

  std::vector<float> map(pixels);
  for (std::size_t k = 0; k < pixels; ++k) {
    const double power = std::pow(hyab(reference_lab[k], test_lab[k]), kQc);  // base >= 0
    // §3.2: [0, pc cmax) onto [0, pt), [pc cmax, cmax] onto [pt, 1]; cmax > pc cmax > 0.
    const double colour = power < pccmax ? kPt / pccmax * power
                                         : kPt + (power - pccmax) / (cmax - pccmax) * (1.0 - kPt);
    const double feature_difference =
        std::max(std::abs(reference_features[0][k] - test_features[0][k]),
                 std::abs(reference_features[1][k] - test_features[1][k]));
    const double feature = std::pow(feature_difference / std::numbers::sqrt2, kQf);  // >= 0
    // colour <= 1: cmax (green against blue) is the largest HyAB distance in the unit cube.
    map[k] = static_cast<float>(std::pow(colour, 1.0 - feature));
  }
  return map;
}

}  // namespace relief
