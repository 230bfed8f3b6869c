// Cast shadows, per pixel (docs/stages.md, "Cast shadows"): the share of the sun disc above the
// terrain's horizon at a shaded point, from the horizons of sun_horizons.h.
//
// The point's level is the finest whose samples surround it. At each of the four samples
// around it the horizon's slope toward the sun, tangent - lift * inv_distance, is that sample's
// horizon seen from the point's own height (the pixel carries the octaves finer than the
// level's: `lift` is how far it stands above the level's bilinear surface, never below it, so
// that the finer octaves lower the horizon of a bump but never raise one into self-shadow).
// The disc's visible share at a horizon of elevation e_h, for the sun at e_s with angular radius
// r, is smoothstep(-1, 1, sin(e_s - e_h) / sin r): 1 where e_h <= e_s - r, 0 where
// e_h >= e_s + r, in between a smooth step of the angle (a disc cut by a horizontal line
// within 1.5% of its covered area). The four shares are interpolated bilinearly. Within N / 32
// samples of its level's edge the share fades linearly into the next coarser level's (the
// squares nest: that level holds the point too), so a pixel passing from one level to the next
// sees no step, and the levels' squares, which follow the camera a spacing at a time, move no
// shadow edge at once.
//
// A sample whose horizon lies below tan(e_s - r) lights the disc whatever the lift; a pixel
// whose four samples do so is lit without any arithmetic beyond four comparisons (counted, as
// are the pixels evaluated and those whose share comes out 0).
#pragma once

#include <cstdint>

#include "core/sun_horizons.h"

namespace relief {

struct ShadowWork {
  std::uint64_t pixels = 0;     // covered pixels looked up
  std::uint64_t lit = 0;        // of those, proven lit by four comparisons a level (skip_lit)
  std::uint64_t evaluated = 0;  // the disc's share evaluated at four samples of some level
  std::uint64_t dark = 0;       // of any, in full shadow (share 0, or the sun has set)
  std::uint64_t outside = 0;    // beyond the cache: lit

  ShadowWork& operator+=(const ShadowWork& o) {
    pixels += o.pixels;
    lit += o.lit;
    evaluated += o.evaluated;
    dark += o.dark;
    outside += o.outside;
    return *this;
  }
};

// The sun disc's visible share at camera-relative (dx, height, dz), in [0, 1]. Precondition:
// params enabled, the cache swept (every level). Finite inputs.
template <class Real>
Real sun_visibility(const ShadowParams<Real>& params, const SunHorizonCache<Real>& cache, Real dx,
                    Real height, Real dz, ShadowWork& work);

}  // namespace relief
