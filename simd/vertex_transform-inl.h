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
#include "simd/vertex_vectors-inl.h"

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
  using V = hn::Vec<decltype(d)>;
  const V x0 = hn::Set(d, t.row_x[0]), x1 = hn::Set(d, t.row_x[1]), x2 = hn::Set(d, t.row_x[2]);
  const V y0 = hn::Set(d, t.row_y[0]), y1 = hn::Set(d, t.row_y[1]), y2 = hn::Set(d, t.row_y[2]);
  const V w0 = hn::Set(d, t.row_w[0]), w1 = hn::Set(d, t.row_w[1]), w2 = hn::Set(d, t.row_w[2]);
  const V z_clip = hn::Set(d, t.z_clip);
  const float* const inputs[3] = {dx, height, dz};
  float* const outputs[4] = {x, y, z, w};
  ForEachVertexVector(
      range, inputs, need, kDraw, outputs, [&](const auto drawn, const V(&p)[3], V(&clip)[4]) {
        const V cx = hn::Add(hn::Add(hn::Mul(x0, p[0]), hn::Mul(x1, p[1])), hn::Mul(x2, p[2]));
        const V cy = hn::Add(hn::Add(hn::Mul(y0, p[0]), hn::Mul(y1, p[1])), hn::Mul(y2, p[2]));
        const V cw = hn::Add(hn::Add(hn::Mul(w0, p[0]), hn::Mul(w1, p[1])), hn::Mul(w2, p[2]));
        clip[0] = hn::IfThenElseZero(drawn, cx);
        clip[1] = hn::IfThenElseZero(drawn, cy);
        clip[2] = hn::IfThenElseZero(drawn, z_clip);
        clip[3] = hn::IfThenElseZero(drawn, cw);
      });
}

// light_vertices (core/vertex_transform.h): lambert = ndl > 0 ? ndl : 0 with
// ndl = (nx sun_x + ny sun_y) + nz sun_z, and 0 where no drawn triangle needs the vertex.
void LightVertices(const TransformParams<float>& t, IndexRange range, const float* HWY_RESTRICT nx,
                   const float* HWY_RESTRICT ny, const float* HWY_RESTRICT nz,
                   const std::uint8_t* HWY_RESTRICT need, float* HWY_RESTRICT lambert) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const V sun_x = hn::Set(d, t.sun_x), sun_y = hn::Set(d, t.sun_y), sun_z = hn::Set(d, t.sun_z);
  const float* const inputs[3] = {nx, ny, nz};
  float* const outputs[1] = {lambert};
  ForEachVertexVector(
      range, inputs, need, kDraw, outputs, [&](const auto drawn, const V(&n)[3], V(&out)[1]) {
        const V ndl =
            hn::Add(hn::Add(hn::Mul(n[0], sun_x), hn::Mul(n[1], sun_y)), hn::Mul(n[2], sun_z));
        out[0] = hn::IfThenElseZero(hn::And(drawn, hn::Gt(ndl, hn::Zero(d))), ndl);
      });
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
