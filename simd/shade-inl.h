// Per-target body of simd/shade.h: stage 8 of core/shade.cc (terrain_radiance and
// background_radiance for float, times the exposure) on a vector of pixels of one row.
// Every per-pixel branch of the scalar code becomes a mask: a lane gets exactly the operations
// the scalar code does for its pixel, in the same order; work is skipped only where no lane
// needs it, and the work counters count the lanes of the masks the scalar code branches on.
// Lanes that are not covered (or lie past the rectangle) are zeroed before the terrain path
// reads them, so their (discarded) arithmetic never gathers outside a texture or the lattice.
#if defined(RELIEF_SIMD_SHADE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_SHADE_INL_H_
#undef RELIEF_SIMD_SHADE_INL_H_
#else
#define RELIEF_SIMD_SHADE_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>

#include <hwy/highway.h>

#include "core/limits.h"
#include "core/shade.h"
#include "core/stage_params.h"
#include "simd/gradient_shade-inl.h"
#include "simd/planet_shade-inl.h"
#include "simd/shade_calls-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/sky-inl.h"
#include "simd/textured_shade-inl.h"
#include "simd/water-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// terrain_radiance (shade.cc) for the lanes of `covered`, whose attributes are `a`.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> TerrainRadiance(D d, const ShadeContext& ctx, const AttributeVectors<V>& a,
                                 M covered, ShadeWork& work) {
  const ShadeParams<float>& p = *ctx.p;
  const V zero = hn::Zero(d);
  work.terrain_pixels += hn::CountTrue(d, covered);
  const V relative_y = a.height;
  // On a planet the position is the bent one, the height a.drop above it (shade.cc; on the
  // plane the drop is 0 and y - 0 is y: not formed).
  const bool planet = p.planet_center_distance > 0.0;
  const V3<V> position{a.dx, planet ? hn::Sub(relative_y, a.drop) : relative_y, a.dz};
  const V length_sq = Dot3(position, position);
  const V distance = hn::Sqrt(length_sq);
  const V3<V> view = NormalizeOrWith(d, position, length_sq, Set3(d, p.camera_forward));
  // The cloud layer's shadow (clouds.cc), at the pixel's footprint.
  AttributeVectors<V> lit = a;
  if (p.clouds) {
    lit.sun = hn::Mul(
        a.sun, CloudSunShareLanes(p, ctx.lattice, position,
                                  hn::Mul(distance, hn::Set(d, p.pixel_angle)), covered, work));
  }
  V3<V> radiance = p.gradient_enabled
                       ? GouraudLight(d, p, GradientAlbedo(d, p, relative_y), lit.lambert, lit.ny,
                                      lit.sun, lit.sky)
                       : TexturedRadiance(d, ctx, lit, distance, view, covered, work);

  V fog_distance = distance;
  if (p.water_enabled && p.terrain_water) {
    const V level = hn::Set(d, p.water_level);
    const M under_water =
        hn::And(covered, hn::And(hn::Lt(relative_y, level), hn::Lt(view.y, zero)));
    const std::size_t count = hn::CountTrue(d, under_water);
    if (count != 0) {
      // On a planet the surface lies a.drop lower too, and is shaded in the local frame of
      // the point (its up the sphere's radial direction through the bent position).
      const V surface = hn::Div(planet ? hn::Sub(level, a.drop) : level, view.y);
      V3<V> water_view = view;
      if (planet) {
        const V center_y = hn::Set(d, float(p.planet_center_distance));
        const V3<V> radial{position.x, hn::Add(position.y, center_y), position.z};
        const V3<V> up = NormalizeOr(d, radial, Set3(d, 0.0f, 1.0f, 0.0f));
        water_view = ToLocalFrame(d, view, up);
      }
      const V footprint = SurfaceFootprint(d, p, surface, water_view.y);
      const V3<V> water = ShadeWaterLanes(
          p, ctx.lattice, ctx.skybox, water_view, surface, StdMax(zero, a.water_depth), radiance,
          footprint, a.water_sun, V3<V>{a.reflection_r, a.reflection_g, a.reflection_b},
          a.reflection_weight, under_water, work);
      radiance = Select3(under_water, water, radiance);
      fog_distance = hn::IfThenElse(under_water, surface, distance);
      work.water_pixels += count;
    }
  }
  if (p.fog_enabled) {
    work.fogged_pixels += hn::CountTrue(d, covered);
    radiance = ApplyFog(d, p, radiance, view, fog_distance);
  }
  return p.clouds ? CloudsOverLanes(p, ctx.lattice, radiance, V3<V>{zero, zero, zero}, zero, view,
                                    fog_distance, covered, work)
                  : radiance;
}

// One vector of pixels k .. k + lanes - 1 of a row, `valid` the lanes inside the rectangle;
// the attribute pointers hold at least Lanes(d) values.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> ShadeVector(D d, const ShadeContext& ctx, const std::uint32_t* primitive,
                             const float* const* fields, M valid, int px0, int py,
                             ShadeWork& work) {
  const hn::RebindToUnsigned<D> du;
  const M covered = hn::And(
      valid,
      hn::RebindMask(d, hn::Not(hn::Eq(hn::LoadU(du, primitive), hn::Set(du, 0xffffffffu)))));
  const M background = hn::AndNot(covered, valid);
  V3<V> radiance{hn::Zero(d), hn::Zero(d), hn::Zero(d)};
  if (!hn::AllFalse(d, covered)) {
    // Zero where not covered: those lanes' arithmetic is discarded, and stays in range.
    const auto load = [&](int field) {
      return hn::IfThenElseZero(covered, hn::LoadU(d, fields[field]));
    };
    const AttributeVectors<V> a{load(0),  load(1),  load(2),  load(3),  load(4),  load(5),
                                load(6),  load(7),  load(8),  load(9),  load(10), load(11),
                                load(12), load(13), load(14), load(15), load(16), load(17),
                                load(18), load(19), load(20), load(21), load(22)};
    radiance = TerrainRadiance(d, ctx, a, covered, work);
  }
  if (!hn::AllFalse(d, background)) {
    radiance = Select3(covered, radiance, BackgroundLanes(ctx, px0, py, background, work));
  }
  const V exposure = hn::Set(d, ctx.p->exposure);
  return Scale3(radiance, exposure);
}

void ShadeRect(const ShadeParams<float>& p, const ShadeResources& r, const ShadingInputs& in,
               int x0, int y0, int width, int height, int stride, float* HWY_RESTRICT rgb,
               ShadeWork& total) {
  const hn::ScalableTag<float> d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  ShadeContext ctx;
  ctx.p = &p;
  if (r.lattice != nullptr) {
    ctx.lattice = view_of(*r.lattice);
  }
  // Gradient mode reads no texture (and the scene's resources hold none).
  for (int layer = 0; p.gradient_enabled == 0 && layer < p.layer_count; ++layer) {
    ctx.textures[layer] = texture_view_of(r.textures[layer]);
  }
  ctx.skybox = skybox_view_of(r.skybox);
  const std::span<const float> spans[kShadeFields] = {in.dx,
                                                      in.dz,
                                                      in.height,
                                                      in.dx_ddx,
                                                      in.dx_ddy,
                                                      in.dz_ddx,
                                                      in.dz_ddy,
                                                      in.height_ddx,
                                                      in.height_ddy,
                                                      in.nx,
                                                      in.ny,
                                                      in.nz,
                                                      in.slope,
                                                      in.water_depth,
                                                      in.sun,
                                                      in.lambert,
                                                      in.drop,
                                                      in.sky,
                                                      in.water_sun,
                                                      in.reflection_r,
                                                      in.reflection_g,
                                                      in.reflection_b,
                                                      in.reflection_weight};
  // The water depth, the sun's share at the water surface and the reflection are not resolved
  // (and may be absent) where no terrain lies under water.
  const bool reads_depth = p.water_enabled && p.terrain_water;
  // Fields read from the constant tail (0, the plane's drop among them; the sun's share 1, the
  // whole disc): absent, or unread.
  const auto absent = [&](int f) {
    return spans[f].empty() ||
           ((f == kDepthField || f == kWaterSunField || f >= kReflectionFields) && !reads_depth);
  };
  constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  HWY_ALIGN float tail[kShadeFields][kMaxLanes] = {};
  std::fill(std::begin(tail[kSunField]), std::end(tail[kSunField]), 1.0f);
  std::fill(std::begin(tail[kSkyField]), std::end(tail[kSkyField]), 1.0f);
  std::fill(std::begin(tail[kWaterSunField]), std::end(tail[kWaterSunField]), 1.0f);
  HWY_ALIGN std::uint32_t tail_primitive[kMaxLanes] = {};
  HWY_ALIGN float out[3 * kMaxLanes];
  ShadeWork work;
  for (int j = 0; j < height; ++j) {
    const int py = y0 + j;
    for (int i = 0; i < width; i += lanes) {
      const std::size_t k = static_cast<std::size_t>(j) * stride + i;
      const int count = width - i < lanes ? width - i : lanes;
      const float* fields[kShadeFields];
      const std::uint32_t* primitive;
      if (count == lanes) {
        for (int f = 0; f < kShadeFields; ++f) {
          fields[f] = absent(f) ? tail[f] : spans[f].data() + k;
        }
        primitive = in.primitive.data() + k;
      } else {
        // The last pixels of the row: copies, the lanes past the rectangle not valid.
        for (int f = 0; f < kShadeFields; ++f) {
          if (absent(f)) {
            fields[f] = tail[f];
            continue;
          }
          for (int t = 0; t < count; ++t) {
            tail[f][t] = spans[f][k + t];
          }
          fields[f] = tail[f];
        }
        for (int t = 0; t < count; ++t) {
          tail_primitive[t] = in.primitive[k + t];
        }
        primitive = tail_primitive;
      }
      const V3<hn::Vec<decltype(d)>> c =
          ShadeVector(d, ctx, primitive, fields, hn::FirstN(d, static_cast<std::size_t>(count)),
                      x0 + i, py, work);
      if (count == lanes) {
        hn::StoreInterleaved3(c.x, c.y, c.z, d, rgb + 3 * k);
      } else {
        hn::StoreInterleaved3(c.x, c.y, c.z, d, out);
        for (int t = 0; t < 3 * count; ++t) {
          rgb[3 * k + static_cast<std::size_t>(t)] = out[t];
        }
      }
    }
  }
  total += work;
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
