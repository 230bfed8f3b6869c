// Per-target body of simd/vertex_transform.h: x = (r0 px + r1 py) + r2 pz per clip row, and
// zeros where no drawn triangle needs the vertex (core/vertex_culling.h, kDraw); gradient
// mode's per-vertex Lambert term likewise.
#if defined(RELIEF_SIMD_VERTEX_TRANSFORM_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_VERTEX_TRANSFORM_INL_H_
#undef RELIEF_SIMD_VERTEX_TRANSFORM_INL_H_
#else
#define RELIEF_SIMD_VERTEX_TRANSFORM_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/stage_params.h"
#include "core/vertex_culling.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

void TransformVertices(const TransformParams<float>& t, IndexRange range,
                       const float* HWY_RESTRICT dx, const float* HWY_RESTRICT dz,
                       const float* HWY_RESTRICT height, const std::uint8_t* HWY_RESTRICT need,
                       float* HWY_RESTRICT x, float* HWY_RESTRICT y, float* HWY_RESTRICT z,
                       float* HWY_RESTRICT w) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const V x0 = hn::Set(d, t.row_x[0]), x1 = hn::Set(d, t.row_x[1]), x2 = hn::Set(d, t.row_x[2]);
  const V y0 = hn::Set(d, t.row_y[0]), y1 = hn::Set(d, t.row_y[1]), y2 = hn::Set(d, t.row_y[2]);
  const V w0 = hn::Set(d, t.row_w[0]), w1 = hn::Set(d, t.row_w[1]), w2 = hn::Set(d, t.row_w[2]);
  const V z_clip = hn::Set(d, t.z_clip);
  const auto draw_bit = hn::Set(di, kDraw);
  const auto one_vector = [&](std::size_t k, std::size_t count) {
    HWY_ALIGN float in[3][HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN std::uint8_t flags[HWY_MAX_BYTES / sizeof(float)] = {};
    const bool whole = count == lanes;
    if (!whole) {
      for (std::size_t l = 0; l < count; ++l) {
        in[0][l] = dx[k + l];
        in[1][l] = height[k + l];
        in[2][l] = dz[k + l];
        flags[l] = need == nullptr ? std::uint8_t(kDraw) : need[k + l];
      }
    }
    const V px = whole ? hn::LoadU(d, dx + k) : hn::Load(d, in[0]);
    const V py = whole ? hn::LoadU(d, height + k) : hn::Load(d, in[1]);
    const V pz = whole ? hn::LoadU(d, dz + k) : hn::Load(d, in[2]);
    auto drawn = hn::FirstN(d, count);
    if (need != nullptr || !whole) {
      const auto bits = hn::PromoteTo(di, whole ? hn::LoadU(d8, need + k) : hn::Load(d8, flags));
      drawn = hn::RebindMask(d, hn::Ne(hn::And(bits, draw_bit), hn::Zero(di)));
    }
    const V cx = hn::Add(hn::Add(hn::Mul(x0, px), hn::Mul(x1, py)), hn::Mul(x2, pz));
    const V cy = hn::Add(hn::Add(hn::Mul(y0, px), hn::Mul(y1, py)), hn::Mul(y2, pz));
    const V cw = hn::Add(hn::Add(hn::Mul(w0, px), hn::Mul(w1, py)), hn::Mul(w2, pz));
    HWY_ALIGN float out[4][HWY_MAX_BYTES / sizeof(float)];
    float* targets[4] = {x, y, z, w};
    const V values[4] = {hn::IfThenElseZero(drawn, cx), hn::IfThenElseZero(drawn, cy),
                         hn::IfThenElseZero(drawn, z_clip), hn::IfThenElseZero(drawn, cw)};
    for (int c = 0; c < 4; ++c) {
      if (whole) {
        hn::StoreU(values[c], d, targets[c] + k);
      } else {
        hn::Store(values[c], d, out[c]);
        for (std::size_t l = 0; l < count; ++l) {
          targets[c][k + l] = out[c][l];
        }
      }
    }
  };
  std::size_t k = range.begin;
  for (; k + lanes <= range.end; k += lanes) {
    one_vector(k, lanes);
  }
  if (k < range.end) {
    one_vector(k, range.end - k);
  }
}

// light_vertices (core/vertex_transform.h): lambert = ndl > 0 ? ndl : 0 with
// ndl = (nx sun_x + ny sun_y) + nz sun_z, and 0 where no drawn triangle needs the vertex.
void LightVertices(const TransformParams<float>& t, IndexRange range, const float* HWY_RESTRICT nx,
                   const float* HWY_RESTRICT ny, const float* HWY_RESTRICT nz,
                   const std::uint8_t* HWY_RESTRICT need, float* HWY_RESTRICT lambert) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const V sun_x = hn::Set(d, t.sun_x), sun_y = hn::Set(d, t.sun_y), sun_z = hn::Set(d, t.sun_z);
  const auto draw_bit = hn::Set(di, kDraw);
  const auto one_vector = [&](std::size_t k, std::size_t count) {
    HWY_ALIGN float in[3][HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN std::uint8_t flags[HWY_MAX_BYTES / sizeof(float)] = {};
    HWY_ALIGN float out[HWY_MAX_BYTES / sizeof(float)];
    const bool whole = count == lanes;
    if (!whole) {
      for (std::size_t l = 0; l < count; ++l) {
        in[0][l] = nx[k + l];
        in[1][l] = ny[k + l];
        in[2][l] = nz[k + l];
        flags[l] = need == nullptr ? std::uint8_t(kDraw) : need[k + l];
      }
    }
    const V x = whole ? hn::LoadU(d, nx + k) : hn::Load(d, in[0]);
    const V y = whole ? hn::LoadU(d, ny + k) : hn::Load(d, in[1]);
    const V z = whole ? hn::LoadU(d, nz + k) : hn::Load(d, in[2]);
    auto drawn = hn::FirstN(d, count);
    if (need != nullptr || !whole) {
      const auto bits = hn::PromoteTo(di, whole ? hn::LoadU(d8, need + k) : hn::Load(d8, flags));
      drawn = hn::RebindMask(d, hn::Ne(hn::And(bits, draw_bit), hn::Zero(di)));
    }
    const V ndl = hn::Add(hn::Add(hn::Mul(x, sun_x), hn::Mul(y, sun_y)), hn::Mul(z, sun_z));
    const V value = hn::IfThenElseZero(hn::And(drawn, hn::Gt(ndl, hn::Zero(d))), ndl);
    if (whole) {
      hn::StoreU(value, d, lambert + k);
    } else {
      hn::Store(value, d, out);
      for (std::size_t l = 0; l < count; ++l) {
        lambert[k + l] = out[l];
      }
    }
  };
  std::size_t k = range.begin;
  for (; k + lanes <= range.end; k += lanes) {
    one_vector(k, lanes);
  }
  if (k < range.end) {
    one_vector(k, range.end - k);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
