#include "eval/frame_comparison.h"

#include <algorithm>
#include <cmath>

namespace relief {

namespace {

// The angle between two vectors in degrees, atan2(|a x b|, a . b): accurate for tiny angles,
// where acos of the dot product loses them. 0 where both the cross and the dot product are 0.
double angle_deg(double ax, double ay, double az, double bx, double by, double bz) {
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
  const double dot = ax * bx + ay * by + az * bz;
  if (cross == 0 && dot == 0) {
    return 0;
  }
  return std::atan2(cross, dot) * 180.0 / 3.14159265358979323846;
}

// max(current, |a - b|); a NaN on either side makes the difference infinite.
double worse(double current, double a, double b) {
  const double d = std::abs(a - b);
  return std::isnan(d) ? HUGE_VAL : std::max(current, d);
}

double worse_angle(double current, const float* a, const float* b) {
  const double angle = angle_deg(a[0], a[1], a[2], b[0], b[1], b[2]);
  return std::isnan(angle) ? HUGE_VAL : std::max(current, angle);
}

}  // namespace

GridDifference compare_grids(const GridBuffers<float>& a, const GridBuffers<float>& b) {
  GridDifference d;
  const std::size_t n = std::min(a.valid.size(), b.valid.size());
  d.height_error.assign(n, 0.0f);
  double sum_sq = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const bool in_a = a.valid[k] != 0, in_b = b.valid[k] != 0;
    if (in_a != in_b) {
      ++d.valid_mismatch;
    }
    if (!in_a || !in_b) {
      continue;
    }
    ++d.vertices;
    const double dh = std::abs(double(a.height[k]) - double(b.height[k]));
    d.height_error[k] = static_cast<float>(dh);
    d.max_height_error = worse(d.max_height_error, a.height[k], b.height[k]);
    sum_sq += dh * dh;
    d.max_octave_error = worse(d.max_octave_error, a.nu[k], b.nu[k]);
    const float na[3] = {a.nx[k], a.ny[k], a.nz[k]}, nb[3] = {b.nx[k], b.ny[k], b.nz[k]};
    d.max_normal_angle_deg = worse_angle(d.max_normal_angle_deg, na, nb);
  }
  d.rms_height_error = d.vertices == 0 ? 0.0 : std::sqrt(sum_sq / double(d.vertices));
  return d;
}

PixelDifference compare_pixels(const FrameImage& a, const FrameImage& b) {
  PixelDifference d;
  if (a.width != b.width || a.height != b.height) {
    return d;
  }
  d.pixels = std::uint64_t(a.width) * std::uint64_t(a.height);
  double sum_sq = 0;
  for (std::size_t k = 0; k < a.srgb.size() && k < b.srgb.size(); ++k) {
    const double e = std::abs(double(a.srgb[k]) - double(b.srgb[k]));
    d.max_srgb_error = std::max(d.max_srgb_error, e);
    sum_sq += (e / 255) * (e / 255);
  }
  const double rms = a.srgb.empty() ? 0.0 : std::sqrt(sum_sq / double(a.srgb.size()));
  d.srgb_psnr = rms == 0 ? HUGE_VAL : 20 * std::log10(1.0 / rms);
  for (std::size_t k = 0; k < d.pixels; ++k) {
    if (a.primitive[k] != b.primitive[k]) {
      ++d.primitive_mismatch;
      continue;
    }
    if (a.primitive[k] == 0xffffffffu) {
      continue;  // background in both
    }
    d.max_depth_error = worse(d.max_depth_error, a.depth[k], b.depth[k]);
    d.max_height_error = worse(d.max_height_error, a.world_height[k], b.world_height[k]);
    d.max_octave_error = worse(d.max_octave_error, a.octaves[k], b.octaves[k]);
    d.max_normal_angle_deg =
        worse_angle(d.max_normal_angle_deg, &a.normal[3 * k], &b.normal[3 * k]);
  }
  return d;
}

}  // namespace relief
