// Per-target body of simd/planet_bend.h: bend_vertices and bend_normals (core/planet_bend.cc)
// for float, one vertex per lane, sin_cos_det and sin_det through simd/det_trig-inl.h; the
// scalar branches (an invalid vertex, theta 0, the nadir's undefined direction) as masks.
#if defined(RELIEF_SIMD_PLANET_BEND_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_PLANET_BEND_INL_H_
#undef RELIEF_SIMD_PLANET_BEND_INL_H_
#else
#define RELIEF_SIMD_PLANET_BEND_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/planet_plan.h"
#include "simd/det_trig-inl.h"
#include "simd/vertex_vectors-inl.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

void BendVertices(const PlanetParams<float>& p, IndexRange range, const float* HWY_RESTRICT dx,
                  const float* HWY_RESTRICT dz, const float* HWY_RESTRICT height,
                  const std::uint8_t* HWY_RESTRICT valid, float* HWY_RESTRICT x,
                  float* HWY_RESTRICT y, float* HWY_RESTRICT z, float* HWY_RESTRICT drop) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const float* const inputs[3] = {dx, dz, height};
  float* const outputs[4] = {x, y, z, drop};
  ForEachVertexVector(
      range, inputs, valid, std::uint8_t(0xff), outputs, [&](auto ok, const V(&in)[3], V(&out)[4]) {
        const V rho = hn::Sqrt(hn::Add(hn::Mul(in[0], in[0]), hn::Mul(in[1], in[1])));
        const V theta = hn::Mul(rho, hn::Set(d, p.inv_radius));
        V sine, cosine, half_sine, half_cosine;
        SinCosLanes(d, theta, sine, cosine);
        // sinc: 1 at 0 (the limit); the division's domain: theta > 0.
        const auto positive = hn::Gt(theta, zero);
        const V sinc =
            hn::IfThenElse(positive, hn::Div(sine, hn::IfThenElse(positive, theta, one)), one);
        SinCosLanes(d, hn::Mul(theta, hn::Set(d, 0.5f)), half_sine, half_cosine);
        const V radius_here = hn::Add(hn::Set(d, p.center_distance), in[2]);
        const V scale = hn::Mul(hn::Mul(radius_here, hn::Set(d, p.inv_radius)), sinc);
        const V bend_drop =
            hn::Mul(radius_here, hn::Mul(hn::Mul(hn::Set(d, 2.0f), half_sine), half_sine));
        out[0] = hn::IfThenElseZero(ok, hn::Mul(in[0], scale));
        out[1] = hn::IfThenElseZero(ok, hn::Sub(in[2], bend_drop));
        out[2] = hn::IfThenElseZero(ok, hn::Mul(in[1], scale));
        out[3] = hn::IfThenElseZero(ok, bend_drop);
      });
}

void BendNormals(const PlanetParams<float>& p, IndexRange range, const float* HWY_RESTRICT dx,
                 const float* HWY_RESTRICT dz, const std::uint8_t* HWY_RESTRICT valid,
                 float* HWY_RESTRICT nx, float* HWY_RESTRICT ny, float* HWY_RESTRICT nz) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const float* const inputs[5] = {dx, dz, nx, ny, nz};
  float* const outputs[3] = {nx, ny, nz};
  ForEachVertexVector(
      range, inputs, valid, std::uint8_t(0xff), outputs, [&](auto ok, const V(&in)[5], V(&out)[3]) {
        const V rho = hn::Sqrt(hn::Add(hn::Mul(in[0], in[0]), hn::Mul(in[1], in[1])));
        // The nadir's frame is the camera's: unchanged where rho is not > 0.
        const auto turned = hn::And(ok, hn::Gt(rho, zero));
        const V theta = hn::Mul(rho, hn::Set(d, p.inv_radius));
        V sine, cosine, half_sine, half_cosine;
        SinCosLanes(d, theta, sine, cosine);
        SinCosLanes(d, hn::Mul(theta, hn::Set(d, 0.5f)), half_sine, half_cosine);
        const V cos_minus_one = hn::Mul(hn::Mul(hn::Set(d, -2.0f), half_sine), half_sine);
        const V safe_rho = hn::IfThenElse(turned, rho, one);  // domain: rho > 0
        const V ux = hn::Div(in[0], safe_rho), uz = hn::Div(in[1], safe_rho);
        const V along = hn::Add(hn::Mul(in[2], ux), hn::Mul(in[4], uz));
        const V n_y = in[3];
        const V delta = hn::Add(hn::Mul(along, cos_minus_one), hn::Mul(n_y, sine));
        out[0] = hn::IfThenElse(turned, hn::Add(in[2], hn::Mul(delta, ux)), in[2]);
        out[2] = hn::IfThenElse(turned, hn::Add(in[4], hn::Mul(delta, uz)), in[4]);
        out[1] = hn::IfThenElse(
            turned, hn::Sub(hn::Add(n_y, hn::Mul(n_y, cos_minus_one)), hn::Mul(along, sine)), n_y);
      });
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
