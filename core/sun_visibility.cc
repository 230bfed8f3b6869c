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
  // argument >= 1). Between the two tangents both angles lie in (-90, 90] degrees and the
  // difference within the disc's radius. t is clamped to +-1e6 first (a horizon within 6e-5
  // degrees of the zenith, the same share to float's precision), so that t^2 stays far inside
  // float: dark_tangent is 1e30 where the disc reaches the zenith, and a cache's slopes reach
  // amplitude / spacing.
  const Real t = std::clamp(tangent, Real(-1e6), Real(1e6));
  const Real sine = (p.sin_elevation - t * p.cos_elevation) / std::sqrt(Real(1) + t * t);
  // sin_radius >= sin(0.11 degrees) > 0 (limits.h, kMinSunDiscDeg).
  const Real x = std::clamp(sine / p.sin_radius, Real(-1), Real(1));
  const Real s = Real(0.5) + Real(0.5) * x;
  return s * s * (Real(3) - Real(2) * s);
}

// The disc's share at level `level`, the point at sample coordinates (fi, fj) inside it
// (0 <= fi, fj < N - 1); `proven_lit` whether four comparisons settled it.
template <class Real>
Real level_share(const ShadowParams<Real>& p, const SunHorizonCache<Real>& c, int level, Real fi,
                 Real fj, Real height, bool& proven_lit) {
  const int i = int(fi), j = int(fj);  // floor: both >= 0
  const Real f = fi - Real(i), g = fj - Real(j);
  const std::size_t k[4] = {c.index(level, j, i), c.index(level, j, i + 1),
                            c.index(level, j + 1, i), c.index(level, j + 1, i + 1)};
  // The lift only lowers a horizon: four below the disc's lower edge light it whatever the
  // lift (the evaluation below gives exactly 1 there too: FrameSkips::lit_shadows).
  proven_lit = p.skip_lit != 0 && c.tangent[k[0]] <= p.lit_tangent &&
               c.tangent[k[1]] <= p.lit_tangent && c.tangent[k[2]] <= p.lit_tangent &&
               c.tangent[k[3]] <= p.lit_tangent;
  if (proven_lit) {
    return Real(1);
  }
  const Real surface =
      lerp(lerp(c.height[k[0]], c.height[k[1]], f), lerp(c.height[k[2]], c.height[k[3]], f), g);
  const Real lift = std::max(Real(0), height - surface);
  Real share[4];
  for (int corner = 0; corner < 4; ++corner) {
    share[corner] = disc_share(p, c.tangent[k[corner]] - lift * c.inv_distance[k[corner]]);
  }
  return lerp(lerp(share[0], share[1], f), lerp(share[2], share[3], f), g);
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
  bool proven_lit = true;
  Real share = 0;
  const auto at = [&](int level, Real fi, Real fj) {
    bool lit = false;
    const Real level_value = level_share(p, c, level, fi, fj, height, lit);
    proven_lit = proven_lit && lit;
    return level_value;
  };
  if (!blended_level_value(p, u, v, at, share)) {  // NaN coordinates, or beyond the cache: lit
    ++work.outside;
    return Real(1);
  }
  if (proven_lit) {
    ++work.lit;
  } else {
    ++work.evaluated;
  }
  work.dark += share == Real(0);
  return share;
}

template float sun_visibility<float>(const ShadowParams<float>&, const SunHorizonCache<float>&,
                                     float, float, float, ShadowWork&);
template double sun_visibility<double>(const ShadowParams<double>&, const SunHorizonCache<double>&,
                                       double, double, double, ShadowWork&);

}  // namespace relief
