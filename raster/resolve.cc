#include "raster/resolve.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace relief::raster {

VertexPositions VertexPositions::from_clip(ClipVertices clip, const Viewport& viewport) {
  VertexPositions p;
  p.x_ = clip.x;
  p.y_ = clip.y;
  p.w_ = clip.w;
  p.scale_x_ = viewport.width * 0.5;
  p.scale_y_ = viewport.height * 0.5;
  p.translate_x_ = viewport.x + viewport.width * 0.5;
  p.translate_y_ = viewport.y + viewport.height * 0.5;
  return p;
}

VertexPositions VertexPositions::from_window(WindowVertices window) {
  VertexPositions p;
  p.x_ = window.x;
  p.y_ = window.y;
  p.window_ = true;
  return p;
}

void VertexPositions::get(std::uint32_t v, double& x, double& y, double& w) const {
  if (window_) {
    x = x_[v];
    y = y_[v];
    w = 1.0;
    return;
  }
  w = w_[v];
  x = x_[v] * scale_x_ + w * translate_x_;
  y = y_[v] * scale_y_ + w * translate_y_;
}

PerspectivePlane::PerspectivePlane(const double x[3], const double y[3], const double w[3]) {
  for (int i = 0; i < 3; ++i) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    // (X_a - u W_a)(Y_b - v W_b) - (Y_a - v W_a)(X_b - u W_b)
    k[i] = x[a] * y[b] - y[a] * x[b];
    ku[i] = y[a] * w[b] - w[a] * y[b];
    kv[i] = w[a] * x[b] - x[a] * w[b];
  }
}

bool PerspectivePlane::barycentrics(double u, double v, double b[3]) const {
  const double l0 = k[0] + ku[0] * u + kv[0] * v;
  const double l1 = k[1] + ku[1] * u + kv[1] * v;
  const double l2 = k[2] + ku[2] * u + kv[2] * v;
  const double sum = l0 + l1 + l2;
  if (!(std::abs(sum) > 0.0) || !std::isfinite(sum)) {
    return false;
  }
  const double inv_sum = 1.0 / sum;
  b[0] = l0 * inv_sum;
  b[1] = l1 * inv_sum;
  b[2] = l2 * inv_sum;
  return std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]);
}

QuadWeights quad_weights(const PerspectivePlane& plane, int px, int py) {
  QuadWeights q;
  if (!plane.barycentrics(px + 0.5, py + 0.5, q.b)) {
    q.b[0] = q.b[1] = q.b[2] = 1.0 / 3.0;
  }
  // Quad partners: same row, the other column of the quad; same column, other row.
  q.has_x = plane.barycentrics((px ^ 1) + 0.5, py + 0.5, q.bx);
  q.has_y = plane.barycentrics(px + 0.5, (py ^ 1) + 0.5, q.by);
  q.sign_x = (px & 1) ? -1.0 : 1.0;
  q.sign_y = (py & 1) ? -1.0 : 1.0;
  return q;
}

template <class Source>
void resolve(const VisibilityBuffer& visibility, const VertexPositions& positions,
             const Source& source, std::span<const std::span<const float>> attributes,
             std::size_t derivative_streams, ResolvedFrame& out) {
  const int width = visibility.width;
  const int height = visibility.height;
  const std::size_t size = static_cast<std::size_t>(width) * height;
  const std::size_t streams = attributes.size();
  out.width = width;
  out.height = height;
  out.b0.assign(size, 0.0f);
  out.b1.assign(size, 0.0f);
  out.b2.assign(size, 0.0f);
  out.value.assign(streams, AlignedVector<float>(size, 0.0f));
  derivative_streams = std::min(derivative_streams, streams);
  out.ddx.assign(derivative_streams, AlignedVector<float>(size, 0.0f));
  out.ddy.assign(derivative_streams, AlignedVector<float>(size, 0.0f));
  const int quad_rows = (height + 1) / 2;
  tbb::parallel_for(tbb::blocked_range<int>(0, quad_rows), [&](const tbb::blocked_range<int>& r) {
    std::uint32_t cached = kNoPrimitive;
    std::uint32_t v[3] = {0, 0, 0};
    const double zero[3] = {0, 0, 0};
    PerspectivePlane plane(zero, zero, zero);
    for (int py = 2 * r.begin(); py < std::min(height, 2 * r.end()); ++py) {
      for (int px = 0; px < width; ++px) {
        const std::size_t k = visibility.index(px, py);
        const std::uint32_t primitive = visibility.primitive[k];
        if (primitive == kNoPrimitive) {
          continue;
        }
        // Neighbouring pixels mostly share their triangle: set its plane up once per run.
        if (primitive != cached) {
          cached = primitive;
          source.vertices(primitive, v);
          double x[3], y[3], w[3];
          for (int i = 0; i < 3; ++i) {
            positions.get(v[i], x[i], y[i], w[i]);
          }
          plane = PerspectivePlane(x, y, w);
        }
        const QuadWeights q = quad_weights(plane, px, py);
        out.b0[k] = static_cast<float>(q.b[0]);
        out.b1[k] = static_cast<float>(q.b[1]);
        out.b2[k] = static_cast<float>(q.b[2]);
        for (std::size_t s = 0; s < streams; ++s) {
          const std::span<const float> a = attributes[s];
          const double value = QuadWeights::at(q.b, a[v[0]], a[v[1]], a[v[2]]);
          out.value[s][k] = static_cast<float>(value);
          if (s >= derivative_streams) {
            continue;
          }
          if (q.has_x) {
            const double other = QuadWeights::at(q.bx, a[v[0]], a[v[1]], a[v[2]]);
            out.ddx[s][k] = static_cast<float>(q.sign_x * (other - value));
          }
          if (q.has_y) {
            const double other = QuadWeights::at(q.by, a[v[0]], a[v[1]], a[v[2]]);
            out.ddy[s][k] = static_cast<float>(q.sign_y * (other - value));
          }
        }
      }
    }
  });
}

template void resolve<IndexedTriangles>(const VisibilityBuffer&, const VertexPositions&,
                                        const IndexedTriangles&,
                                        std::span<const std::span<const float>>, std::size_t,
                                        ResolvedFrame&);
template void resolve<GridTriangles>(const VisibilityBuffer&, const VertexPositions&,
                                     const GridTriangles&, std::span<const std::span<const float>>,
                                     std::size_t, ResolvedFrame&);

}  // namespace relief::raster
