// Stage 5: vertex transform (docs/architecture.md). Displaced grid vertices to clip space.
//
// Camera-relative position p = (dx, h, dz), h the camera-relative height of stage 3 (float: the
// camera's absolute position never meets a per-vertex value), then one 4x3 matrix: view rotation
// and an infinite reverse-Z perspective projection, for glClipControl(GL_LOWER_LEFT,
// GL_ZERO_TO_ONE):
//   x_clip = p . right   * (1 / (tan(fov_y / 2) aspect))
//   y_clip = p . up      * (1 / tan(fov_y / 2))
//   z_clip = near                       (so depth z/w = near / distance: 1 at the near
//   w_clip = p . forward                 plane, falling to 0 at infinity; no far plane)
// The rows are formed in double once per frame (FramePlan) and rounded to float once.
#pragma once

#include <cstdint>
#include <span>

#include "core/camera.h"
#include "core/grid_buffers.h"

namespace relief {

struct ClipTransform {
  double row_x[3];  // x_clip = row_x . p
  double row_y[3];
  double row_w[3];
  double z_clip;  // the near distance
};

ClipTransform make_clip_transform(const CameraFrame& camera);

template <class Real>
struct ClipSpans {
  std::span<Real> x, y, z, w;
};

template <class Real>
struct TransformParams;  // stage_params.h: ClipTransform's rows, rounded once

// clip[k] for k in range, from camera-relative (dx, dz) and camera-relative height h, where
// need[k] has kDraw (core/vertex_culling.h; elsewhere 0); `need` empty: everywhere.
template <class Real>
void transform_vertices(const TransformParams<Real>& params, IndexRange range,
                        std::span<const Real> dx, std::span<const Real> dz,
                        std::span<const Real> height, std::span<const std::uint8_t> need,
                        ClipSpans<Real> clip);

// Gouraud shading (shading.mode = gradient; castledragmire lights each vertex and lets the
// triangle interpolate): the Lambert term of each drawn vertex,
//   lambert[k] = max(0, (nx sun_x + ny sun_y) + nz sun_z)
// from its stage-4 normal (a planet's bent one) and params.sun_*, where need[k] has kDraw
// (`need` empty: everywhere), else 0. Stage 5 runs it beside the transform where
// params.gouraud is set, as GL's fixed-function vertex stage lit vertices.
template <class Real>
void light_vertices(const TransformParams<Real>& params, IndexRange range, std::span<const Real> nx,
                    std::span<const Real> ny, std::span<const Real> nz,
                    std::span<const std::uint8_t> need, std::span<Real> lambert);

}  // namespace relief
