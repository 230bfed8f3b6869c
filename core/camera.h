// The camera in double precision (docs/architecture.md, Conventions): world axes right-handed, y
// up, OpenGL view convention (the camera looks along -z when yaw = pitch = 0).
#pragma once

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace relief {

struct CameraFrame {
  glm::dvec3 position;  // world, double: the only absolute position in a frame
  glm::dvec3 forward;   // unit view direction
  glm::dvec3 right;     // unit, horizontal (no roll)
  glm::dvec3 up;        // unit, right x forward
  double tan_half_fov_y = 0;
  double tan_half_fov_x = 0;
  double aspect = 1;  // viewport width / height
  double near = 0;
  double far = 0;
};

// forward = (sin yaw cos pitch, sin pitch, -cos yaw cos pitch), right = (cos yaw, 0, sin yaw),
// up = right x forward. Defined for every pitch in [-90, 90], straight down included.
CameraFrame make_camera_frame(const CameraSettings& camera, const ViewportSettings& viewport);

}  // namespace relief
