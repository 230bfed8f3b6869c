#include "eval/flicker.h"

#include <cmath>
#include <numbers>

namespace relief {

std::string_view camera_move_name(CameraMove move) {
  return move == CameraMove::kForward ? "forward" : "turn";
}

Scene moved_scene(const Scene& scene, CameraMove move, double step, int k) {
  Scene out = scene;
  if (move == CameraMove::kTurn) {
    out.camera.yaw_deg = scene.camera.yaw_deg + double(k) * step;
    return out;
  }
  // The camera's horizontal forward direction (core/camera.cc: forward's x and z at pitch 0).
  const double yaw = scene.camera.yaw_deg * (std::numbers::pi / 180.0);
  out.camera.position[0] = scene.camera.position[0] + double(k) * step * std::sin(yaw);
  out.camera.position[2] = scene.camera.position[2] - double(k) * step * std::cos(yaw);
  return out;
}

FlickerReport summarise_flicker(std::vector<FlickerFrame> frames) {
  FlickerReport report;
  const std::size_t values = kDistanceBands + 1;
  report.realtime_change.assign(values, 0.0);
  report.truth_change.assign(values, 0.0);
  report.mean_flip.assign(values, 0.0);
  report.change_frames.assign(values, 0);
  report.flip_frames.assign(values, 0);
  for (const FlickerFrame& f : frames) {
    for (std::size_t b = 0; b < values; ++b) {
      // The band's pixels in this frame (its bands and its change's: the same truth's).
      const BandError& e = b < kDistanceBands ? f.error.bands[b] : f.error.all;
      if (e.pixels == 0) {
        continue;
      }
      report.mean_flip[b] += e.mean_flip;
      ++report.flip_frames[b];
      if (!f.realtime.empty()) {
        report.realtime_change[b] += f.realtime[b];
        report.truth_change[b] += f.truth[b];
        ++report.change_frames[b];
      }
    }
  }
  for (std::size_t b = 0; b < values; ++b) {  // the divisions' domain: counts > 0
    if (report.flip_frames[b] > 0) {
      report.mean_flip[b] /= double(report.flip_frames[b]);
    }
    if (report.change_frames[b] > 0) {
      report.realtime_change[b] /= double(report.change_frames[b]);
      report.truth_change[b] /= double(report.change_frames[b]);
    }
  }
  report.frames = std::move(frames);
  return report;
}

}  // namespace relief
