// The grid path of the triangle set-up (triangle_setup.h, setup_grid): a per-vertex pass over
// a chunk's vertices, the grid walked cell by cell with the per-triangle path's decisions, and
// the depth planes of the plain triangles in batches.
#include "raster/triangle_setup.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>

#include "raster/setup_internal.h"

namespace relief::raster {

using namespace setup_detail;

void PreparedVertices::resize(std::size_t n) {
  flags.resize(n);
  outcode.resize(n);
  floor_x.resize(n);
  floor_y.resize(n);
  z.resize(n);
  fx.resize(n);
  fy.resize(n);
}

namespace {

// prepare_vertices works through blocks of vertices in loops of independent iterations with
// no branches and no conditional loads, which compilers can vectorise, computing every value
// for every vertex and keeping it where it is the one setup_clip computes.
constexpr std::size_t kPrepareBlock = 256;

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

// Intermediate bits of a vertex (the low ones are PreparedVertices' flags).
constexpr std::uint32_t kOutcodeShift = 8;           // clip_outcode, bits 8-13
constexpr std::uint32_t kGuardUndecided = 1u << 16;  // guard bits still to be computed

struct VertexBlock {
  float x[kPrepareBlock], y[kPrepareBlock];  // window coordinates
  std::uint32_t bits[kPrepareBlock];
};

// First pass: flags, the near and far bits, the guard bits where float arithmetic decides
// them, window coordinates. Valid and drawn vertices, as GridTriangles reads valid and need.
template <bool kHasValid, bool kHasNeed>
void prepare_block(const float* vx, const float* vy, const float* vz, const float* vw,
                   const std::uint8_t* valid, const std::uint8_t* need, std::size_t n,
                   float guard_x, float guard_y, float sx, float sy, float tx, float ty,
                   float* window_z, VertexBlock& block) {
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
    // Elsewhere the second pass computes the outcode exactly.
    const float gxw = guard_x * w, gyw = guard_y * w;
    constexpr float kMin = std::numeric_limits<float>::min();
    constexpr float kMax = std::numeric_limits<float>::max();
    const std::uint32_t guards_inside =
        std::uint32_t(w > 0.0f) & std::uint32_t(gxw >= kMin) & std::uint32_t(gxw <= kMax) &
        std::uint32_t(gyw >= kMin) & std::uint32_t(gyw <= kMax) &
        std::uint32_t(std::abs(x) * 2.0f <= gxw) & std::uint32_t(std::abs(y) * 2.0f <= gyw);
    // to_window, the same operations (kept only for snapped vertices, which have w > 0).
    const float inv_w = 1.0f / w;
    block.x[e] = x * inv_w * sx + tx;
    block.y[e] = y * inv_w * sy + ty;
    window_z[e] = z * inv_w;
    block.bits[e] = is_valid * PreparedVertices::kValid | is_drawn * PreparedVertices::kDrawn |
                    plain * PreparedVertices::kPlain | near_bit << kOutcodeShift |
                    far_bit << (kOutcodeShift + 1) |
                    (kGuardUndecided & mask_of(guards_inside == 0u));
  }
}

}  // namespace

void TriangleSetup::prepare_vertices(ClipVertices vertices, std::size_t begin, std::size_t end,
                                     std::span<const std::uint8_t> valid,
                                     std::span<const std::uint8_t> need,
                                     PreparedVertices& out) const {
  out.begin = begin;
  out.resize(end - begin);
  VertexBlock block;
  for (std::size_t block_begin = begin; block_begin < end; block_begin += kPrepareBlock) {
    const std::size_t n = std::min(kPrepareBlock, end - block_begin);
    const std::size_t o = block_begin - begin;  // offset in `out`
    const float* vx = vertices.x.data() + block_begin;
    const float* vy = vertices.y.data() + block_begin;
    const float* vz = vertices.z.data() + block_begin;
    const float* vw = vertices.w.data() + block_begin;
    const std::uint8_t* valid_at = valid.empty() ? nullptr : valid.data() + block_begin;
    const std::uint8_t* need_at = need.empty() ? nullptr : need.data() + block_begin;
    float* window_z = out.z.data() + o;
    const float gx = planes_.guard_x, gy = planes_.guard_y;
    const float sx = scale_x_, sy = scale_y_, tx = translate_x_, ty = translate_y_;
    if (valid_at != nullptr && need_at != nullptr) {
      prepare_block<true, true>(vx, vy, vz, vw, valid_at, need_at, n, gx, gy, sx, sy, tx, ty,
                                window_z, block);
    } else if (valid_at != nullptr) {
      prepare_block<true, false>(vx, vy, vz, vw, valid_at, need_at, n, gx, gy, sx, sy, tx, ty,
                                 window_z, block);
    } else if (need_at != nullptr) {
      prepare_block<false, true>(vx, vy, vz, vw, valid_at, need_at, n, gx, gy, sx, sy, tx, ty,
                                 window_z, block);
    } else {
      prepare_block<false, false>(vx, vy, vz, vw, valid_at, need_at, n, gx, gy, sx, sy, tx, ty,
                                  window_z, block);
    }
    // Second pass, for the few plain vertices whose guard bits float did not decide: the whole
    // outcode as clip_triangle computes it.
    for (std::size_t e = 0; e < n; ++e) {
      const std::uint32_t bits = block.bits[e];
      if ((bits & kGuardUndecided) != 0 && (bits & PreparedVertices::kPlain) != 0) {
        const unsigned outcode = clip_outcode(ClipVertex{vx[e], vy[e], vz[e], vw[e]}, planes_);
        block.bits[e] = (bits & ~(kClipOutcodeMask << kOutcodeShift)) | outcode << kOutcodeShift;
      }
    }
    // Third pass: setup_polygon's snap limit, the snapped coordinates and the floors, kept for
    // a plain vertex of outcode 0 (w > 0 there: 0 <= z <= w, and w = 0 would leave only the
    // origin, which is not plain). Elsewhere the coordinates are replaced by 0 before the
    // conversions to integers, which keeps them defined.
    std::uint8_t* flags = out.flags.data() + o;
    std::uint8_t* outcodes = out.outcode.data() + o;
    float* floor_x = out.floor_x.data() + o;
    float* floor_y = out.floor_y.data() + o;
    std::int32_t* fx = out.fx.data() + o;
    std::int32_t* fy = out.fy.data() + o;
    constexpr float kLimit = static_cast<float>(kSnapLimitPixels);  // 2^21 + 1: exact
    for (std::size_t e = 0; e < n; ++e) {
      const std::uint32_t bits = block.bits[e];
      const float x = block.x[e], y = block.y[e];
      const std::uint32_t outcode = (bits >> kOutcodeShift) & kClipOutcodeMask;
      // |double(x)| < kSnapLimitPixels, in float: the same test (NaN fails both).
      const std::uint32_t snapped =
          std::uint32_t((bits & PreparedVertices::kPlain) != 0) & std::uint32_t(outcode == 0u) &
          std::uint32_t(std::abs(x) < kLimit) & std::uint32_t(std::abs(y) < kLimit);
      const std::uint32_t keep = mask_of(snapped != 0u);
      const float sx_in = std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) & keep);
      const float sy_in = std::bit_cast<float>(std::bit_cast<std::uint32_t>(y) & keep);
      block.x[e] = sx_in;
      block.y[e] = sy_in;
      floor_x[e] = floor_small(sx_in);
      floor_y[e] = floor_small(sy_in);
      outcodes[e] = static_cast<std::uint8_t>(outcode);
      flags[e] =
          static_cast<std::uint8_t>((bits & (PreparedVertices::kValid | PreparedVertices::kDrawn |
                                             PreparedVertices::kPlain)) |
                                    (PreparedVertices::kSnapped & keep));
    }
    for (std::size_t e = 0; e < n; ++e) {
      fx[e] = snap_to_fixed(block.x[e]);
      fy[e] = snap_to_fixed(block.y[e]);
    }
  }
}

namespace {

// Depth planes computed a batch at a time, after the batch's triangles have passed the edge
// tests: the same operations as TriangleSetup::depth_plane and piece_depth, lane by lane, in a
// loop of independent iterations.
constexpr int kDepthBatch = 32;

struct DepthBatch {
  int count = 0;
  std::size_t slot[kDepthBatch];       // index of the triangle in `out`
  std::size_t vertex[3][kDepthBatch];  // its three vertices
  double floor_x[kDepthBatch], floor_y[kDepthBatch], first_z[kDepthBatch];
};

double det3_lane(double p0, double p1, double p2, double q0, double q1, double q2, double r0,
                 double r1, double r2) {
  return p0 * (q1 * r2 - q2 * r1) - p1 * (q0 * r2 - q2 * r0) + p2 * (q0 * r1 - q1 * r0);
}

// Set-up triangles of one call of setup_grid, written in place (a vector would value-initialise
// or copy each record) into storage each thread reuses, so that it stays in cache.
class TriangleScratch {
 public:
  RasterTriangle* data() { return data_.get(); }
  std::size_t size() const { return size_; }
  void clear() { size_ = 0; }
  // A record at the end, uninitialised.
  RasterTriangle& append() {
    if (size_ == capacity_) {
      grow();
    }
    return data_[size_++];
  }

 private:
  void grow() {
    const std::size_t capacity = capacity_ == 0 ? kSetupChunk : 2 * capacity_;
    std::unique_ptr<RasterTriangle[]> data(new RasterTriangle[capacity]);
    std::copy(data_.get(), data_.get() + size_, data.get());
    data_ = std::move(data);
    capacity_ = capacity;
  }
  std::unique_ptr<RasterTriangle[]> data_;
  std::size_t size_ = 0, capacity_ = 0;
};

// The depth planes of a batch, written into their records in `out` (indexed by the slots):
// piece_depth's values, with depth_plane's operations (s, t: the viewport's scale and
// translation).
void depth_batch(ClipVertices vertices, const DepthBatch& batch, float scale_x, float scale_y,
                 float translate_x, float translate_y, RasterTriangle* out) {
  const int n = batch.count;
  double X[3][kDepthBatch], Y[3][kDepthBatch], Z[3][kDepthBatch], W[3][kDepthBatch];
  const double sx = double(scale_x), sy = double(scale_y);
  const double tx = double(translate_x), ty = double(translate_y);
  double cx[kDepthBatch], cy[kDepthBatch];
  for (int b = 0; b < n; ++b) {
    cx[b] = tx - batch.floor_x[b];  // exact: integers and floats below 2^24
    cy[b] = ty - batch.floor_y[b];
  }
  for (int k = 0; k < 3; ++k) {
    for (int b = 0; b < n; ++b) {
      const std::size_t i = batch.vertex[k][b];
      X[k][b] = double(vertices.x[i]) * sx + double(vertices.w[i]) * cx[b];
      Y[k][b] = double(vertices.y[i]) * sy + double(vertices.w[i]) * cy[b];
      Z[k][b] = vertices.z[i];
      W[k][b] = vertices.w[i];
    }
  }
  // One iteration per triangle, independent (and free of branches and conditional loads, so
  // that compilers can vectorise it: the same operations lane by lane).
  double z0[kDepthBatch], dzdx[kDepthBatch], dzdy[kDepthBatch];
  for (int b = 0; b < n; ++b) {
    const double n_x =
        det3_lane(Y[0][b], Y[1][b], Y[2][b], Z[0][b], Z[1][b], Z[2][b], W[0][b], W[1][b], W[2][b]);
    const double n_y =
        -det3_lane(X[0][b], X[1][b], X[2][b], Z[0][b], Z[1][b], Z[2][b], W[0][b], W[1][b], W[2][b]);
    const double n_z =
        det3_lane(X[0][b], X[1][b], X[2][b], Y[0][b], Y[1][b], Y[2][b], W[0][b], W[1][b], W[2][b]);
    const double n_w =
        -det3_lane(X[0][b], X[1][b], X[2][b], Y[0][b], Y[1][b], Y[2][b], Z[0][b], Z[1][b], Z[2][b]);
    const double gx = -n_x / n_z;
    const double gy = -n_y / n_z;
    const double gz = -n_w / n_z;
    // depth_plane's domain test and finiteness tests (|v| <= max: finite, not NaN).
    constexpr double kMax = std::numeric_limits<double>::max();
    const bool ok =
        (std::uint32_t(std::abs(n_z) > 0.0) & std::uint32_t(std::abs(gx) <= kMax) &
         std::uint32_t(std::abs(gy) <= kMax) & std::uint32_t(std::abs(gz) <= kMax)) != 0u;
    const double u0 = batch.floor_x[b], v0 = batch.floor_y[b], first_z = batch.first_z[b];
    const double z_ref = ok ? gz : first_z;
    const double plane_x = ok ? gx : 0.0, plane_y = ok ? gy : 0.0;
    dzdx[b] = plane_x;
    dzdy[b] = plane_y;
    z0[b] = z_ref + plane_x * (0.5 - u0) + plane_y * (0.5 - v0);
  }
  for (int b = 0; b < n; ++b) {
    RasterTriangle& t = out[batch.slot[b]];
    t.z0 = z0[b];
    t.dzdx = dzdx[b];
    t.dzdy = dzdy[b];
  }
}

}  // namespace

void TriangleSetup::setup_grid(ClipVertices vertices, const GridTriangles& source,
                               std::uint32_t begin, std::uint32_t end,
                               const PreparedVertices& prepared, std::uint32_t& submitted,
                               RasterTriangles& out) const {
  if (begin >= end) {
    return;
  }
  const GridLayout& layout = source.layout;
  const auto columns = static_cast<std::uint32_t>(layout.width - 1);  // cells per row
  const std::uint32_t first_cell = begin >> 1, last_cell = (end - 1) >> 1;
  int i = static_cast<int>(first_cell % columns);
  int j = static_cast<int>(first_cell / columns);
  const std::size_t pitch = static_cast<std::size_t>(layout.pitch);
  const std::size_t base = prepared.begin;
  const std::uint8_t* flags = prepared.flags.data();
  const std::uint8_t* outcode = prepared.outcode.data();
  const float* floor_x = prepared.floor_x.data();
  const float* floor_y = prepared.floor_y.data();
  const float* window_z = prepared.z.data();
  const std::int32_t* fx = prepared.fx.data();
  const std::int32_t* fy = prepared.fy.data();
  DepthBatch batch;
  thread_local TriangleScratch scratch;
  thread_local std::vector<RasterTriangle> clipped;  // the pieces of one clipped triangle
  scratch.clear();
  for (std::uint32_t cell = first_cell; cell <= last_cell; ++cell) {
    // Corners as GridTriangles names them: a = (i, j), b = (i+1, j), c = (i+1, j+1),
    // d = (i, j+1); triangles (a, b, c) and (a, c, d).
    const std::size_t a = layout.index(i, j) - base, b = a + 1, d = a + pitch, c = d + 1;
    if (++i == static_cast<int>(columns)) {
      i = 0;
      ++j;
    }
    const unsigned fa = flags[a], fb = flags[b], fc = flags[c], fd = flags[d];
    if ((fa & fb & fc & fd & PreparedVertices::kValid) == 0) {
      continue;  // a corner is invalid: neither triangle is drawn
    }
    for (std::uint32_t half = 0; half < 2; ++half) {
      const std::uint32_t t = 2 * cell + half;
      const std::size_t k0 = a, k1 = half ? c : b, k2 = half ? d : c;
      const unsigned all = fa & (half ? fc & fd : fb & fc);
      if ((all & PreparedVertices::kDrawn) == 0 || t < begin || t >= end) {
        continue;  // not drawn (need), or not in [begin, end)
      }
      ++submitted;
      // Exactly setup_clip's decisions and values, from the prepared vertices where they
      // decide it; setup_clip itself otherwise.
      if (all & PreparedVertices::kSnapped) {
        // Inside every plane: setup_polygon's single piece, its depth plane to come.
        std::int32_t px[3] = {fx[k0], fx[k1], fx[k2]};
        std::int32_t py[3] = {fy[k0], fy[k1], fy[k2]};
        std::int32_t box[4];
        bool swapped = false;
        if (!edge_box(edge_rules_, px, py, box, swapped)) {
          continue;
        }
        RasterTriangle& tri = scratch.append();
        write_edges(px, py, box, tri);
        tri.primitive = t;  // z0, dzdx, dzdy: depth_batch's
        const int slot = batch.count++;
        batch.slot[slot] = scratch.size() - 1;
        batch.vertex[0][slot] = base + k0;
        batch.vertex[1][slot] = base + k1;
        batch.vertex[2][slot] = base + k2;
        batch.floor_x[slot] = floor_x[k0];
        batch.floor_y[slot] = floor_y[k0];
        batch.first_z[slot] = window_z[k0];
        if (batch.count == kDepthBatch) {
          depth_batch(vertices, batch, scale_x_, scale_y_, translate_x_, translate_y_,
                      scratch.data());
          batch.count = 0;
        }
        continue;
      }
      if (all & PreparedVertices::kPlain) {
        const unsigned o0 = outcode[k0], o1 = outcode[k1], o2 = outcode[k2];
        if ((o0 & o1 & o2) != 0) {
          continue;  // all three outside one plane
        }
        if ((o0 | o1 | o2) == 0) {
          continue;  // inside every plane, a vertex beyond the snap limit: dropped
        }
      }
      const std::size_t v[3] = {base + k0, base + k1, base + k2};
      const ClipVertex cv[3] = {
          {vertices.x[v[0]], vertices.y[v[0]], vertices.z[v[0]], vertices.w[v[0]]},
          {vertices.x[v[1]], vertices.y[v[1]], vertices.z[v[1]], vertices.w[v[1]]},
          {vertices.x[v[2]], vertices.y[v[2]], vertices.z[v[2]], vertices.w[v[2]]}};
      clipped.clear();
      setup_clip(t, cv, clipped);
      for (const RasterTriangle& piece : clipped) {
        scratch.append() = piece;
      }
    }
  }
  depth_batch(vertices, batch, scale_x_, scale_y_, translate_x_, translate_y_, scratch.data());
  if (scratch.size() > 0) {
    const std::size_t first = out.size();
    out.resize(first + scratch.size());  // default-initialised: written here
    std::memcpy(static_cast<void*>(out.data() + first), scratch.data(),
                scratch.size() * sizeof(RasterTriangle));
  }
}

}  // namespace relief::raster
