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

#if HWY_TARGET != HWY_SCALAR
#undef RELIEF_RASTER_BLOCKS
#define RELIEF_RASTER_BLOCKS 1
// Edge coefficients up to this magnitude take the block path: a block's lane offsets from
// its origin, |a| 256 dx + |b| 256 dy with dx <= 3 and dy <= 3, stay below 6 2^24.
constexpr std::int64_t kBlockMaxCoefficient = std::int64_t{1} << 16;
// The block origin's edge values are clamped to +-kBlockClamp: beyond it, value and offsets
// together keep the sign of the exact value (|offset| < 2^27 < kBlockClamp), and the sum fits
// 32 bits.
constexpr std::int64_t kBlockClamp = std::int64_t{1} << 29;

template <class DI>
HWY_INLINE bool FitsBlocks(DI /*di*/, const EdgeTriangle& t) {
  for (int e = 0; e < 3; ++e) {
    if (t.a[e] > kBlockMaxCoefficient || t.a[e] < -kBlockMaxCoefficient ||
        t.b[e] > kBlockMaxCoefficient || t.b[e] < -kBlockMaxCoefficient) {
      return false;
    }
  }
  return true;
}

// The projected grid's triangles cover a few pixels each: blocks of 4 columns and Lanes / 4
// rows (4 x 4 on AVX3, 4 x 2 on AVX2) test a whole small triangle in one or two steps, in
// 32-bit lanes: lane l is pixel (bx + l % 4, by + l / 4), its edge values the block origin's
// (exact 64-bit, clamped) plus l's offset, its depth z0 + dzdx px + dzdy py in double as the
// scalar code forms it. Blocks never straddle the tile's edge (they are moved inside; lanes
// outside the triangle's box are not covered), so each block row is four whole floats of a
// tile row.
template <class DI>
HWY_INLINE void DrawTriangleInBlocks(DI di, const EdgeTriangle& t, DepthCompare test,
                                     const TileBuffers& tile) {
  const hn::Rebind<float, DI> df;
  const hn::Rebind<std::uint32_t, DI> du;
  const hn::Half<decltype(df)> dfh;
  const hn::Rebind<double, decltype(dfh)> dd;
  const hn::Half<DI> dih;
  const hn::CappedTag<float, 4> d4;
  const hn::CappedTag<std::uint32_t, 4> du4;
  constexpr int kColumns = 4;
  const int rows = static_cast<int>(hn::Lanes(di)) / kColumns;
  const auto lane = hn::Iota(di, 0);
  const auto lane_x = hn::And(lane, hn::Set(di, kColumns - 1));
  const auto lane_y = hn::ShiftRight<2>(lane);
  hn::Vec<DI> offset[3];
  for (int e = 0; e < 3; ++e) {
    offset[e] = hn::Add(hn::Mul(hn::Set(di, t.a[e] * std::int32_t(kSubpixel)), lane_x),
                        hn::Mul(hn::Set(di, t.b[e] * std::int32_t(kSubpixel)), lane_y));
  }
  const auto zero = hn::Zero(di);
  const auto zero_d = hn::Zero(dd), one_d = hn::Set(dd, 1.0);
  const auto z0 = hn::Set(dd, t.z0), dzdx = hn::Set(dd, t.dzdx), dzdy = hn::Set(dd, t.dzdy);
  const auto depth_lanes = [&](hn::Vec<decltype(dih)> px, hn::Vec<decltype(dih)> py) {
    const auto z = hn::Add(hn::Add(z0, hn::Mul(dzdx, hn::PromoteTo(dd, px))),
                           hn::Mul(dzdy, hn::PromoteTo(dd, py)));
    // (z < 0 ? 0 : (z > 1 ? 1 : z)), then to float.
    return hn::DemoteTo(
        dfh, hn::IfThenElse(hn::Lt(z, zero_d), zero_d, hn::IfThenElse(hn::Gt(z, one_d), one_d, z)));
  };
  for (int row0 = t.y0; row0 <= t.y1; row0 += rows) {
    const int by = row0 + rows > tile.y0 + kTile ? tile.y0 + kTile - rows : row0;
    for (int column0 = t.x0; column0 <= t.x1; column0 += kColumns) {
      const int bx = column0 + kColumns > tile.x0 + kTile ? tile.x0 + kTile - kColumns : column0;
      const auto px = hn::Add(hn::Set(di, bx), lane_x);
      const auto py = hn::Add(hn::Set(di, by), lane_y);
      // This step's pixels: inside the box, from (column0, row0) on.
      auto covered = hn::And(
          hn::And(hn::Not(hn::Lt(px, hn::Set(di, column0))),
                  hn::Not(hn::Gt(px, hn::Set(di, t.x1)))),
          hn::And(hn::Not(hn::Lt(py, hn::Set(di, row0))), hn::Not(hn::Gt(py, hn::Set(di, t.y1)))));
      for (int e = 0; e < 3; ++e) {
        std::int64_t origin = std::int64_t{t.a[e]} * (std::int64_t{bx} * kSubpixel) +
                              std::int64_t{t.b[e]} * (std::int64_t{by} * kSubpixel) + t.c[e];
        origin =
            origin > kBlockClamp ? kBlockClamp : (origin < -kBlockClamp ? -kBlockClamp : origin);
        const auto value = hn::Add(hn::Set(di, static_cast<std::int32_t>(origin)), offset[e]);
        covered = hn::And(covered, hn::Gt(value, zero));
      }
      if (hn::AllFalse(di, covered)) {
        continue;
      }
      const auto depth =
          hn::Combine(df, depth_lanes(hn::UpperHalf(dih, px), hn::UpperHalf(dih, py)),
                      depth_lanes(hn::LowerHalf(dih, px), hn::LowerHalf(dih, py)));
      // The block's rows of the tile's buffers, four floats each.
      HWY_ALIGN float stored_depth[HWY_MAX_BYTES / sizeof(float)];
      HWY_ALIGN std::uint32_t stored_primitive[HWY_MAX_BYTES / sizeof(float)];
      const std::size_t first =
          static_cast<std::size_t>(by - tile.y0) * kTile + static_cast<std::size_t>(bx - tile.x0);
      for (int r = 0; r < rows; ++r) {
        const std::size_t k = first + static_cast<std::size_t>(r) * kTile;
        hn::Store(hn::LoadU(d4, tile.depth + k), d4, stored_depth + kColumns * r);
        hn::Store(hn::LoadU(du4, tile.primitive + k), du4, stored_primitive + kColumns * r);
      }
      const auto stored = hn::Load(df, stored_depth);
      const auto write = hn::And(hn::RebindMask(df, covered), PassesLanes(df, test, depth, stored));
      if (hn::AllFalse(df, write)) {
        continue;
      }
      hn::Store(hn::IfThenElse(write, depth, stored), df, stored_depth);
      hn::Store(hn::IfThenElse(hn::RebindMask(du, write), hn::Set(du, t.primitive),
                               hn::Load(du, stored_primitive)),
                du, stored_primitive);
      for (int r = 0; r < rows; ++r) {
        const std::size_t k = first + static_cast<std::size_t>(r) * kTile;
        hn::StoreU(hn::Load(d4, stored_depth + kColumns * r), d4, tile.depth + k);
        hn::StoreU(hn::Load(du4, stored_primitive + kColumns * r), du4, tile.primitive + k);
      }
    }
  }
}

#else
#undef RELIEF_RASTER_BLOCKS
#define RELIEF_RASTER_BLOCKS 0
#endif

void DrawTriangles(const EdgeTriangle* triangles, std::size_t count, DepthCompare test,
                   const TileBuffers& tile) {
#if RELIEF_RASTER_BLOCKS
  const hn::ScalableTag<std::int32_t> di;
  const bool blocks = hn::Lanes(di) >= 8;
  for (std::size_t t = 0; t < count; ++t) {
    if (blocks && FitsBlocks(di, triangles[t])) {
      DrawTriangleInBlocks(di, triangles[t], test, tile);
    } else {
      DrawTriangleInTile(triangles[t], test, tile);
    }
  }
#else
  for (std::size_t t = 0; t < count; ++t) {
    DrawTriangleInTile(triangles[t], test, tile);
  }
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace relief::simd
HWY_AFTER_NAMESPACE();

#endif  // include guard
