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
  const Real last = Real(p.resolution - 1);
  Real fi = 0, fj = 0;
  const auto inside = [&](int level) {
    fi = (u - p.origin_u[level]) * p.inv_spacing[level];
    fj = (v - p.origin_v[level]) * p.inv_spacing[level];
    return fi >= Real(0) && fi < last && fj >= Real(0) && fj < last;
  };
  // The finest level from `first_level` whose square holds the point (the squares nest: it
  // holds the point in every coarser level too).
  int level = p.first_level;
  while (level < p.end_level && !inside(level)) {
    ++level;
  }
  if (level >= p.end_level) {  // NaN coordinates, or beyond the coarsest level: lit
    ++work.outside;
    return Real(1);
  }
  bool proven_lit = false;
  Real share = level_share(p, c, level, fi, fj, height, proven_lit);
  // Within the band of `blend_samples` along its square's edge a level's share fades into the
  // next coarser level's, which holds the point too (the squares nest): continuous where a
  // pixel passes from one level to the next, so that the squares' steps with the camera
  // (a spacing at a time) move no shadow edge at once.
  const Real edge = std::min(std::min(fi, fj), std::min(last - fi, last - fj));
  if (edge < p.blend_samples && level + 1 < p.end_level && inside(level + 1)) {
    bool coarse_lit = false;
    const Real coarse = level_share(p, c, level + 1, fi, fj, height, coarse_lit);
    share = lerp(coarse, share, edge * p.inv_blend_samples);
    proven_lit = proven_lit && coarse_lit;
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
