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
#include "simd/background_rays-inl.h"
#include "simd/det_math-inl.h"
#include "simd/lattice-inl.h"
#include "simd/layer_weights-inl.h"
#include "simd/shade_vec3-inl.h"
#include "simd/sky-inl.h"
#include "simd/texture-inl.h"
#include "simd/water-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// shade.cc's thresholds, rounded to float as Real(...) rounds them there.
constexpr double kShadeMinProjectionWeight = 0.01;
constexpr double kShadeMinLayerWeight = 1e-3;

// The per-pixel fields ShadeRect reads, in AttributeVectors' order; two may be absent.
constexpr int kShadeFields = 15, kDepthField = 13, kSunField = 14;

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
  V sun;  // the sun disc's visible share (1 without cast shadows)
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
                       const V3<V>& view, V specular, V sun_share, M covered, ShadeWork& work) {
  const V zero = hn::Zero(d);
  const V3<V> to_sun = Set3(d, p.sun_direction);
  const V3<V> sun = Set3(d, p.sun);
  const V ndl = StdMax(zero, Dot3(n, to_sun));
  const V sunlit = hn::Mul(ndl, sun_share);
  const V half = hn::Set(d, 0.5f);
  const V3<V> hemisphere =
      Mix3(Set3(d, p.ground_light), Set3(d, p.sky_light), hn::Add(half, hn::Mul(half, n.y)));
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

// surface_footprint (shade.cc): distance pixel_angle / max(|view.y|, 0.05).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SurfaceFootprint(D d, const ShadeParams<float>& p, V distance, V view_y) {
  return hn::Div(hn::Mul(distance, hn::Set(d, p.pixel_angle)),
                 StdMax(hn::Abs(view_y), hn::Set(d, float(0.05))));
}

// terrain_radiance (shade.cc) for the lanes of `covered`, whose attributes are `a`.
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> TerrainRadiance(D d, const ShadeContext& ctx, const AttributeVectors<V>& a,
                                 M covered, ShadeWork& work) {
  const ShadeParams<float>& p = *ctx.p;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  work.terrain_pixels += hn::CountTrue(d, covered);
  const V relative_y = a.height;
  const V3<V> position{a.dx, relative_y, a.dz};
  const V length_sq = Dot3(position, position);
  const V distance = hn::Sqrt(length_sq);
  const V3<V> view = NormalizeOrWith(d, position, length_sq, Set3(d, p.camera_forward));
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
  V3<V> radiance = Light(d, p, albedo, FacingNormal(d, n, view, covered, work), view,
                         hn::Div(specular, used), a.sun, covered, work);

  V fog_distance = distance;
  if (p.water_enabled && p.terrain_water) {
    const V level = hn::Set(d, p.water_level);
    const M under_water =
        hn::And(covered, hn::And(hn::Lt(relative_y, level), hn::Lt(view.y, zero)));
    const std::size_t count = hn::CountTrue(d, under_water);
    if (count != 0) {
      const V surface = hn::Div(level, view.y);
      const V footprint = SurfaceFootprint(d, p, surface, view.y);
      const V3<V> water = ShadeWater(d, p, ctx.lattice, ctx.skybox, view, surface,
                                     StdMax(zero, a.water_depth), radiance, footprint, under_water);
      radiance = Select3(under_water, water, radiance);
      fog_distance = hn::IfThenElse(under_water, surface, distance);
      work.water_pixels += count;
    }
  }
  if (!p.fog_enabled) {
    return radiance;
  }
  work.fogged_pixels += hn::CountTrue(d, covered);
  return ApplyFog(d, p, radiance, view, fog_distance);
}

// background_radiance (shade.cc) for the lanes of `background`, pixels (px0 + lane, py).
template <class D, class V = hn::Vec<D>, class M = hn::Mask<D>>
HWY_INLINE V3<V> BackgroundRadiance(D d, const ShadeContext& ctx, int px0, int py, M background,
                                    ShadeWork& work) {
  const ShadeParams<float>& p = *ctx.p;
  const V zero = hn::Zero(d);
  work.background_pixels += hn::CountTrue(d, background);
  const V3<V> dir = NormalizeOr(d, BackgroundRays(d, p, px0, py), Set3(d, p.camera_forward));
  const M below = hn::Lt(dir.y, zero);
  const M below_lanes = hn::And(background, below);
  V3<V> result{zero, zero, zero};
  if (!hn::AllFalse(d, hn::AndNot(below, background))) {
    result = SkyRadiance(d, p, ctx.skybox, dir);
  }
  const std::size_t count = hn::CountTrue(d, below_lanes);
  if (count == 0) {
    return result;
  }
  V3<V> ground;
  if (p.water_enabled) {
    const V surface = hn::Div(hn::Set(d, p.water_level), dir.y);
    const V footprint = SurfaceFootprint(d, p, surface, dir.y);
    ground = ShadeWater(d, p, ctx.lattice, ctx.skybox, dir, surface, hn::Set(d, 1e6f),
                        V3<V>{zero, zero, zero}, footprint, below_lanes);
    work.water_pixels += count;
    if (p.fog_enabled) {
      work.fogged_pixels += count;
      ground = ApplyFog(d, p, ground, dir, surface);
    }
  } else {
    ground = FogColor(d, p, dir);
  }
  return Select3(below, ground, result);
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
    const AttributeVectors<V> a{load(0),  load(1),  load(2),  load(3),  load(4),
                                load(5),  load(6),  load(7),  load(8),  load(9),
                                load(10), load(11), load(12), load(13), load(14)};
    radiance = TerrainRadiance(d, ctx, a, covered, work);
  }
  if (!hn::AllFalse(d, background)) {
    radiance = Select3(covered, radiance, BackgroundRadiance(d, ctx, px0, py, background, work));
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
  for (int layer = 0; layer < p.layer_count; ++layer) {
    ctx.textures[layer] = texture_view_of(r.textures[layer]);
  }
  ctx.skybox = skybox_view_of(r.skybox);
  const std::span<const float> spans[kShadeFields] = {
      in.dx,     in.dz,     in.height,     in.dx_ddx,      in.dx_ddy,
      in.dz_ddx, in.dz_ddy, in.height_ddx, in.height_ddy,  in.nx,
      in.ny,     in.nz,     in.slope,      in.water_depth, in.sun};
  // The water depth is not resolved (and may be absent) where no terrain lies under water.
  const bool reads_depth = p.water_enabled && p.terrain_water;
  // Fields read from the constant tail (0; the sun's share 1, the whole disc): absent, or unread.
  const auto absent = [&](int f) { return spans[f].empty() || (f == kDepthField && !reads_depth); };
  constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  HWY_ALIGN float tail[kShadeFields][kMaxLanes] = {};
  std::fill(std::begin(tail[kSunField]), std::end(tail[kSunField]), 1.0f);
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
