#include "tools/crosscheck.h"

#include <algorithm>
#include <cmath>

namespace relief {

namespace {

// The angle between two vectors in degrees, atan2(|a x b|, a . b): accurate for tiny angles,
// where acos of the dot product loses them. 0 where either is zero.
double angle_deg(double ax, double ay, double az, double bx, double by, double bz) {
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
  const double dot = ax * bx + ay * by + az * bz;
  if (cross == 0 && dot == 0) {
    return 0;
  }
  return std::atan2(cross, dot) * 180.0 / 3.14159265358979323846;
}

// An image's channels as floats, rows as stored.
FloatImage float_image(int width, int height, int channels, const std::vector<float>& values) {
  FloatImage image{width, height, channels, {}, values};
  return image;
}

FloatImage srgb_image(const FrameImage& frame) {
  std::vector<float> values(frame.srgb.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    values[k] = float(frame.srgb[k]) / 255.0f;
  }
  return float_image(frame.width, frame.height, 3, values);
}

// max(current, |a - b|), NaN-aware: a NaN on either side makes the difference infinite.
double worse(double current, double a, double b) {
  const double d = std::abs(a - b);
  return std::isnan(d) ? HUGE_VAL : std::max(current, d);
}

}  // namespace

GridDifference compare_grids(const GridBuffers<float>& cpu, const GridBuffers<float>& gl) {
  GridDifference d;
  const std::size_t n = std::min(cpu.valid.size(), gl.valid.size());
  d.height_error.assign(n, 0.0f);
  double sum_sq = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const bool a = cpu.valid[k] != 0, b = gl.valid[k] != 0;
    if (a != b) {
      ++d.valid_mismatch;
    }
    if (!a || !b) {
      continue;
    }
    ++d.vertices;
    const double dh = std::abs(double(cpu.height[k]) - double(gl.height[k]));
    d.height_error[k] = static_cast<float>(dh);
    d.max_height_error = worse(d.max_height_error, cpu.height[k], gl.height[k]);
    sum_sq += dh * dh;
    d.max_octave_error = worse(d.max_octave_error, cpu.nu[k], gl.nu[k]);
    const double angle = angle_deg(cpu.nx[k], cpu.ny[k], cpu.nz[k], gl.nx[k], gl.ny[k], gl.nz[k]);
    d.max_normal_angle_deg = std::isnan(angle) ? HUGE_VAL : std::max(d.max_normal_angle_deg, angle);
  }
  d.rms_height_error = d.vertices == 0 ? 0.0 : std::sqrt(sum_sq / double(d.vertices));
  return d;
}

FrameDifference compare_frames(const FrameImage& cpu, const FrameImage& gl,
                               const CompareThresholds& thresholds) {
  FrameDifference d;
  const FloatImage cpu_srgb = srgb_image(cpu), gl_srgb = srgb_image(gl);
  d.srgb = compare_images(cpu_srgb, gl_srgb, thresholds);
  if (cpu.width != gl.width || cpu.height != gl.height) {
    return d;
  }
  d.srgb_difference = largest_channel_difference(cpu_srgb, gl_srgb);
  d.linear = compare_images(float_image(cpu.width, cpu.height, 3, cpu.linear),
                            float_image(gl.width, gl.height, 3, gl.linear), thresholds);
  d.pixels = std::uint64_t(cpu.width) * std::uint64_t(cpu.height);
  for (std::size_t k = 0; k < d.pixels; ++k) {
    if (cpu.primitive[k] != gl.primitive[k]) {
      ++d.primitive_mismatch;
      continue;
    }
    if (cpu.primitive[k] == 0xffffffffu) {
      continue;  // background in both
    }
    d.max_depth_error = worse(d.max_depth_error, cpu.depth[k], gl.depth[k]);
    d.max_height_error = worse(d.max_height_error, cpu.world_height[k], gl.world_height[k]);
    d.max_octave_error = worse(d.max_octave_error, cpu.octaves[k], gl.octaves[k]);
    const float* a = &cpu.normal[3 * k];
    const float* b = &gl.normal[3 * k];
    const double angle = angle_deg(a[0], a[1], a[2], b[0], b[1], b[2]);
    d.max_normal_angle_deg = std::isnan(angle) ? HUGE_VAL : std::max(d.max_normal_angle_deg, angle);
  }
  return d;
}

}  // namespace relief
