// Triangle setup (stage 6, first half): clip, viewport transform, snap, cull, and build the
// integer edge functions and the depth plane of each triangle that can cover a pixel.
//
// Edge functions (16.8 fixed point, pixel centres at multiples of 256, raster_types.h): for a
// counter-clockwise triangle (positive area in GL's y-up window coordinates) edge i from v_i
// to v_i+1 is E_i(X, Y) = a_i X + b_i Y + c_i, a_i = y_i - y_i+1, b_i = x_i+1 - x_i; positive
// inside. Fill rule, GL's window coordinates: a pixel centre exactly on an edge belongs to
// left edges (dy < 0) and bottom edges (dy = 0, dx > 0), not to right or top ones (D3D's
// top-left rule seen with y flipped; llvmpipe's rule for GL framebuffers). It is folded into
// c_i (+1 on inclusive edges), so "inside" is E_i > 0 for all three, in exact int64 arithmetic:
// every pixel of a closed mesh is covered exactly once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "raster/clip.h"
#include "raster/raster_types.h"
#include "raster/topology.h"
#include "raster/triangle_storage.h"

namespace relief::raster {

struct RasterTriangle {
  std::int64_t c[3];  // edge constants, fill-rule bias included
  std::int32_t a[3];  // edge coefficients per fixed-point unit
  std::int32_t b[3];
  std::int32_t x0, y0, x1, y1;  // inclusive pixel bounds, inside viewport and framebuffer
  // Depth at pixel (px, py): z0 + dzdx px + dzdy py, in double, then clamped to [0, 1] (GL's
  // depth range) and rounded to float. The plane: for a clip-space triangle, clipped or not,
  // the plane of the whole triangle from its clip coordinates in double (z/w is affine in
  // window x, y over it), so that neither a rounded window coordinate nor a rounded clipped
  // vertex enters it: within one float ulp of 1 of exact arithmetic (measured: half an ulp,
  // docs/rasteriser-accuracy.md). For a window-coordinate triangle, the plane through its
  // (unsnapped) vertices.
  double z0, dzdx, dzdy;
  std::uint32_t primitive;

  bool covers(int px, int py) const {
    const std::int64_t x = static_cast<std::int64_t>(px) * kSubpixelScale;
    const std::int64_t y = static_cast<std::int64_t>(py) * kSubpixelScale;
    return a[0] * x + b[0] * y + c[0] > 0 && a[1] * x + b[1] * y + c[1] > 0 &&
           a[2] * x + b[2] * y + c[2] > 0;
  }
  float depth(int px, int py) const {
    const double z = z0 + dzdx * px + dzdy * py;
    return static_cast<float>(z < 0.0 ? 0.0 : (z > 1.0 ? 1.0 : z));
  }
};

// A chunk's set-up triangles (SetupChunk::triangles), in storage made for them.
using RasterTriangles = std::vector<RasterTriangle, TriangleStorageAllocator<RasterTriangle>>;

// What set-up computes for each vertex of a triangle that needs no clipping, computed once per
// vertex for vertices [begin, begin + flags.size()) of a vertex buffer (SoA, element k - begin)
// rather than once per triangle and vertex (TriangleSetup::prepare_vertices). The values are
// exactly setup_clip's, so a triangle set up from them gives the same RasterTriangle.
struct PreparedVertices {
  enum : std::uint8_t {
    kValid = 1,    // valid (GridTriangles::valid; no condition: 1)
    kDrawn = 2,    // valid and flagged kDraw (GridTriangles::need; no condition: valid)
    kPlain = 4,    // plain_clip_vertex: prepare_clip_input keeps it as it is
    kSnapped = 8,  // kPlain, outcode 0, window x and y within the snap limit: floor_x, floor_y,
                   // z, fx, fy are set (else they are unspecified)
  };
  // The passes' intermediate bits (SnapKernels::window): the flags above in bits 0-2,
  // clip_outcode in bits 8-13 (the near and far bits; the others where float left them
  // undecided), and kGuardUndecided where float could not decide the guard-band bits.
  static constexpr std::uint32_t kOutcodeShift = 8;
  static constexpr std::uint32_t kGuardUndecided = 1u << 16;

  std::size_t begin = 0;
  std::vector<std::uint8_t> flags;
  std::vector<std::uint8_t> outcode;  // clip_outcode (set when kPlain)
  // From to_window's float window coordinates x, y, z: floor(x), floor(y) (floats: exact),
  // z, and the snapped snap_to_fixed(x), snap_to_fixed(y).
  std::vector<float> floor_x, floor_y, z;
  std::vector<std::int32_t> fx, fy;
  // Scratch of the passes: window x and y, and the intermediate bits.
  std::vector<float> window_x, window_y;
  std::vector<std::uint32_t> bits;

  void resize(std::size_t n);
};

// The per-frame constants of the per-vertex passes: the guard band in clip units, and the
// viewport transform (to_window).
struct SnapConstants {
  float guard_x, guard_y;
  float scale_x, scale_y, translate_x, translate_y;
};

// prepare_vertices' two per-vertex passes over n vertices, as a backend may supply them (the
// simd backend's Highway kernels); each must give its values bit for bit. Between them,
// prepare_vertices computes the whole outcode of the few vertices marked kGuardUndecided.
struct SnapKernels {
  // Window coordinates (to_window) and the intermediate bits. valid and need may be null (all
  // valid; all drawn), else bit kDraw = 2 of need marks a drawn vertex.
  void (*window)(const SnapConstants& constants, const float* x, const float* y, const float* z,
                 const float* w, const std::uint8_t* valid, const std::uint8_t* need, std::size_t n,
                 float* window_x, float* window_y, float* window_z, std::uint32_t* bits);
  // The flags, outcodes, floors and snapped coordinates from the window coordinates and bits.
  void (*snap)(std::size_t n, const std::uint32_t* bits, const float* window_x,
               const float* window_y, std::uint8_t* flags, std::uint8_t* outcode, float* floor_x,
               float* floor_y, std::int32_t* fx, std::int32_t* fy);
};

// The pixel region and face culling of a raster state, as the edge set-up applies them.
struct EdgeRules {
  int region_x0 = 0, region_y0 = 0, region_x1 = -1, region_y1 = -1;  // inclusive pixel region
  bool cull_counter_clockwise = false, cull_clockwise = false;       // by the snapped area's sign
};

// Per-frame constants of setup, derived from the raster state.
class TriangleSetup {
 public:
  explicit TriangleSetup(const RasterState& state);

  // Appends the rasterisable pieces of one clip-space triangle (none if culled, clipped away,
  // zero-area or outside the pixel region; several if clipping made a polygon).
  void setup_clip(std::uint32_t primitive, const ClipVertex v[3],
                  std::vector<RasterTriangle>& out) const;

  // Prepares vertices [begin, end) of `vertices` into `out` (out.begin = begin), with their
  // validity (valid empty: all valid) and draw flag (need empty: all drawn; else bit kDraw = 2
  // of need[k]), as GridTriangles reads them.
  void prepare_vertices(ClipVertices vertices, std::size_t begin, std::size_t end,
                        std::span<const std::uint8_t> valid, std::span<const std::uint8_t> need,
                        PreparedVertices& out) const;

  // prepare_vertices through `kernels` from now on (null: the portable loops); the values are
  // the same.
  void set_snap_kernels(const SnapKernels* kernels) { snap_kernels_ = kernels; }
  SnapConstants snap_constants() const;

  // setup_chunk for the grid: the drawn triangles among [begin, end) of `source` set up in
  // order, each exactly as setup_clip would set it up, appended to `out`; `submitted` counts
  // the drawn ones. `prepared` covers the vertices of those triangles
  // (GridTriangles::vertex_span), prepared from the same `vertices`, source.valid and
  // source.need.
  void setup_grid(ClipVertices vertices, const GridTriangles& source, std::uint32_t begin,
                  std::uint32_t end, const PreparedVertices& prepared, std::uint32_t& submitted,
                  RasterTriangles& out) const;

  // The same for an index list: the drawn triangles among [begin, end) of `source`, each as
  // setup_clip would set it up, from vertices prepared in blocks of `block_vertices` (a power
  // of two; vertex k
  // in blocks[k / block_vertices] at k % block_vertices, prepared with no valid or need
  // condition or with the ones that hold), once per frame instead of once per triangle.
  void setup_indexed(ClipVertices vertices, const IndexedTriangles& source, std::uint32_t begin,
                     std::uint32_t end, std::span<const PreparedVertices> blocks,
                     std::size_t block_vertices, std::uint32_t& submitted,
                     RasterTriangles& out) const;

  // Appends one triangle given in window coordinates (precondition: within the guard band; a
  // triangle with a coordinate beyond it or NaN is dropped, never snapped).
  void setup_window(std::uint32_t primitive, const float x[3], const float y[3], const float z[3],
                    std::vector<RasterTriangle>& out) const;

  // Window x, y, z of a clip-space vertex: x/w * scale + translate, in float, in the order GL
  // implementations evaluate it. Precondition: w > 0 and |x|, |y| within the guard band times
  // w (an input vertex inside every clip plane, after prepare_clip_input).
  void to_window(const ClipVertex& v, float& x, float& y, float& z) const;

  // Window x, y of a vertex made by clipping, in double (precondition: w > 0, as clip_triangle
  // guarantees).
  void to_window(const PolygonVertex& v, double& x, double& y) const;

 private:
  // Edge functions and pixel bounds of a snapped triangle (made counter-clockwise: `swapped`
  // tells whether vertices 1 and 2 were exchanged); false when it is culled, has zero area or
  // covers no pixel centre of the region.
  bool set_up_edges(std::int32_t fx[3], std::int32_t fy[3], RasterTriangle& t, bool& swapped) const;
  // The pieces of a triangle that is not rejected: `polygon` and `count` from clip_triangle
  // (for a triangle inside every plane, the three input vertices, of which only `source` is
  // set), `v` the prepared input.
  void setup_polygon(std::uint32_t primitive, const ClipVertex v[3],
                     const PolygonVertex polygon[kMaxClippedVertices], int count,
                     std::vector<RasterTriangle>& out) const;
  // The depth plane of a piece, as setup_polygon gives it: from the original triangle `v` and
  // the window coordinates of the polygon's first vertex.
  void piece_depth(const ClipVertex v[3], double first_x, double first_y, double first_z,
                   double& z0, double& dzdx, double& dzdy) const;
  // Depth plane of the original triangle: z = z_ref + dzdx (x - u0) + dzdy (y - v0) in window
  // coordinates; false where it is undefined (the triangle is seen edge-on).
  bool depth_plane(const ClipVertex v[3], double u0, double v0, double& z_ref, double& dzdx,
                   double& dzdy) const;

  ClipPlanes planes_;
  float scale_x_, scale_y_, translate_x_, translate_y_;
  EdgeRules edge_rules_;
  const SnapKernels* snap_kernels_ = nullptr;
};

// Round-half-to-even of (coordinate - 0.5) * 256 in float: llvmpipe's snapping, exactly.
std::int32_t snap_to_fixed(float window_coordinate);

// The same in double, for vertices made by clipping (precondition: |coordinate| < 2^22).
std::int32_t snap_double_to_fixed(double window_coordinate);

}  // namespace relief::raster
