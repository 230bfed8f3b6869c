#include "core/camera.h"

#include <cmath>

namespace relief {

CameraFrame make_camera_frame(const CameraSettings& camera, const ViewportSettings& viewport) {
  const double yaw = camera.yaw_deg * (M_PI / 180.0);
  const double pitch = camera.pitch_deg * (M_PI / 180.0);
  CameraFrame frame;
  frame.position = glm::dvec3(camera.position[0], camera.position[1], camera.position[2]);
  frame.forward = glm::dvec3(std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                             -std::cos(yaw) * std::cos(pitch));
  frame.right = glm::dvec3(std::cos(yaw), 0.0, std::sin(yaw));
  frame.up = glm::cross(frame.right, frame.forward);
  frame.aspect = static_cast<double>(viewport.width) / static_cast<double>(viewport.height);
  frame.tan_half_fov_y = std::tan(camera.fov_y_deg * (M_PI / 360.0));
  frame.tan_half_fov_x = frame.tan_half_fov_y * frame.aspect;
  frame.near = camera.near;
  frame.far = camera.far;
  return frame;
}

}  // namespace relief
