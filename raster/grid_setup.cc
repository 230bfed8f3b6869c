// The grid path of the triangle set-up (triangle_setup.h, setup_grid): the grid walked cell by
// cell with the per-triangle path's decisions, from the prepared vertices (vertex_prepare.cc),
// and the depth planes of the plain triangles in batches.
#include "raster/triangle_setup.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "raster/setup_internal.h"

namespace relief::raster {

using namespace setup_detail;

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

// The arrays of one block of prepared vertices, as raw pointers the loops keep in registers.
struct PreparedView {
  const std::uint8_t *flags, *outcode;
  const float *floor_x, *floor_y, *z;
  const std::int32_t *fx, *fy;
};
PreparedView view_of(const PreparedVertices& p) {
  return {p.flags.data(), p.outcode.data(), p.floor_x.data(), p.floor_y.data(),
          p.z.data(),     p.fx.data(),      p.fy.data()};
}

// A prepared vertex by its index in the vertex buffer: one block (setup_grid's chunk) or
// blocks of a power-of-two size (an index list's, prepared once per frame).
struct OneBlock {
  PreparedView view;
  std::size_t base;
  std::size_t at(std::size_t k) const { return k - base; }
  PreparedView of(std::size_t) const { return view; }
};
struct FixedBlocks {
  std::vector<PreparedView> views;
  int shift;  // log2 of the block's vertices
  std::size_t at(std::size_t k) const { return k & ((std::size_t(1) << shift) - 1); }
  PreparedView of(std::size_t k) const { return views[k >> shift]; }
};

// The set-up of the triangles `walk` names (walk(emit) calls emit(t, k0, k1, k2) for each
// triangle t to set up, in order, k the vertices' indices in `vertices`): exactly setup_clip's
// decisions and values, from the prepared vertices where they decide it, setup_clip itself
// otherwise; `submitted` counts the drawn ones (kDrawn on all three).
template <class Prepared, class Walk>
void set_up_prepared(const TriangleSetup& setup, const EdgeRules& rules, ClipVertices vertices,
                     const Prepared& prepared, float scale_x, float scale_y, float translate_x,
                     float translate_y, std::uint32_t& submitted, RasterTriangles& out,
                     Walk&& walk) {
  DepthBatch batch;
  thread_local TriangleScratch scratch;
  thread_local std::vector<RasterTriangle> clipped;  // the pieces of one clipped triangle
  scratch.clear();
  walk([&](std::uint32_t t, std::size_t v0, std::size_t v1, std::size_t v2) {
    const PreparedView p0 = prepared.of(v0), p1 = prepared.of(v1), p2 = prepared.of(v2);
    const std::size_t k0 = prepared.at(v0), k1 = prepared.at(v1), k2 = prepared.at(v2);
    const unsigned all = p0.flags[k0] & p1.flags[k1] & p2.flags[k2];
    if ((all & PreparedVertices::kDrawn) == 0) {
      return;  // not drawn (need)
    }
    ++submitted;
    if (all & PreparedVertices::kSnapped) {
      // Inside every plane: setup_polygon's single piece, its depth plane to come.
      std::int32_t px[3] = {p0.fx[k0], p1.fx[k1], p2.fx[k2]};
      std::int32_t py[3] = {p0.fy[k0], p1.fy[k1], p2.fy[k2]};
      std::int32_t box[4];
      bool swapped = false;
      if (!edge_box(rules, px, py, box, swapped)) {
        return;
      }
      RasterTriangle& tri = scratch.append();
      write_edges(px, py, box, tri);
      tri.primitive = t;  // z0, dzdx, dzdy: depth_batch's
      const int slot = batch.count++;
      batch.slot[slot] = scratch.size() - 1;
      batch.vertex[0][slot] = v0;
      batch.vertex[1][slot] = v1;
      batch.vertex[2][slot] = v2;
      batch.floor_x[slot] = p0.floor_x[k0];
      batch.floor_y[slot] = p0.floor_y[k0];
      batch.first_z[slot] = p0.z[k0];
      if (batch.count == kDepthBatch) {
        depth_batch(vertices, batch, scale_x, scale_y, translate_x, translate_y, scratch.data());
        batch.count = 0;
      }
      return;
    }
    if (all & PreparedVertices::kPlain) {
      const unsigned o0 = p0.outcode[k0], o1 = p1.outcode[k1], o2 = p2.outcode[k2];
      if ((o0 & o1 & o2) != 0) {
        return;  // all three outside one plane
      }
      if ((o0 | o1 | o2) == 0) {
        return;  // inside every plane, a vertex beyond the snap limit: dropped
      }
    }
    const std::size_t v[3] = {v0, v1, v2};
    const ClipVertex cv[3] = {
        {vertices.x[v[0]], vertices.y[v[0]], vertices.z[v[0]], vertices.w[v[0]]},
        {vertices.x[v[1]], vertices.y[v[1]], vertices.z[v[1]], vertices.w[v[1]]},
        {vertices.x[v[2]], vertices.y[v[2]], vertices.z[v[2]], vertices.w[v[2]]}};
    clipped.clear();
    setup.setup_clip(t, cv, clipped);
    for (const RasterTriangle& piece : clipped) {
      scratch.append() = piece;
    }
  });
  depth_batch(vertices, batch, scale_x, scale_y, translate_x, translate_y, scratch.data());
  if (scratch.size() > 0) {
    const std::size_t first = out.size();
    out.resize(first + scratch.size());  // default-initialised: written here
    std::memcpy(static_cast<void*>(out.data() + first), scratch.data(),
                scratch.size() * sizeof(RasterTriangle));
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
  const std::size_t pitch = static_cast<std::size_t>(layout.pitch);
  const std::uint8_t* flags = prepared.flags.data();
  const std::size_t base = prepared.begin;
  set_up_prepared(*this, edge_rules_, vertices, OneBlock{view_of(prepared), base}, scale_x_,
                  scale_y_, translate_x_, translate_y_, submitted, out, [&](auto&& emit) {
                    int i = static_cast<int>(first_cell % columns);
                    int j = static_cast<int>(first_cell / columns);
                    for (std::uint32_t cell = first_cell; cell <= last_cell; ++cell) {
                      // Corners as GridTriangles names them: a = (i, j), b = (i+1, j), c = (i+1,
                      // j+1), d = (i, j+1); triangles (a, b, c) and (a, c, d).
                      const std::size_t a = layout.index(i, j), b = a + 1, d = a + pitch, c = d + 1;
                      if (++i == static_cast<int>(columns)) {
                        i = 0;
                        ++j;
                      }
                      if ((flags[a - base] & flags[b - base] & flags[c - base] & flags[d - base] &
                           PreparedVertices::kValid) == 0) {
                        continue;  // a corner is invalid: neither triangle is drawn
                      }
                      for (std::uint32_t half = 0; half < 2; ++half) {
                        const std::uint32_t t = 2 * cell + half;
                        if (t >= begin && t < end) {
                          emit(t, a, half ? c : b, half ? d : c);
                        }
                      }
                    }
                  });
}

void TriangleSetup::setup_indexed(ClipVertices vertices, const IndexedTriangles& source,
                                  std::uint32_t begin, std::uint32_t end,
                                  std::span<const PreparedVertices> blocks,
                                  std::size_t block_vertices, std::uint32_t& submitted,
                                  RasterTriangles& out) const {
  if (!std::has_single_bit(block_vertices)) {
    throw std::invalid_argument("setup_indexed: blocks of " + std::to_string(block_vertices) +
                                " vertices; allowed a power of two");
  }
  FixedBlocks prepared{{}, std::countr_zero(block_vertices)};
  prepared.views.reserve(blocks.size());
  for (const PreparedVertices& block : blocks) {
    prepared.views.push_back(view_of(block));
  }
  set_up_prepared(*this, edge_rules_, vertices, prepared, scale_x_, scale_y_, translate_x_,
                  translate_y_, submitted, out, [&](auto&& emit) {
                    for (std::uint32_t t = begin; t < end; ++t) {
                      std::uint32_t v[3];
                      source.vertices(t, v);
                      emit(t, v[0], v[1], v[2]);
                    }
                  });
}

}  // namespace relief::raster
