#include "tools/panorama.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/srgb.h"

namespace relief {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

// The view's pixel coordinates of direction d (pixel centres at integers + 1/2 of the GL
// convention, here at integers: px = (x_ndc + 1) side / 2 - 1/2), or false where d is behind
// the view. Domain: dot(d, forward) > 0 (divided by).
bool view_coordinates(const PanoramaFace& f, const glm::dvec3& d, double& px, double& py) {
  const double z = glm::dot(d, f.camera.forward);
  if (!(z > 0.0)) {
    return false;
  }
  const double x_ndc = glm::dot(d, f.camera.right) / z / f.camera.tan_half_fov_x;
  const double y_ndc = glm::dot(d, f.camera.up) / z / f.camera.tan_half_fov_y;
  px = (x_ndc + 1.0) * 0.5 * f.side - 0.5;
  py = (y_ndc + 1.0) * 0.5 * f.side - 0.5;
  return true;
}

// Bilinear linear radiance at (px, py), the taps clamped to the view.
void bilinear(const PanoramaFace& f, double px, double py, double rgb[3]) {
  const double x0 = std::floor(px), y0 = std::floor(py);
  const double tx = px - x0, ty = py - y0;
  const auto tap = [&](double x, double y, int c) {
    const int i = std::clamp(int(x), 0, f.side - 1), j = std::clamp(int(y), 0, f.side - 1);
    return double(f.linear[(std::size_t(j) * std::size_t(f.side) + std::size_t(i)) * 3 + c]);
  };
  for (int c = 0; c < 3; ++c) {
    const double bottom = tap(x0, y0, c) + tx * (tap(x0 + 1, y0, c) - tap(x0, y0, c));
    const double top = tap(x0, y0 + 1, c) + tx * (tap(x0 + 1, y0 + 1, c) - tap(x0, y0 + 1, c));
    rgb[c] = bottom + ty * (top - bottom);
  }
}

struct RowSeams {
  std::uint64_t directions = 0;
  std::uint64_t sum = 0;
  int max = 0;
};

}  // namespace

PanoramaViews panorama_views(const CameraSettings& camera, int side) {
  PanoramaViews views;
  views.viewport.width = side;
  views.viewport.height = side;
  // tan(half fov) = side / (side - 2 margin): the central side - 2 margin pixels span 90 degrees.
  const double fov =
      2.0 * std::atan(double(side) / double(side - 2 * kPanoramaFaceMargin)) * kDegrees;
  for (int k = 0; k < 6; ++k) {
    CameraSettings face = camera;
    face.fov_y_deg = fov;
    // yaw within [-180, 180): the scene's range holds it.
    face.yaw_deg = k < 4 ? std::remainder(camera.yaw_deg + 90.0 * k, 360.0) : camera.yaw_deg;
    face.pitch_deg = k < 4 ? 0.0 : (k == 4 ? 90.0 : -90.0);
    views.cameras.push_back(face);
  }
  return views;
}

Panorama resample_panorama(const std::vector<PanoramaFace>& faces, double yaw_deg, int width) {
  Panorama out;
  out.width = width;
  out.height = width / 2;
  out.srgb.resize(std::size_t(out.width) * std::size_t(out.height) * 3);
  std::vector<RowSeams> rows(std::size_t(out.height));
  const double yaw = yaw_deg / kDegrees;
  tbb::parallel_for(tbb::blocked_range<int>(0, out.height), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j) {
      const double latitude = ((j + 0.5) / out.height - 0.5) * std::numbers::pi;
      RowSeams& seams = rows[std::size_t(j)];
      for (int i = 0; i < out.width; ++i) {
        const double turn = yaw + ((i + 0.5) / out.width - 0.5) * 2.0 * std::numbers::pi;
        // The camera's forward at yaw `turn` and pitch `latitude` (core/camera.h).
        const glm::dvec3 d(std::sin(turn) * std::cos(latitude), std::sin(latitude),
                           -std::cos(turn) * std::cos(latitude));
        // The view d is most central in, then the next: a cube face and its neighbour.
        std::size_t best = 0, second = 1;
        double best_z = -2.0, second_z = -2.0;
        for (std::size_t f = 0; f < faces.size(); ++f) {
          const double z = glm::dot(d, faces[f].camera.forward);
          if (z > best_z) {
            second = best, second_z = best_z;
            best = f, best_z = z;
          } else if (z > second_z) {
            second = f, second_z = z;
          }
        }
        double px = 0, py = 0, rgb[3];
        view_coordinates(faces[best], d, px, py);  // best_z >= 1/sqrt(3): in front
        bilinear(faces[best], px, py, rgb);
        std::uint8_t* pixel =
            &out.srgb[(std::size_t(j) * std::size_t(out.width) + std::size_t(i)) * 3];
        for (int c = 0; c < 3; ++c) {
          pixel[c] = srgb_byte(float(rgb[c]));
        }
        // The seam: the neighbour holds d within its margin (both taps inside its image).
        double qx = 0, qy = 0, other[3];
        const int last = faces[second].side - 1;
        if (view_coordinates(faces[second], d, qx, qy) && qx >= 0 && qy >= 0 && qx < last &&
            qy < last) {
          bilinear(faces[second], qx, qy, other);
          int worst = 0;
          for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(int(pixel[c]) - int(srgb_byte(float(other[c])))));
          }
          ++seams.directions;
          seams.sum += std::uint64_t(worst);
          seams.max = std::max(seams.max, worst);
        }
      }
    }
  });
  std::uint64_t sum = 0;
  for (const RowSeams& r : rows) {  // in row order: the same figures for any thread count
    out.seams.directions += r.directions;
    sum += r.sum;
    out.seams.max_codes = std::max(out.seams.max_codes, r.max);
  }
  out.seams.mean_codes =
      out.seams.directions > 0 ? double(sum) / double(out.seams.directions) : 0.0;
  return out;
}

}  // namespace relief
