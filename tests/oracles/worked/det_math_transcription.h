// exp2_det and sin_cos_det (with its three pieces of pi/2) re-implemented from the text of
// docs/architecture.md, "The deterministic functions (`core/det_math.h`)", not from the code:
// tests/oracles/worked/worked_numbers.cc traces them to print that section's tables and
// compares them bit for bit with relief::exp2_det and relief::sin_cos_det.
#pragma once

#include <bit>
#include <cstdint>
#include <cstdio>

#include "tests/oracles/worked/worked_trace.h"

namespace relief::test::worked {

// c[k] = (ln 2)^k / k!; T = 9 terms in float, 14 in double.
inline constexpr double kExp2Series[14] = {1.0,
                                           0.6931471805599453,
                                           0.2402265069591007,
                                           0.055504108664821576,
                                           0.009618129107628477,
                                           0.0013333558146428441,
                                           0.00015403530393381606,
                                           1.5252733804059838e-05,
                                           1.3215486790144305e-06,
                                           1.0178086009239696e-07,
                                           7.054911620801121e-09,
                                           4.44553827187081e-10,
                                           2.5678435993488196e-11,
                                           1.3691488853904124e-12};

template <class Real>
Real spec_exp2(Real x, bool trace) {
  const bool is_float = sizeof(Real) == 4;
  const Real limit = is_float ? Real(125) : Real(1021);
  x = x < -limit ? -limit : (x > limit ? limit : x);
  const double magic = 6755399441055744.0;  // 1.5 * 2^52
  const Real n = Real((double(x) + magic) - magic);
  const Real f = x - n;
  const int terms = is_float ? 9 : 14;
  Real s = Real(kExp2Series[terms - 1]);
  for (int k = terms - 2; k >= 0; --k)
    s = s * f + Real(kExp2Series[k]);
  Real two_n;
  if constexpr (sizeof(Real) == 4) {
    two_n = std::bit_cast<float>(std::uint32_t(int(n) + 127) << 23);
  } else {
    two_n = std::bit_cast<double>(std::uint64_t(int(n) + 1023) << 52);
  }
  const Real result = s * two_n;
  if (trace) {
    print_real("x", x), print_real("n", n), print_real("f = x - n", f), print_real("series 2^f", s),
        print_real("2^n", two_n), print_real("exp2_det(x)", result);
  }
  return result;
}

// s[i] = (-1)^i / (2i+1)! (S = 5 in float, 8 in double); cc[i] = (-1)^i / (2i)! (C = 6, 9).
inline constexpr double kSinSeries[8] = {1.0,
                                         -0.16666666666666666,
                                         0.008333333333333333,
                                         -0.0001984126984126984,
                                         2.7557319223985893e-06,
                                         -2.505210838544172e-08,
                                         1.6059043836821613e-10,
                                         -7.647163731819816e-13};
inline constexpr double kCosSeries[9] = {1.0,
                                         -0.5,
                                         0.041666666666666664,
                                         -0.001388888888888889,
                                         2.48015873015873e-05,
                                         -2.755731922398589e-07,
                                         2.08767569878681e-09,
                                         -1.1470745597729725e-11,
                                         4.779477332387385e-14};

// pi/2 in three pieces, as the docs list them.
template <class Real>
struct SpecHalfPi;
template <>
struct SpecHalfPi<float> {
  static constexpr float hi = 1.5703125f, mid = 0.00048382580280303955f,
                         lo = 9.920935796805404e-10f;
};
template <>
struct SpecHalfPi<double> {
  static constexpr double hi = 1.5707963267341256, mid = 6.077100506303966e-11,
                          lo = 2.0222662487959506e-21;
};

template <class Real>
void spec_sincos(Real x, Real& sine, Real& cosine, bool trace) {
  const bool is_float = sizeof(Real) == 4;
  const Real hi = SpecHalfPi<Real>::hi, mid = SpecHalfPi<Real>::mid, lo = SpecHalfPi<Real>::lo;
  const Real inv_half_pi = Real(1.0 / 1.5707963267948966);
  Real q = x * inv_half_pi;
  q = q < Real(-64) ? Real(-64) : (q > Real(64) ? Real(64) : q);
  const int k = int(q < Real(0) ? q - Real(0.5) : q + Real(0.5));
  const Real r = ((x - Real(k) * hi) - Real(k) * mid) - Real(k) * lo;
  const Real r2 = r * r;
  const int ns = is_float ? 5 : 8, nc = is_float ? 6 : 9;
  Real ps = Real(kSinSeries[ns - 1]);
  for (int i = ns - 2; i >= 0; --i)
    ps = ps * r2 + Real(kSinSeries[i]);
  Real pc = Real(kCosSeries[nc - 1]);
  for (int i = nc - 2; i >= 0; --i)
    pc = pc * r2 + Real(kCosSeries[i]);
  const Real s = r * ps, c = pc;
  switch (k & 3) {
    case 0:
      sine = s, cosine = c;
      break;
    case 1:
      sine = c, cosine = -s;
      break;
    case 2:
      sine = -s, cosine = -c;
      break;
    default:
      sine = -c, cosine = s;
      break;
  }
  if (trace) {
    print_real("x", x), print_real("1/(pi/2) in Real", inv_half_pi),
        print_real("q = x * 1/(pi/2)", q);
    std::printf("  %-28s %d\n", "k", k);
    print_real("r", r), print_real("r2", r2), print_real("ps (Horner)", ps),
        print_real("pc (Horner)", pc), print_real("s = r * ps", s);
    print_real("sine", sine), print_real("cosine", cosine);
  }
}

}  // namespace relief::test::worked
