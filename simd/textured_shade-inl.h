// Per-target stage-8 pieces of simd/shade-inl.h for shading.mode = textures (core/shade.cc):
// what the kernel reads per pixel and besides, the proto-texture samples of the layers, and
// the per-pixel light (Scape). Each function mirrors its scalar namesake operation by operation.
#if defined(RELIEF_SIMD_TEXTURED_SHADE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_TEXTURED_SHADE_INL_H_
#undef RELIEF_SIMD_TEXTURED_SHADE_INL_H_
#else
#define RELIEF_SIMD_TEXTURED_SHADE_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/limits.h"
#include "core/shade.h"
#include "core/stage_params.h"
#include "simd/det_math-inl.h"
#include "simd/lattice-inl.h"
#include "simd/layer_weights-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/skybox-inl.h"
#include "simd/texture-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// shade.cc's thresholds, rounded to float as Real(...) rounds them there.
constexpr double kShadeMinProjectionWeight = 0.01;
constexpr double kShadeMinLayerWeight = 1e-3;

// The per-pixel fields ShadeRect reads, in AttributeVectors' order; ten may be absent (the
// reflection's four from kReflectionFields on).
constexpr int kShadeFields = 23, kDepthField = 13, kSunField = 14, kLambertField = 15,
              kDropField = 16, kSkyField = 17, kWaterSunField = 18, kReflectionFields = 19;

// What the kernel reads besides the pixels: the parameters and the resources' views.
struct ShadeContext {
  const ShadeParams<float>* p = nullptr;
  LatticeView lattice{};
  SkyboxView skybox{};
  TextureView textures[limits::kMaxMaterialLayers];
};

// PixelAttributes<float> with one pixel per lane.
template <class V>
struct AttributeVectors {
  V dx, dz, height;
  V dx_ddx, dx_ddy, dz_ddx, dz_ddy, height_ddx, height_ddy;
  V nx, ny, nz;
  V slope, water_depth;
  V sun;        // the sun disc's visible share (1 without cast shadows)
  V lambert;    // gradient mode's interpolated per-vertex Lambert term (0 otherwise)
  V drop;       // a planet's curvature drop (0 on the plane)
  V sky;        // the sky's open share (1 without sky light)
  V water_sun;  // the sun's share at the water surface in front (1 without cast shadows)
  // The terrain reflected there and its weight (0 without reflections: core/water_reflection.h)
  V reflection_r, reflection_g, reflection_b, reflection_weight;
};

// sample (shade.cc): texture_lod at level 0's size (nearest_mip_lod's level where the frame
// filters with the nearest level), then sample_trilinear.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> SampleTexture(D d, const TextureView& t, bool nearest_mip, V u, V v, V dudx,
                               V dvdx, V dudy, V dvdy, M active) {
  V lod = TextureLod(d, t.size0, dudx, dvdx, dudy, dvdy);
  if (nearest_mip) {
    // nearest_mip_lod: lod > 1/2 ? ceil(lod - 1/2) : 0 (NaN: 0).
    const V half = hn::Set(d, 0.5f);
    lod = hn::IfThenElseZero(hn::Gt(lod, half), hn::Ceil(hn::Sub(lod, half)));
  }
  return SampleTrilinear(d, t, u, v, lod, active);
}

// layer_albedo (shade.cc) for the lanes of `gate`; counts the texture fetches of those lanes.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> LayerAlbedo(D d, const ShadeParams<float>& p, const LayerParams<float>& l,
                             const TextureView& texture, const AttributeVectors<V>& a,
                             const V3<V>& n, M gate, ShadeWork& work) {
  const V inv = hn::Set(d, l.inv_tile);
  const V x = hn::Add(hn::Set(d, l.offset_x), hn::Mul(a.dx, inv));
  const V z = hn::Add(hn::Set(d, l.offset_z), hn::Mul(a.dz, inv));
  const V xdx = hn::Mul(a.dx_ddx, inv), xdy = hn::Mul(a.dx_ddy, inv);
  const V zdx = hn::Mul(a.dz_ddx, inv), zdy = hn::Mul(a.dz_ddy, inv);
  if (!p.triplanar) {
    work.texture_fetches += hn::CountTrue(d, gate);
    return SampleTexture(d, texture, p.nearest_mip != 0, x, z, xdx, zdx, xdy, zdy, gate);
  }
  const V y = hn::Add(hn::Set(d, l.offset_y), hn::Mul(a.height, inv));
  const V ydx = hn::Mul(a.height_ddx, inv), ydy = hn::Mul(a.height_ddy, inv);
  // Squared-normal weights; below the threshold a projection's weight is 0.
  const V zero = hn::Zero(d);
  const V threshold = hn::Set(d, float(kShadeMinProjectionWeight));
  V w[3] = {hn::Mul(n.x, n.x), hn::Mul(n.y, n.y), hn::Mul(n.z, n.z)};
  V used = zero;
  for (V& weight : w) {
    weight = hn::IfThenZeroElse(hn::Lt(weight, threshold), weight);
    used = hn::Add(used, weight);
  }
  V3<V> sum{zero, zero, zero};
  for (int axis = 0; axis < 3; ++axis) {
    const M sampled = p.skip_zero_weights ? hn::And(gate, hn::Gt(w[axis], zero)) : gate;
    const std::size_t count = hn::CountTrue(d, sampled);
    work.texture_fetches += count;
    if (count == 0) {
      continue;
    }
    V3<V> c;
    if (axis == 0) {
      c = SampleTexture(d, texture, p.nearest_mip != 0, z, y, zdx, ydx, zdy, ydy, sampled);
    } else if (axis == 1) {
      c = SampleTexture(d, texture, p.nearest_mip != 0, x, z, xdx, zdx, xdy, zdy, sampled);
    } else {
      c = SampleTexture(d, texture, p.nearest_mip != 0, x, y, xdx, ydx, xdy, ydy, sampled);
    }
    sum = Select3(sampled, Add3(sum, Scale3(c, w[axis])), sum);
  }
  return Scale3(sum, hn::Div(hn::Set(d, 1.0f), used));
}

// facing_normal (shade.cc) for the lanes of `covered`.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> FacingNormal(D d, const V3<V>& n, const V3<V>& view, M covered, ShadeWork& work) {
  const V away = Dot3(n, view);
  const M turned = hn::And(covered, hn::Gt(away, hn::Zero(d)));
  const std::size_t count = hn::CountTrue(d, turned);
  if (count == 0) {
    return n;
  }
  work.facing_normals += count;
  const V3<V> toward_eye{hn::Neg(view.x), hn::Neg(view.y), hn::Neg(view.z)};
  return Select3(turned, NormalizeOr(d, Sub3(n, Scale3(view, away)), toward_eye), n);
}

// light (shade.cc) for the lanes of `covered`.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> Light(D d, const ShadeParams<float>& p, const V3<V>& albedo, const V3<V>& n,
                       const V3<V>& view, V specular, V sun_share, V sky_share, M covered,
                       ShadeWork& work) {
  const V zero = hn::Zero(d);
  const V3<V> to_sun = Set3(d, p.sun_direction);
  const V3<V> sun = Set3(d, p.sun);
  const V ndl = StdMax(zero, Dot3(n, to_sun));
  const V sunlit = hn::Mul(ndl, sun_share);
  const V half = hn::Set(d, 0.5f);
  const V3<V> hemisphere = Mix3(Set3(d, p.ground_light), Set3(d, p.sky_light),
                                hn::Mul(hn::Add(half, hn::Mul(half, n.y)), sky_share));
  const V ambient = hn::Set(d, p.ambient);
  V3<V> radiance =
      Mul3(albedo, Add3(Add3(Scale3(sun, sunlit), hemisphere), V3<V>{ambient, ambient, ambient}));
  const M wanted = p.always_specular ? covered : hn::And(covered, hn::Gt(specular, zero));
  const M specular_lanes = hn::And(wanted, hn::Gt(sunlit, zero));
  const std::size_t count = hn::CountTrue(d, specular_lanes);
  work.specular_pixels += count;
  if (count == 0) {
    return radiance;
  }
  const V3<V> reflected = Sub3(Scale3(n, hn::Mul(hn::Set(d, 2.0f), ndl)), to_sun);
  const V rv = hn::Neg(Dot3(reflected, view));
  const M lit = hn::And(specular_lanes, hn::Gt(rv, zero));  // log's domain
  if (hn::AllFalse(d, lit)) {
    return radiance;
  }
  const V term = hn::Mul(hn::Mul(specular, sun_share),
                         Exp2Det(d, hn::Mul(hn::Set(d, p.shininess), Log2Det(d, rv))));
  return Select3(lit, Add3(radiance, Scale3(sun, term)), radiance);
}

// The proto-texture part of terrain_radiance (shade.cc, textured_radiance) for the lanes of
// `covered`: the layers' albedo, lit per pixel.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> TexturedRadiance(D d, const ShadeContext& ctx, const AttributeVectors<V>& a,
                                  V distance, const V3<V>& view, M covered, ShadeWork& work) {
  const ShadeParams<float>& p = *ctx.p;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const V relative_y = a.height;
  const V3<V> n = NormalizeOr(d, V3<V>{a.nx, a.ny, a.nz}, V3<V>{zero, one, zero});

  // Dithered transitions, faded out with the footprint.
  V dither_offset = zero;
  const V inv = hn::Set(d, p.dither_inv_scale);
  const V two = hn::Set(d, 2.0f);
  const V dither_fade = StdMin(
      one, hn::Sub(two, hn::Mul(hn::Mul(hn::Mul(two, distance), hn::Set(d, p.pixel_angle)), inv)));
  if (p.dither_enabled) {
    const M dithered = hn::And(covered, hn::Gt(dither_fade, zero));
    const std::size_t count = hn::CountTrue(d, dithered);
    if (count != 0) {
      const V noise = SampleLattice<Interpolant::kCubic>(
          d, ctx.lattice, hn::Set(d, ctx.lattice.period), hn::Set(d, ctx.lattice.inv_period),
          hn::Add(hn::Set(d, p.dither_offset_x), hn::Mul(a.dx, inv)),
          hn::Add(hn::Set(d, p.dither_offset_z), hn::Mul(a.dz, inv)));
      dither_offset = hn::IfThenElseZero(
          dithered, hn::Mul(hn::Mul(hn::Set(d, p.dither_half_amount), noise), dither_fade));
      work.dither_samples += count;
    }
  }
  V weights[limits::kMaxMaterialLayers];
  LayerWeights(d, p, relative_y, a.slope, dither_offset, weights);
  V3<V> albedo{zero, zero, zero};
  V specular = zero, used = zero;
  const V min_weight = hn::Set(d, float(kShadeMinLayerWeight));
  for (int layer = 0; layer < p.layer_count; ++layer) {
    const M negligible = hn::Lt(weights[layer], min_weight);
    const V w = hn::IfThenZeroElse(negligible, weights[layer]);
    // Skipped (p.skip_zero_weights), a zero-weight layer costs no fetch and adds nothing.
    const M gate = p.skip_zero_weights ? hn::AndNot(negligible, covered) : covered;
    if (hn::AllFalse(d, gate)) {
      continue;
    }
    const V3<V> layer_albedo =
        LayerAlbedo(d, p, p.layers[layer], ctx.textures[layer], a, n, gate, work);
    albedo = Select3(gate, Add3(albedo, Scale3(layer_albedo, w)), albedo);
    specular = hn::IfThenElse(
        gate, hn::Add(specular, hn::Mul(hn::Set(d, p.layers[layer].specular), w)), specular);
    used = hn::IfThenElse(gate, hn::Add(used, w), used);
  }
  albedo = Scale3(albedo, hn::Div(one, used));
  return Light(d, p, albedo, FacingNormal(d, n, view, covered, work), view, hn::Div(specular, used),
               a.sun, a.sky, covered, work);
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
