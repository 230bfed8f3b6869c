// Per-target body of simd/reflection_rays.h: reflection_ray<float> (core/water_reflection.cc)
// on a vector of pixels. Lanes not active are zeroed, and their surface points too where the
// view ray does not descend, before the wave normal's gathers, which then read in range.
#if defined(RELIEF_SIMD_REFLECTION_RAYS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_REFLECTION_RAYS_INL_H_
#undef RELIEF_SIMD_REFLECTION_RAYS_INL_H_
#else
#define RELIEF_SIMD_REFLECTION_RAYS_INL_H_
#endif

#include <algorithm>
#include <cstdint>

#include <hwy/highway.h>

#include "core/stage_params.h"
#include "simd/lattice-inl.h"
#include "simd/reflection_rays.h"
#include "simd/shade_vec3-inl.h"
#include "simd/water-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

void ReflectionRays(const ShadeParams<float>& p, const NoiseLattice& lattice,
                    const std::uint32_t* primitive, const float* dx, const float* height,
                    const float* dz, const float* depth, int count, const ReflectionRayRow& row) {
  const hn::ScalableTag<float> d;
  const hn::RebindToUnsigned<decltype(d)> du;
  const int lanes = static_cast<int>(hn::Lanes(d));
  const LatticeView view_lattice = view_of(lattice);
  const auto zero = hn::Zero(d);
  constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  HWY_ALIGN float out[7][kMaxLanes];
  HWY_ALIGN float tail[4][kMaxLanes];
  HWY_ALIGN std::uint32_t tail_primitive[kMaxLanes];
  for (int i = 0; i < count; i += lanes) {
    const int n = std::min(lanes, count - i);
    // The row's last pixels: copies, the lanes past it not covered.
    const float* in[4] = {dx + i, height + i, dz + i, depth + i};
    const std::uint32_t* covered = primitive + i;
    if (n < lanes) {
      for (int k = 0; k < 4; ++k) {
        std::fill(tail[k], tail[k] + kMaxLanes, 0.0f);
        std::copy(in[k], in[k] + n, tail[k]);
        in[k] = tail[k];
      }
      std::fill(tail_primitive, tail_primitive + kMaxLanes, 0xffffffffu);
      std::copy(covered, covered + n, tail_primitive);
      covered = tail_primitive;
    }
    // The water test of tile_reflections.cc: covered, the ground below the level.
    const auto on = hn::And(
        hn::RebindMask(d, hn::Not(hn::Eq(hn::LoadU(du, covered), hn::Set(du, 0xffffffffu)))),
        hn::Lt(hn::LoadU(d, in[1]), hn::Set(d, p.water_level)));
    const auto load = [&](int k) { return hn::IfThenElseZero(on, hn::LoadU(d, in[k])); };
    // reflection_ray's steps, one by one.
    const V3<hn::Vec<decltype(d)>> position{load(0), load(1), load(2)};
    const auto view = NormalizeOr(d, position, Set3(d, p.camera_forward));
    const auto ok = hn::And(on, hn::Lt(view.y, zero));
    const auto level = hn::Set(d, p.water_level);
    // Zero where the ray does not descend: the wave normal's gathers then read in range.
    const auto surface = hn::IfThenElseZero(ok, hn::Div(level, view.y));
    const auto footprint = SurfaceFootprint(d, p, surface, view.y);
    const auto f = Smooth01(d, hn::Mul(StdMax(zero, load(3)), hn::Set(d, p.inv_full_depth)));
    const auto sx = hn::Mul(view.x, surface), sz = hn::Mul(view.z, surface);
    const auto normal = WaveNormal(d, p, view_lattice, sx, sz,
                                   hn::Mul(hn::Set(d, p.wave_strength), f), footprint, ok);
    const auto reflected =
        Sub3(view, Scale3(normal, hn::Mul(hn::Set(d, 2.0f), Dot3(view, normal))));
    const auto weight = Smooth01(d, hn::Div(reflected.y, hn::Mul(hn::Set(d, -0.5f), view.y)));
    const auto direction = NormalizeOr(d, reflected, Set3(d, 0.0f, 1.0f, 0.0f));
    hn::Store(sx, d, out[0]);
    hn::Store(sz, d, out[1]);
    hn::Store(surface, d, out[2]);
    hn::Store(direction.x, d, out[3]);
    hn::Store(direction.y, d, out[4]);
    hn::Store(direction.z, d, out[5]);
    hn::Store(hn::IfThenElseZero(ok, weight), d, out[6]);
    float* const targets[7] = {row.start_x,     row.start_z,     row.surface, row.direction_x,
                               row.direction_y, row.direction_z, row.weight};
    for (int k = 0; k < 7; ++k) {
      std::copy(out[k], out[k] + n, targets[k] + i);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
