// Per-target body of simd/vertex_outcodes.h: per vertex, the five frustum planes tested
// against the vertical segment [h_lo, h_hi] (or the point h) as core/vertex_culling.cc tests
// them; std::max(a, b) is (a < b ? b : a), here as there.
#if defined(RELIEF_SIMD_VERTEX_OUTCODES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_VERTEX_OUTCODES_INL_H_
#undef RELIEF_SIMD_VERTEX_OUTCODES_INL_H_
#else
#define RELIEF_SIMD_VERTEX_OUTCODES_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "core/frame_plan.h"
#include "core/vertex_culling.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

void VertexOutcodes(const CullParams<float>& p, RowRange rows, const float* HWY_RESTRICT dx,
                    const float* HWY_RESTRICT dz, const float* HWY_RESTRICT height,
                    const std::uint8_t* HWY_RESTRICT valid, std::uint8_t* HWY_RESTRICT outcode) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::Rebind<std::uint8_t, decltype(d)> d8;
  using V = hn::Vec<decltype(d)>;
  constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  const std::size_t lanes = hn::Lanes(d);
  const bool bounds = height == nullptr;
  V normal[5][3];
  V offset[5];
  for (int plane = 0; plane < 5; ++plane) {
    for (int c = 0; c < 3; ++c) {
      normal[plane][c] = hn::Set(d, p.plane[plane][c]);
    }
    offset[plane] = hn::Set(d, plane == 4 ? p.near : 0.0f);
  }
  const V tolerance = hn::Set(d, p.tolerance), near = hn::Set(d, p.near);
  const V bound_lo = hn::Set(d, p.height_lo), bound_hi = hn::Set(d, p.height_hi);
  const auto all_outside = hn::Set(di, 0x1f);
  const auto width = hn::Set(di, p.width);
  // Larger of a and b as std::max(a, b) picks it.
  const auto larger = [](V a, V b) { return hn::IfThenElse(hn::Lt(a, b), b, a); };
  for (int j = rows.begin; j < rows.end; ++j) {
    const std::size_t row = static_cast<std::size_t>(j) * p.pitch;
    for (int i = 0; i < p.pitch; i += static_cast<int>(lanes)) {
      const std::size_t k = row + static_cast<std::size_t>(i);
      const std::size_t count = std::min<std::size_t>(lanes, static_cast<std::size_t>(p.pitch - i));
      const bool whole = count == lanes;
      HWY_ALIGN float in[3][kMaxLanes] = {};
      HWY_ALIGN std::uint8_t flags[kMaxLanes] = {};
      if (!whole) {
        for (std::size_t l = 0; l < count; ++l) {
          in[0][l] = dx[k + l];
          in[1][l] = dz[k + l];
          in[2][l] = bounds ? 0.0f : height[k + l];
          flags[l] = valid[k + l];
        }
      }
      const V x = whole ? hn::LoadU(d, dx + k) : hn::Load(d, in[0]);
      const V z = whole ? hn::LoadU(d, dz + k) : hn::Load(d, in[1]);
      V h_lo = bound_lo, h_hi = bound_hi;
      if (!bounds) {
        h_lo = h_hi = whole ? hn::LoadU(d, height + k) : hn::Load(d, in[2]);
      }
      const V margin = hn::Mul(tolerance, hn::Add(hn::Add(hn::Add(hn::Abs(x), hn::Abs(z)),
                                                          larger(hn::Abs(h_lo), hn::Abs(h_hi))),
                                                  near));
      const V below = hn::Neg(margin);
      auto code = hn::Zero(di);
      for (int plane = 0; plane < 5; ++plane) {
        const V flat = hn::Sub(hn::Add(hn::Mul(normal[plane][0], x), hn::Mul(normal[plane][2], z)),
                               offset[plane]);
        const V lo = hn::Add(flat, hn::Mul(normal[plane][1], h_lo));
        const V hi = hn::Add(flat, hn::Mul(normal[plane][1], h_hi));
        const auto outside = hn::RebindMask(di, hn::Lt(larger(lo, hi), below));
        code = hn::Or(code, hn::IfThenElseZero(outside, hn::Set(di, 1 << plane)));
      }
      // Columns past the width and invalid vertices: every plane outside.
      const auto column = hn::Add(hn::Set(di, i), hn::Iota(di, 0));
      const auto is_valid = hn::Ne(
          hn::PromoteTo(di, whole ? hn::LoadU(d8, valid + k) : hn::Load(d8, flags)), hn::Zero(di));
      code = hn::IfThenElse(hn::And(is_valid, hn::Lt(column, width)), code, all_outside);
      HWY_ALIGN std::uint8_t out[kMaxLanes];
      hn::Store(hn::DemoteTo(d8, code), d8, out);
      for (std::size_t l = 0; l < count; ++l) {
        outcode[k + l] = out[l];
      }
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
