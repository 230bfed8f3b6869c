#include "core/sun_visibility.h"

#include <algorithm>
#include <cmath>

namespace relief {

namespace {

// a + (b - a) f: exactly a where a == b (a lit neighbourhood stays exactly 1).
template <class Real>
Real lerp(Real a, Real b, Real f) {
  return a + (b - a) * f;
}

// The disc's share above a horizon of slope `tangent` (sun_visibility.h).
template <class Real>
Real disc_share(const ShadowParams<Real>& p, Real tangent) {
  if (tangent <= p.lit_tangent) {
    return Real(1);
  }
  if (tangent >= p.dark_tangent) {
    return Real(0);
  }
  // sin(e_s - e_h) with sin e_h = t / sqrt(1 + t^2), cos e_h = 1 / sqrt(1 + t^2) (sqrt's
  // argument >= 1; |t| is at most 1e6, its square far inside float). Between the two tangents
  // both angles lie in (-90, 90) degrees and the difference within the disc's radius.
  const Real sine =
      (p.sin_elevation - tangent * p.cos_elevation) / std::sqrt(Real(1) + tangent * tangent);
  // sin_radius >= sin(0.11 degrees) > 0 (limits.h, kMinSunDiscDeg).
  const Real x = std::clamp(sine / p.sin_radius, Real(-1), Real(1));
  const Real t = Real(0.5) + Real(0.5) * x;
  return t * t * (Real(3) - Real(2) * t);
}

}  // namespace

template <class Real>
Real sun_visibility(const ShadowParams<Real>& p, const SunHorizonCache<Real>& c, Real dx,
                    Real height, Real dz, ShadowWork& work) {
  ++work.pixels;
  if (p.sun_set != 0) {
    ++work.dark;
    return Real(0);
  }
  const Real u = dx * p.axis_x + dz * p.axis_z;
  const Real v = dz * p.axis_x - dx * p.axis_z;
  const Real last = Real(p.resolution - 1);
  for (int level = 0; level < p.levels; ++level) {
    const Real fi = (u - p.origin_u[level]) * p.inv_spacing[level];
    const Real fj = (v - p.origin_v[level]) * p.inv_spacing[level];
    if (!(fi >= Real(0) && fi < last && fj >= Real(0) && fj < last)) {
      continue;
    }
    const int i = int(fi), j = int(fj);  // floor: both >= 0
    const Real f = fi - Real(i), g = fj - Real(j);
    const std::size_t k[4] = {c.index(level, j, i), c.index(level, j, i + 1),
                              c.index(level, j + 1, i), c.index(level, j + 1, i + 1)};
    // The lift only lowers a horizon: four below the disc's lower edge light it whatever the
    // lift (the evaluation below gives exactly 1 there too: FrameSkips::lit_shadows).
    if (p.skip_lit != 0 && c.tangent[k[0]] <= p.lit_tangent && c.tangent[k[1]] <= p.lit_tangent &&
        c.tangent[k[2]] <= p.lit_tangent && c.tangent[k[3]] <= p.lit_tangent) {
      ++work.lit;
      return Real(1);
    }
    const Real surface =
        lerp(lerp(c.height[k[0]], c.height[k[1]], f), lerp(c.height[k[2]], c.height[k[3]], f), g);
    const Real lift = std::max(Real(0), height - surface);
    Real share[4];
    bool dark = true;
    for (int corner = 0; corner < 4; ++corner) {
      // distance >= the level's spacing > 0 (sun_horizons.cc).
      const Real tangent = c.tangent[k[corner]] - lift / c.distance[k[corner]];
      share[corner] = disc_share(p, tangent);
      dark = dark && tangent >= p.dark_tangent;
    }
    ++work.evaluated;
    work.dark += dark;
    return lerp(lerp(share[0], share[1], f), lerp(share[2], share[3], f), g);
  }
  ++work.outside;
  return Real(1);
}

template float sun_visibility<float>(const ShadowParams<float>&, const SunHorizonCache<float>&,
                                     float, float, float, ShadowWork&);
template double sun_visibility<double>(const ShadowParams<double>&, const SunHorizonCache<double>&,
                                       double, double, double, ShadowWork&);

}  // namespace relief
