// The per-vertex half of the grid's triangle set-up (TriangleSetup::prepare_vertices): each
// vertex of a chunk's triangles gets, once, what setup_clip would compute for it in every
// triangle it belongs to: its flags, its clip outcode, its window coordinates snapped to the
// 16.8 grid, and the floors the depth plane is referred to.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "raster/setup_internal.h"
#include "raster/triangle_setup.h"

namespace relief::raster {

using namespace setup_detail;

void PreparedVertices::resize(std::size_t n) {
  for (std::vector<std::uint8_t>* v : {&flags, &outcode}) {
    v->resize(n);
  }
  for (std::vector<float>* v : {&floor_x, &floor_y, &z, &window_x, &window_y}) {
    v->resize(n);
  }
  fx.resize(n);
  fy.resize(n);
  bits.resize(n);
}

namespace {

// The passes are loops of independent iterations with no branches and no conditional loads,
// which compilers can vectorise (and the simd backend's kernels repeat lane by lane): every
// value is computed for every vertex and kept where it is the one setup_clip computes.

// All ones where `condition` holds, else 0.
inline std::uint32_t mask_of(bool condition) {
  return 0u - std::uint32_t(condition);
}

// ordinary_clip_coordinate (clip.h) as 0 or 1: the magnitude is 0 or that of a normal float.
inline std::uint32_t ordinary_bit(float c) {
  const std::uint32_t magnitude = std::bit_cast<std::uint32_t>(c) & 0x7fffffffu;
  return std::uint32_t(magnitude == 0u) | std::uint32_t(magnitude - 0x00800000u < 0x7f000000u);
}

// std::floor of a float below 2^31 in magnitude, as a float (exact, floor(-0) = -0 included):
// truncated through int32 with x's sign, then one less where truncation went up.
inline float floor_small(float x) {
  const float truncated = static_cast<float>(static_cast<std::int32_t>(x));
  const float t = std::bit_cast<float>(std::bit_cast<std::uint32_t>(truncated) |
                                       (std::bit_cast<std::uint32_t>(x) & 0x80000000u));
  return t - std::bit_cast<float>(mask_of(t > x) & 0x3f800000u);  // t - 1.0f or t - 0.0f
}

// First pass: flags, the near and far bits, the guard bits where float arithmetic decides
// them, window coordinates. Valid and drawn vertices, as GridTriangles reads valid and need.
template <bool kHasValid, bool kHasNeed>
void window_pass(const SnapConstants& c, const float* vx, const float* vy, const float* vz,
                 const float* vw, const std::uint8_t* valid, const std::uint8_t* need,
                 std::size_t n, float* window_x, float* window_y, float* window_z,
                 std::uint32_t* bits) {
  constexpr std::uint32_t kShift = PreparedVertices::kOutcodeShift;
  for (std::size_t e = 0; e < n; ++e) {
    const float x = vx[e], y = vy[e], z = vz[e], w = vw[e];
    const std::uint32_t is_valid = kHasValid ? std::uint32_t(valid[e] != 0) : 1u;
    const std::uint32_t is_drawn = is_valid & (kHasNeed ? std::uint32_t((need[e] & 2u) != 0) : 1u);
    // plain_clip_vertex: four ordinary coordinates, not all zero.
    const std::uint32_t plain = ordinary_bit(x) & ordinary_bit(y) & ordinary_bit(z) &
                                ordinary_bit(w) &
                                (std::uint32_t(x != 0.0f) | std::uint32_t(y != 0.0f) |
                                 std::uint32_t(z != 0.0f) | std::uint32_t(w != 0.0f));
    // clip_outcode's near and far bits, !(w - z >= 0) and !(z >= 0) in double: for finite
    // floats the double difference is the exact one rounded, which has the exact sign (and is
    // zero only when w = z), so they are !(w >= z) and !(z >= 0) in float. (The outcode is
    // read only for plain vertices, whose coordinates are finite.)
    const std::uint32_t near_bit = std::uint32_t(!(w >= z));
    const std::uint32_t far_bit = std::uint32_t(!(z >= 0.0f));
    // Its guard bits are all 0 exactly when |x| <= g_x w and |y| <= g_y w (g w is exact in
    // double, and g w -+ x has the sign of the exact value). Float decides that where it can:
    // for w > 0 and r = g_x w rounded to a normal float, r <= (1 + 2^-24) g_x w, so
    // 2 |x| <= r implies |x| <= g_x w (2 |x| is exact, or infinite and the test fails).
    // Elsewhere prepare_vertices computes the outcode exactly.
    const float gxw = c.guard_x * w, gyw = c.guard_y * w;
    constexpr float kMin = std::numeric_limits<float>::min();
    constexpr float kMax = std::numeric_limits<float>::max();
    const std::uint32_t guards_inside =
        std::uint32_t(w > 0.0f) & std::uint32_t(gxw >= kMin) & std::uint32_t(gxw <= kMax) &
        std::uint32_t(gyw >= kMin) & std::uint32_t(gyw <= kMax) &
        std::uint32_t(std::abs(x) * 2.0f <= gxw) & std::uint32_t(std::abs(y) * 2.0f <= gyw);
    // to_window, the same operations (kept only for snapped vertices, which have w > 0).
    const float inv_w = 1.0f / w;
    window_x[e] = x * inv_w * c.scale_x + c.translate_x;
    window_y[e] = y * inv_w * c.scale_y + c.translate_y;
    window_z[e] = z * inv_w;
    bits[e] = is_valid * PreparedVertices::kValid | is_drawn * PreparedVertices::kDrawn |
              plain * PreparedVertices::kPlain | near_bit << kShift | far_bit << (kShift + 1) |
              (PreparedVertices::kGuardUndecided & mask_of(guards_inside == 0u));
  }
}

void portable_window(const SnapConstants& c, const float* x, const float* y, const float* z,
                     const float* w, const std::uint8_t* valid, const std::uint8_t* need,
                     std::size_t n, float* window_x, float* window_y, float* window_z,
                     std::uint32_t* bits) {
  if (valid != nullptr && need != nullptr) {
    window_pass<true, true>(c, x, y, z, w, valid, need, n, window_x, window_y, window_z, bits);
  } else if (valid != nullptr) {
    window_pass<true, false>(c, x, y, z, w, valid, need, n, window_x, window_y, window_z, bits);
  } else if (need != nullptr) {
    window_pass<false, true>(c, x, y, z, w, valid, need, n, window_x, window_y, window_z, bits);
  } else {
    window_pass<false, false>(c, x, y, z, w, valid, need, n, window_x, window_y, window_z, bits);
  }
}

// Last pass: setup_polygon's snap limit, the snapped coordinates and the floors, kept for a
// plain vertex of outcode 0 (w > 0 there: 0 <= z <= w, and w = 0 would leave only the origin,
// which is not plain). Elsewhere the coordinates are replaced by 0 before the conversions to
// integers, which keeps them defined.
void portable_snap(std::size_t n, const std::uint32_t* bits, const float* window_x,
                   const float* window_y, std::uint8_t* flags, std::uint8_t* outcodes,
                   float* floor_x, float* floor_y, std::int32_t* fx, std::int32_t* fy) {
  constexpr float kLimit = static_cast<float>(kSnapLimitPixels);  // 2^21 + 1: exact
  for (std::size_t e = 0; e < n; ++e) {
    const float x = window_x[e], y = window_y[e];
    const std::uint32_t outcode = (bits[e] >> PreparedVertices::kOutcodeShift) & kClipOutcodeMask;
    // |double(x)| < kSnapLimitPixels, in float: the same test (NaN fails both).
    const std::uint32_t snapped =
        std::uint32_t((bits[e] & PreparedVertices::kPlain) != 0) & std::uint32_t(outcode == 0u) &
        std::uint32_t(std::abs(x) < kLimit) & std::uint32_t(std::abs(y) < kLimit);
    const std::uint32_t keep = mask_of(snapped != 0u);
    const float sx = std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) & keep);
    const float sy = std::bit_cast<float>(std::bit_cast<std::uint32_t>(y) & keep);
    floor_x[e] = floor_small(sx);
    floor_y[e] = floor_small(sy);
    outcodes[e] = static_cast<std::uint8_t>(outcode);
    flags[e] =
        static_cast<std::uint8_t>((bits[e] & (PreparedVertices::kValid | PreparedVertices::kDrawn |
                                              PreparedVertices::kPlain)) |
                                  (PreparedVertices::kSnapped & keep));
    fx[e] = snap_to_fixed(sx);
    fy[e] = snap_to_fixed(sy);
  }
}

constexpr SnapKernels kPortableKernels{portable_window, portable_snap};

}  // namespace

SnapConstants TriangleSetup::snap_constants() const {
  return {planes_.guard_x, planes_.guard_y, scale_x_, scale_y_, translate_x_, translate_y_};
}

void TriangleSetup::prepare_vertices(ClipVertices vertices, std::size_t begin, std::size_t end,
                                     std::span<const std::uint8_t> valid,
                                     std::span<const std::uint8_t> need,
                                     PreparedVertices& out) const {
  const SnapKernels& kernels = snap_kernels_ != nullptr ? *snap_kernels_ : kPortableKernels;
  const std::size_t n = end - begin;
  out.begin = begin;
  out.resize(n);
  const float* vx = vertices.x.data() + begin;
  const float* vy = vertices.y.data() + begin;
  const float* vz = vertices.z.data() + begin;
  const float* vw = vertices.w.data() + begin;
  kernels.window(snap_constants(), vx, vy, vz, vw, valid.empty() ? nullptr : valid.data() + begin,
                 need.empty() ? nullptr : need.data() + begin, n, out.window_x.data(),
                 out.window_y.data(), out.z.data(), out.bits.data());
  // The few plain vertices whose guard bits float did not decide: the whole outcode as
  // clip_triangle computes it.
  constexpr std::uint32_t kOutcodeBits = kClipOutcodeMask << PreparedVertices::kOutcodeShift;
  for (std::size_t e = 0; e < n; ++e) {
    const std::uint32_t bits = out.bits[e];
    if ((bits & PreparedVertices::kGuardUndecided) != 0 && (bits & PreparedVertices::kPlain) != 0) {
      const unsigned outcode = clip_outcode(ClipVertex{vx[e], vy[e], vz[e], vw[e]}, planes_);
      out.bits[e] = (bits & ~kOutcodeBits) | outcode << PreparedVertices::kOutcodeShift;
    }
  }
  kernels.snap(n, out.bits.data(), out.window_x.data(), out.window_y.data(), out.flags.data(),
               out.outcode.data(), out.floor_x.data(), out.floor_y.data(), out.fx.data(),
               out.fy.data());
}

}  // namespace relief::raster
