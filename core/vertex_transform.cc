#include "core/vertex_transform.h"

#include "core/stage_params.h"
#include "core/vertex_culling.h"

namespace relief {

ClipTransform make_clip_transform(const CameraFrame& camera) {
  const double sx = 1.0 / camera.tan_half_fov_x;
  const double sy = 1.0 / camera.tan_half_fov_y;
  ClipTransform t;
  for (int c = 0; c < 3; ++c) {
    t.row_x[c] = camera.right[c] * sx;
    t.row_y[c] = camera.up[c] * sy;
    t.row_w[c] = camera.forward[c];
  }
  t.z_clip = camera.near;
  return t;
}

template <class Real>
void transform_vertices(const TransformParams<Real>& t, IndexRange range, std::span<const Real> dx,
                        std::span<const Real> dz, std::span<const Real> height,
                        std::span<const std::uint8_t> need, ClipSpans<Real> clip) {
  const Real x0 = t.row_x[0], x1 = t.row_x[1], x2 = t.row_x[2];
  const Real y0 = t.row_y[0], y1 = t.row_y[1], y2 = t.row_y[2];
  const Real w0 = t.row_w[0], w1 = t.row_w[1], w2 = t.row_w[2];
  const Real z = t.z_clip;
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (!need.empty() && !(need[k] & kDraw)) {
      clip.x[k] = clip.y[k] = clip.z[k] = clip.w[k] = Real(0);  // in no drawn triangle
      continue;
    }
    const Real px = dx[k];
    const Real py = height[k];
    const Real pz = dz[k];
    clip.x[k] = x0 * px + x1 * py + x2 * pz;
    clip.y[k] = y0 * px + y1 * py + y2 * pz;
    clip.z[k] = z;
    clip.w[k] = w0 * px + w1 * py + w2 * pz;
  }
}

template <class Real>
void light_vertices(const TransformParams<Real>& t, IndexRange range, std::span<const Real> nx,
                    std::span<const Real> ny, std::span<const Real> nz,
                    std::span<const std::uint8_t> need, std::span<Real> lambert) {
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (!need.empty() && !(need[k] & kDraw)) {
      lambert[k] = Real(0);
      continue;
    }
    const Real ndl = (nx[k] * t.sun_x + ny[k] * t.sun_y) + nz[k] * t.sun_z;
    lambert[k] = ndl > Real(0) ? ndl : Real(0);
  }
}

template void light_vertices<float>(const TransformParams<float>&, IndexRange,
                                    std::span<const float>, std::span<const float>,
                                    std::span<const float>, std::span<const std::uint8_t>,
                                    std::span<float>);
template void light_vertices<double>(const TransformParams<double>&, IndexRange,
                                     std::span<const double>, std::span<const double>,
                                     std::span<const double>, std::span<const std::uint8_t>,
                                     std::span<double>);
template void transform_vertices<float>(const TransformParams<float>&, IndexRange,
                                        std::span<const float>, std::span<const float>,
                                        std::span<const float>, std::span<const std::uint8_t>,
                                        ClipSpans<float>);
template void transform_vertices<double>(const TransformParams<double>&, IndexRange,
                                         std::span<const double>, std::span<const double>,
                                         std::span<const double>, std::span<const std::uint8_t>,
                                         ClipSpans<double>);

}  // namespace relief
