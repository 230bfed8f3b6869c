// The generator of the worked numbers quoted in docs/architecture.md ("Stage 4, operation by
// operation", "The deterministic functions"), docs/terrain-spec.md (section 12, "The periodic
// Gaussian, operation by operation", normalize's summation order) and docs/planet.md ("The
// bend and the normals' rotation, operation by operation"): it prints them from the docs'
// transcriptions (the *_transcription.h beside it) and checks every transcription bit for bit
// against the repository's own function, on the worked inputs and on random ones. Exit status
// 0 when every comparison holds, 1 otherwise ("failures: N" on the last line). The test
// worked_numbers_match_the_code runs it. Every random input comes from the tests' TestRandom
// (tests/support/test_support.h) with a constant seed, so every run compares the same numbers; the
// sample counts are those the docs' numbers were first checked with (the whole run takes about 0.05
// s at -O2, 0.13 s with -fsanitize=address,undefined at -O1).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/basis_images.h"
#include "core/det_math.h"
#include "core/grid_buffers.h"
#include "core/periodic_gaussian.h"
#include "core/planet_bend.h"
#include "core/planet_plan.h"
#include "core/stage_params.h"
#include "core/surface.h"
#include "tests/oracles/worked/basis_filters_transcription.h"
#include "tests/oracles/worked/det_math_transcription.h"
#include "tests/oracles/worked/surface_and_bend_transcription.h"
#include "tests/oracles/worked/worked_trace.h"
#include "tests/support/test_support.h"

namespace relief::test::worked {
namespace {

int failures = 0;

// Bit-for-bit equality: the transcription against the repository.
template <class T>
void same(const char* what, T a, T b) {
  if (std::memcmp(&a, &b, sizeof a) != 0) {
    ++failures;
    std::printf("MISMATCH %s: %.17g vs %.17g\n", what, double(a), double(b));
  }
}

void half_pi_pieces() {
  using det_math_detail::HalfPiPieces;
  std::printf("== sin_cos_det's pieces of pi/2\n");
  std::printf("  float hi %.9g %a mid %.9g %a lo %.9g %a\n", HalfPiPieces<float>::hi,
              HalfPiPieces<float>::hi, HalfPiPieces<float>::mid, HalfPiPieces<float>::mid,
              HalfPiPieces<float>::lo, HalfPiPieces<float>::lo);
  std::printf("  double hi %.17g %a mid %.17g %a lo %.17g %a\n", HalfPiPieces<double>::hi,
              HalfPiPieces<double>::hi, HalfPiPieces<double>::mid, HalfPiPieces<double>::mid,
              HalfPiPieces<double>::lo, HalfPiPieces<double>::lo);
  same("hi f", SpecHalfPi<float>::hi, HalfPiPieces<float>::hi);
  same("mid f", SpecHalfPi<float>::mid, HalfPiPieces<float>::mid);
  same("lo f", SpecHalfPi<float>::lo, HalfPiPieces<float>::lo);
  same("hi d", SpecHalfPi<double>::hi, HalfPiPieces<double>::hi);
  same("mid d", SpecHalfPi<double>::mid, HalfPiPieces<double>::mid);
  same("lo d", SpecHalfPi<double>::lo, HalfPiPieces<double>::lo);
}

void exp2_numbers() {
  std::printf("== exp2_det<double>, the blur's response at sigma 1.5, P = 8, k = 1\n");
  {
    const double pi = 3.14159265358979323846, log2e = 1.4426950408889634;
    const double sigma = 1.5, f = 1.0 / 8.0;
    const double x = -2.0 * pi * pi * sigma * sigma * f * f * log2e;
    same("exp2 d", spec_exp2<double>(x, true), exp2_det<double>(x));
    std::printf("  (std::exp(-2 pi^2 sigma^2 f^2) = %.17g)\n",
                std::exp(-2.0 * pi * pi * sigma * sigma * f * f));
  }
  for (float x : {-1.5f, 2.5f, 0.3f, -200.0f}) {
    std::printf("== exp2_det<float>(%g)\n", double(x));
    same("exp2 f", spec_exp2<float>(x, true), exp2_det<float>(x));
  }
  std::printf("== exp2_det<double>(-1.5), (2.5)\n");
  same("exp2 d", spec_exp2<double>(-1.5, true), exp2_det<double>(-1.5));
  same("exp2 d", spec_exp2<double>(2.5, true), exp2_det<double>(2.5));
  // Random arguments over the whole clamped range and beyond.
  test::TestRandom rng(7);
  for (int i = 0; i < 200000; ++i) {
    const double x = rng.uniform(-1100.0, 1100.0);
    same("exp2 d rnd", spec_exp2<double>(x, false), exp2_det<double>(x));
    const float xf = float(x / 8);
    same("exp2 f rnd", spec_exp2<float>(xf, false), exp2_det<float>(xf));
  }
}

void twiddle_numbers() {
  std::printf("\n== twiddles, n = 16\n");
  const std::vector<Complex> w = spec_twiddles(16, true);
  const double pi = 3.14159265358979323846;
  const long double pil = 3.141592653589793238462643383279502884L;
  for (int k = 0; k < 8; ++k) {
    const double c = std::cos(2 * pi * k / 16), s = -std::sin(2 * pi * k / 16);
    const Complex wk = w[std::size_t(k)];
    std::printf("  w[%d] = %.17g %.17g   (libm cos, -sin of 2 pi k/16: %.17g %.17g)  %a %a\n", k,
                wk.re, wk.im, c, s, wk.re, wk.im);
    const double cl = double(std::cos(2 * pil * k / 16)), sl = double(-std::sin(2 * pil * k / 16));
    std::printf("        long double cos, -sin rounded to double: %.17g %.17g  %a %a%s\n", cl, sl,
                cl, sl, (cl != wk.re || sl != wk.im) ? "  DIFFERS" : "");
  }
}

void blur_numbers() {
  std::printf("\n== periodic_gaussian_blur, 8 x 8, v(x, y) = ((x*x + 3*y) mod 7) / 6, sigma 1.5\n");
  {
    const int n = 8;
    std::vector<double> v(n * n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        v[std::size_t(y * n + x)] = double((x * x + 3 * y) % 7) / 6.0;
    double sum_in = 0;
    for (double a : v)
      sum_in += a;
    std::vector<double> mine = v, theirs = v;
    spec_blur(mine, n, 1.5);
    periodic_gaussian_blur(theirs, n, 1.5);
    for (std::size_t k = 0; k < v.size(); ++k)
      same("blur 8", mine[k], theirs[k]);
    const std::vector<double> g = spec_response(n, 1.5);
    for (int k = 0; k < n; ++k)
      std::printf("  g[%d] = %.17g\n", k, g[std::size_t(k)]);
    std::printf("  input row 0: ");
    for (int x = 0; x < n; ++x)
      std::printf("%.17g ", v[std::size_t(x)]);
    std::printf("\n");
    for (int y : {0, 5}) {
      std::printf("  out row %d:\n", y);
      for (int x = 0; x < n; ++x) {
        const double out = theirs[std::size_t(y * n + x)];
        std::printf("    out(%d, %d) = %.17g  %a\n", x, y, out, out);
      }
    }
    double sum_out = 0;
    for (double a : theirs)
      sum_out += a;
    std::printf("  sum in %.17g, sum out %.17g\n", sum_in, sum_out);
  }
  // Random grids of every power-of-two side to 128, sigma small to n / 2.
  test::TestRandom rng(11);
  int grids = 0;
  for (int n : {1, 2, 4, 8, 16, 32, 64, 128}) {
    for (double sigma : {0.3, 1.0, 2.5, 7.0, double(n) / 2}) {
      std::vector<double> v(std::size_t(n) * std::size_t(n));
      for (double& a : v)
        a = rng.uniform(0.0, 1.0);
      std::vector<double> mine = v, theirs = v;
      spec_blur(mine, n, sigma);
      periodic_gaussian_blur(theirs, n, sigma);
      for (std::size_t k = 0; k < v.size(); ++k)
        same("blur rnd", mine[k], theirs[k]);
      ++grids;
    }
  }
  std::printf("  random grids compared with periodic_gaussian_blur: %d\n", grids);
}

void sin_cos_numbers() {
  for (double x : {0.25, 2.0}) {
    std::printf("\n== sin_cos_det<double>(%g)\n", x);
    double s, c, s2, c2;
    spec_sincos<double>(x, s, c, true);
    sin_cos_det<double>(x, s2, c2);
    same("sin d", s, s2);
    same("cos d", c, c2);
    std::printf("  (libm sin, cos: %.17g %.17g)\n", std::sin(x), std::cos(x));
    std::printf("== sin_cos_det<float>(%g)\n", x);
    float sf, cf, sf2, cf2;
    spec_sincos<float>(float(x), sf, cf, true);
    sin_cos_det<float>(float(x), sf2, cf2);
    same("sin f", sf, sf2);
    same("cos f", cf, cf2);
    std::printf("  (double sin, cos rounded to float: %.9g %.9g)\n", double(float(std::sin(x))),
                double(float(std::cos(x))));
  }
  // Random arguments over [-100, 100) (past the |x| <= 64 of the docs, where q clamps).
  test::TestRandom rng(5);
  for (int i = 0; i < 200000; ++i) {
    const double x = rng.uniform(-100.0, 100.0);
    double s, c, s2, c2;
    spec_sincos<double>(x, s, c, false);
    sin_cos_det<double>(x, s2, c2);
    same("sin d rnd", s, s2);
    same("cos d rnd", c, c2);
    float sf, cf, sf2, cf2;
    spec_sincos<float>(float(x), sf, cf, false);
    sin_cos_det<float>(float(x), sf2, cf2);
    same("sin f rnd", sf, sf2);
    same("cos f rnd", cf, cf2);
  }
}

template <class Real>
void normal_case(const char* title) {
  std::printf("\n== stage 4 normal, %s\n", title);
  const int W = 3, H = 3;
  const GridLayout layout = make_grid_layout(W, H);
  GridBuffers<Real> g(layout);
  // A 3 x 3 patch of a projected grid: rows (j) recede along -z, columns (i) run along x.
  const double dxv[3][3] = {{-13.5, 0.25, 14.0}, {-15.75, 0.5, 16.75}, {-18.5, 0.75, 20.0}};
  const double dzv[3][3] = {
      {-100.0, -100.5, -101.0}, {-115.25, -115.5, -116.0}, {-133.0, -133.25, -133.75}};
  const double hv[3][3] = {
      {-652.5, -650.25, -649.0}, {-655.75, -651.5, -648.25}, {-660.0, -655.5, -650.75}};
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t k = layout.index(i, j);
      g.dx[k] = Real(dxv[j][i]);
      g.dz[k] = Real(dzv[j][i]);
      g.height[k] = Real(hv[j][i]);
      g.valid[k] = 1;
    }
  SurfaceParams<Real> p{};
  p.width = W, p.height = H, p.pitch = layout.pitch;
  p.water_enabled = 0;
  p.water_level = 0;
  p.min_sine_sq = Real(1e-6 * 1e-6);
  p.max_slope = Real(1e6);
  // Visible sides (docs/architecture.md): w_facing = 4, w_least = 1/32. Seen from 650 units
  // above, every side of this vertex faces the eye by far more than 1/4: all weights are 1
  // and the difference is the plain central one that spec_normal transcribes.
  p.inv_silhouette_facing = Real(4);
  p.hidden_side_weight = Real(1.0 / 32);
  surface_pass<Real>(p, RowRange{0, H}, SurfaceInputs<Real>{g.dx, g.dz, g.height, g.valid, {}},
                     g.surface());
  const std::size_t c = layout.index(1, 1);
  Real out[4];
  spec_normal<Real>(g.dx.data(), g.dz.data(), g.height.data(), layout.pitch, int(c), out, true);
  same("nx", out[0], g.nx[c]);
  same("ny", out[1], g.ny[c]);
  same("nz", out[2], g.nz[c]);
  same("slope", out[3], g.slope[c]);
  print_real("nx", g.nx[c]), print_real("ny", g.ny[c]), print_real("nz", g.nz[c]),
      print_real("slope", g.slope[c]);
}

template <class Real>
void bend_normal_case(const char* title, double R, double dxv, double dzv, const double n0[3]) {
  std::printf("\n== bend_normals, %s\n", title);
  PlanetParams<Real> p{};
  p.enabled = 1;
  p.radius = Real(R);
  p.inv_radius = Real(1.0 / R);
  Real dx[1] = {Real(dxv)}, dz[1] = {Real(dzv)};
  std::uint8_t valid[1] = {1};
  Real nx[1] = {Real(n0[0])}, ny[1] = {Real(n0[1])}, nz[1] = {Real(n0[2])};
  bend_normals<Real>(p, IndexRange{0, 1}, dx, dz, valid, nx, ny, nz);
  const BentNormal<Real> s =
      spec_bend_normal<Real>(p.inv_radius, dx[0], dz[0], Real(n0[0]), Real(n0[1]), Real(n0[2]));
  same("bent nx", s.nx, nx[0]);
  same("bent ny", s.ny, ny[0]);
  same("bent nz", s.nz, nz[0]);
  print_real("inv_radius", p.inv_radius), print_real("rho", s.rho), print_real("theta", s.theta),
      print_real("sin theta", s.sine), print_real("sin(theta/2)", s.half_sine),
      print_real("cos theta - 1", s.cm1), print_real("ux", s.ux), print_real("uz", s.uz),
      print_real("along", s.along), print_real("delta", s.delta), print_real("nx'", nx[0]),
      print_real("ny'", ny[0]), print_real("nz'", nz[0]);
}

template <class Real>
void bend_vertex_case(const char* title, double R, double D, double dxv, double dzv, double hv) {
  std::printf("\n== bend_vertices, %s\n", title);
  PlanetParams<Real> p{};
  p.enabled = 1;
  p.radius = Real(R);
  p.inv_radius = Real(1.0 / R);
  p.center_distance = Real(D);
  Real dx[1] = {Real(dxv)}, dz[1] = {Real(dzv)}, h[1] = {Real(hv)};
  std::uint8_t valid[1] = {1};
  Real bx[1], by[1], bz[1], bd[1];
  bend_vertices<Real>(p, IndexRange{0, 1}, dx, dz, h, valid, BentSpans<Real>{bx, by, bz, bd});
  const BentVertex<Real> s =
      spec_bend_vertex<Real>(p.center_distance, p.inv_radius, dx[0], dz[0], h[0]);
  same("px", s.px, bx[0]);
  same("pz", s.pz, bz[0]);
  same("py", s.py, by[0]);
  same("drop", s.drop, bd[0]);
  print_real("D", p.center_distance), print_real("hc", h[0]), print_real("rho", s.rho),
      print_real("theta", s.theta), print_real("sin theta", s.sine), print_real("sinc", s.sinc),
      print_real("sin(theta/2)", s.half_sine), print_real("R + e = D + hc", s.radius_here),
      print_real("scale", s.scale), print_real("drop", s.drop), print_real("px", bx[0]),
      print_real("py", by[0]), print_real("pz", bz[0]);
}

void bend_numbers() {
  const double up[3] = {0.0, 1.0, 0.0}, tilted[3] = {0.6, 0.8, 0.0};
  bend_normal_case<double>("double, R = 2e6, (dx, dz) = (3e5, -4e5), n = (0, 1, 0)", 2e6, 3e5, -4e5,
                           up);
  bend_normal_case<float>("float, R = 2e6, (dx, dz) = (3e5, -4e5), n = (0, 1, 0)", 2e6, 3e5, -4e5,
                          up);
  bend_normal_case<float>("float, R = 2e6, (dx, dz) = (3e5, -4e5), n = (0.6, 0.8, 0)", 2e6, 3e5,
                          -4e5, tilted);
  bend_vertex_case<double>("double, R = 2e6, D = 4e6, (dx, dz) = (3e5, -4e5), hc = -1999250", 2e6,
                           4e6, 3e5, -4e5, -1999250.0);
  bend_vertex_case<float>("float, R = 2e6, D = 4e6, (dx, dz) = (3e5, -4e5), hc = -1999250", 2e6,
                          4e6, 3e5, -4e5, -1999250.0);
}

void normalize_numbers() {
  std::printf("\n== normalize: row-major sums against column-major on a 64 x 64 random grid\n");
  const int n = 64;
  test::TestRandom rng(3);
  GreyGrid g;
  g.side = n;
  g.values.resize(n * n);
  for (double& a : g.values)
    a = std::round(rng.uniform(0.0, 1.0) * 65535.0) / 65535.0;
  GreyGrid theirs = g;
  BasisImageSettings settings;
  settings.normalize = true;
  filter_basis_image(theirs, settings, "test");
  const Moments row = spec_moments(g.values, n, true), column = spec_moments(g.values, n, false);
  int differ = 0;
  for (std::size_t k = 0; k < g.values.size(); ++k) {
    const double normalised = (g.values[k] - row.mean) / row.sd;
    same("normalize", normalised, theirs.values[k]);
    differ += normalised != (g.values[k] - column.mean) / column.sd;
  }
  std::printf(
      "  mean row-major %a, column-major %a; sd %a vs %a; %d of %d normalised values differ\n",
      row.mean, column.mean, row.sd, column.sd, differ, n * n);
}

}  // namespace
}  // namespace relief::test::worked

int main() {
  using namespace relief::test::worked;
  half_pi_pieces();
  exp2_numbers();
  twiddle_numbers();
  blur_numbers();
  sin_cos_numbers();
  normal_case<float>("float");
  normal_case<double>("double");
  bend_numbers();
  normalize_numbers();
  std::printf("\nfailures: %d\n", failures);
  return failures == 0 ? 0 : 1;
}
