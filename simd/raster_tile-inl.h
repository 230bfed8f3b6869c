// Per-target body of simd/raster_tile.h. A row's pixels are tested a vector at a time: the
// edge values of lane l are the row's start value plus l steps (exact integers, as the scalar
// loop's running sums), the depth z0 + dzdx px + dzdy py in double clamped to [0, 1] and
// rounded to float, compared with the stored depth as float. A segment that would reach past
// the tile's row is done pixel by pixel with the same arithmetic.
#if defined(RELIEF_SIMD_RASTER_TILE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RELIEF_SIMD_RASTER_TILE_INL_H_
#undef RELIEF_SIMD_RASTER_TILE_INL_H_
#else
#define RELIEF_SIMD_RASTER_TILE_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "simd/raster_tile.h"

HWY_BEFORE_NAMESPACE();
namespace relief::simd {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

constexpr int kTile = 64;
constexpr std::int64_t kSubpixel = 256;

// RasterTriangle::depth.
inline float PixelDepth(const EdgeTriangle& t, int px, int py) {
  const double z = t.z0 + t.dzdx * px + t.dzdy * py;
  return static_cast<float>(z < 0.0 ? 0.0 : (z > 1.0 ? 1.0 : z));
}

// raster's depth_passes.
inline bool Passes(DepthCompare test, float incoming, float stored) {
  switch (test) {
    case DepthCompare::kGreater:
      return incoming > stored;
    case DepthCompare::kGreaterEqual:
      return incoming >= stored;
    case DepthCompare::kLess:
      return incoming < stored;
    case DepthCompare::kLessEqual:
      return incoming <= stored;
    case DepthCompare::kEqual:
      return incoming == stored;
    case DepthCompare::kAlways:
      return true;
    case DepthCompare::kNever:
      return false;
  }
  return false;
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE hn::Mask<D> PassesLanes(D d, DepthCompare test, V incoming, V stored) {
  switch (test) {
    case DepthCompare::kGreater:
      return hn::Gt(incoming, stored);
    case DepthCompare::kGreaterEqual:
      return hn::Ge(incoming, stored);
    case DepthCompare::kLess:
      return hn::Lt(incoming, stored);
    case DepthCompare::kLessEqual:
      return hn::Le(incoming, stored);
    case DepthCompare::kEqual:
      return hn::Eq(incoming, stored);
    case DepthCompare::kAlways:
      return hn::FirstN(d, hn::Lanes(d));
    case DepthCompare::kNever:
      return hn::FirstN(d, 0);
  }
  return hn::FirstN(d, 0);
}

HWY_INLINE void DrawTriangleInTile(const EdgeTriangle& t, DepthCompare test,
                                   const TileBuffers& tile) {
  const hn::ScalableTag<std::int64_t> d64;
  const hn::Rebind<double, decltype(d64)> dd;
  const hn::Rebind<float, decltype(d64)> df;
  const hn::Rebind<std::uint32_t, decltype(d64)> du;
  const int lanes = static_cast<int>(hn::Lanes(d64));
  const std::int64_t step[3] = {std::int64_t{t.a[0]} * kSubpixel, std::int64_t{t.a[1]} * kSubpixel,
                                std::int64_t{t.a[2]} * kSubpixel};
  // Lane l's offset from the segment's first pixel: l steps.
  HWY_ALIGN std::int64_t offsets[3][HWY_MAX_BYTES / sizeof(std::int64_t)];
  for (int e = 0; e < 3; ++e) {
    for (int l = 0; l < lanes; ++l) {
      offsets[e][l] = step[e] * l;
    }
  }
  const auto lane_offset0 = hn::Load(d64, offsets[0]);
  const auto lane_offset1 = hn::Load(d64, offsets[1]);
  const auto lane_offset2 = hn::Load(d64, offsets[2]);
  const auto zero = hn::Zero(d64);
  const auto dzdx = hn::Set(dd, t.dzdx);
  const auto zero_d = hn::Zero(dd), one_d = hn::Set(dd, 1.0);
  for (int py = t.y0; py <= t.y1; ++py) {
    const std::int64_t fx = std::int64_t{t.x0} * kSubpixel;
    const std::int64_t fy = std::int64_t{py} * kSubpixel;
    std::int64_t e0 = t.a[0] * fx + t.b[0] * fy + t.c[0];
    std::int64_t e1 = t.a[1] * fx + t.b[1] * fy + t.c[1];
    std::int64_t e2 = t.a[2] * fx + t.b[2] * fy + t.c[2];
    const std::size_t row = static_cast<std::size_t>(py - tile.y0) * kTile;
    const auto z_row = hn::Set(dd, t.dzdy * py);
    int px = t.x0;
    // Whole vectors inside the tile's row.
    for (; px <= t.x1 && px - tile.x0 + lanes <= kTile; px += lanes) {
      const int count = t.x1 - px + 1 < lanes ? t.x1 - px + 1 : lanes;
      const auto inside = hn::FirstN(d64, static_cast<std::size_t>(count));
      const auto covered =
          hn::And(hn::And(inside, hn::Gt(hn::Add(hn::Set(d64, e0), lane_offset0), zero)),
                  hn::And(hn::Gt(hn::Add(hn::Set(d64, e1), lane_offset1), zero),
                          hn::Gt(hn::Add(hn::Set(d64, e2), lane_offset2), zero)));
      e0 += step[0] * lanes;
      e1 += step[1] * lanes;
      e2 += step[2] * lanes;
      if (hn::AllFalse(d64, covered)) {
        continue;
      }
      // z0 + dzdx px + dzdy py, clamped: (z < 0 ? 0 : (z > 1 ? 1 : z)), then to float.
      const auto z =
          hn::Add(hn::Add(hn::Set(dd, t.z0), hn::Mul(dzdx, hn::Iota(dd, double(px)))), z_row);
      const auto clamped =
          hn::IfThenElse(hn::Lt(z, zero_d), zero_d, hn::IfThenElse(hn::Gt(z, one_d), one_d, z));
      const auto depth = hn::DemoteTo(df, clamped);
      const std::size_t k = row + static_cast<std::size_t>(px - tile.x0);
      const auto stored = hn::LoadU(df, tile.depth + k);
      // The coverage mask in 32-bit lanes: -1 / 0 narrowed from 64 bits.
      const hn::RebindToUnsigned<decltype(d64)> du64;
      const auto covered32 = hn::RebindMask(
          df,
          hn::MaskFromVec(hn::TruncateTo(du, hn::BitCast(du64, hn::VecFromMask(d64, covered)))));
      const auto write = hn::And(covered32, PassesLanes(df, test, depth, stored));
      hn::StoreU(hn::IfThenElse(write, depth, stored), df, tile.depth + k);
      const auto old = hn::LoadU(du, tile.primitive + k);
      hn::StoreU(hn::IfThenElse(hn::RebindMask(du, write), hn::Set(du, t.primitive), old), du,
                 tile.primitive + k);
    }
    // The rest of the row, pixel by pixel (raster::draw_in_tile).
    for (; px <= t.x1; ++px) {
      if ((e0 > 0) & (e1 > 0) & (e2 > 0)) {
        const float depth = PixelDepth(t, px, py);
        const std::size_t k = row + static_cast<std::size_t>(px - tile.x0);
        if (Passes(test, depth, tile.depth[k])) {
          tile.depth[k] = depth;
          tile.primitive[k] = t.primitive;
        }
      }
      e0 += step[0];
      e1 += step[1];
      e2 += step[2];
    }
  }
}

void DrawTriangles(const EdgeTriangle* triangles, std::size_t count, DepthCompare test,
                   const TileBuffers& tile) {
  for (std::size_t t = 0; t < count; ++t) {
    DrawTriangleInTile(triangles[t], test, tile);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
