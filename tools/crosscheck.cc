#include "tools/crosscheck.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/srgb.h"

namespace relief {

namespace {

FloatImage srgb_image(const FrameImage& frame) {
  FloatImage image{frame.width, frame.height, 3, {}, std::vector<float>(frame.srgb.size())};
  for (std::size_t k = 0; k < frame.srgb.size(); ++k) {
    image.pixels[k] = float(frame.srgb[k]) / 255.0f;
  }
  return image;
}

// Whether pixel (x, y) of the CPU's frame is on the framebuffer's border or has an 8-neighbour
// drawn by another triangle (or by none): where snapping may hand it to another triangle.
bool on_triangle_boundary(const FrameImage& cpu, int x, int y) {
  if (x == 0 || y == 0 || x == cpu.width - 1 || y == cpu.height - 1) {
    return true;
  }
  const std::size_t row = std::size_t(cpu.width);
  const std::uint32_t here = cpu.primitive[std::size_t(y) * row + std::size_t(x)];
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (cpu.primitive[std::size_t(y + dy) * row + std::size_t(x + dx)] != here) {
        return true;
      }
    }
  }
  return false;
}

// Whether GL's channel c of pixel k is the CPU's value at the other mip level (crosscheck.h).
bool level_switch(const FrameImage& cpu, const FrameImage& gl, const FrameImage& trilinear,
                  std::size_t i) {
  const double bilinear = cpu.linear[i];
  // Both radiances are finite (NaN never leaves a stage); the divisor is 7/16.
  const double reach = std::abs(double(trilinear.linear[i]) - bilinear) / (0.5 - kLodTolerance);
  const int low = srgb_byte(static_cast<float>(bilinear - reach)) - 1;
  const int high = srgb_byte(static_cast<float>(bilinear + reach)) + 1;
  return gl.srgb[i] >= low && gl.srgb[i] <= high;
}

// The distance from |x| (as a float) to the next float up.
double float_spacing_at(double x) {
  const float f = std::abs(static_cast<float>(x));
  return double(std::nextafter(f, INFINITY)) - double(f);
}

// Whether the CPU's and GL's heights at pixel k lie on both sides of the water level (each
// within a float ulp) and within kShorelineUlps of each other, measured from the camera as
// the frame decides: shade.cc's `height < water_level` may then answer differently (water on
// one side, the dry ground on the other). Heights that are not finite explain nothing.
bool water_edge(const FrameImage& cpu, const FrameImage& gl, const Shoreline& shore,
                std::size_t k) {
  if (cpu.world_height.empty() || gl.world_height.empty()) {
    return false;
  }
  const double a = double(cpu.world_height[k]) - shore.camera_y;
  const double b = double(gl.world_height[k]) - shore.camera_y;
  const double level = shore.water_level - shore.camera_y;
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(level)) {
    return false;
  }
  const double ulp = std::max(float_spacing_at(a), float_spacing_at(b));
  return std::abs(a - b) <= kShorelineUlps * ulp && std::min(a, b) - ulp <= level &&
         level <= std::max(a, b) + ulp;
}

}  // namespace

FrameDifference compare_frames(const FrameImage& cpu, const FrameImage& gl,
                               const CompareThresholds& thresholds, const FrameImage* cpu_trilinear,
                               bool all_pixels, std::optional<Shoreline> shoreline) {
  FrameDifference d;
  const FloatImage cpu_srgb = srgb_image(cpu), gl_srgb = srgb_image(gl);
  d.srgb_all = compare_images(cpu_srgb, gl_srgb, thresholds);
  d.srgb = d.srgb_all;
  d.verdict = d.srgb.verdict;
  if (cpu.width != gl.width || cpu.height != gl.height) {
    return d;
  }
  d.srgb_difference = largest_channel_difference(cpu_srgb, gl_srgb);
  d.linear = compare_images(FloatImage{cpu.width, cpu.height, 3, {}, cpu.linear},
                            FloatImage{gl.width, gl.height, 3, {}, gl.linear}, thresholds);
  d.pixels = compare_pixels(cpu, gl);
  // GL's image with the CPU's colour wherever the triangle changed: those pixels compare equal.
  FloatImage gl_same = gl_srgb;
  for (int y = 0; y < cpu.height; ++y) {
    for (int x = 0; x < cpu.width; ++x) {
      const std::size_t k = std::size_t(y) * std::size_t(cpu.width) + std::size_t(x);
      const bool boundary = on_triangle_boundary(cpu, x, y);
      d.boundary_pixels += boundary;
      if (cpu.primitive[k] == gl.primitive[k]) {
        if (shoreline && cpu.primitive[k] != 0xffffffffu && water_edge(cpu, gl, *shoreline, k)) {
          ++d.water_edge_pixels;
          std::copy_n(cpu_srgb.pixels.begin() + std::ptrdiff_t(3 * k), 3,
                      gl_same.pixels.begin() + std::ptrdiff_t(3 * k));
          continue;
        }
        for (std::size_t i = 3 * k; i < 3 * k + 3 && cpu_trilinear != nullptr; ++i) {
          if (std::abs(int(cpu.srgb[i]) - int(gl.srgb[i])) > 1 &&
              level_switch(cpu, gl, *cpu_trilinear, i)) {
            ++d.level_switch_channels;
            gl_same.pixels[i] = cpu_srgb.pixels[i];
          }
        }
        continue;
      }
      d.unexplained_changes += !boundary;
      std::copy_n(cpu_srgb.pixels.begin() + std::ptrdiff_t(3 * k), 3,
                  gl_same.pixels.begin() + std::ptrdiff_t(3 * k));
    }
  }
  if (all_pixels) {
    return d;
  }
  d.srgb = compare_images(cpu_srgb, gl_same, thresholds);
  d.verdict = d.unexplained_changes > 0 ? CompareVerdict::kFailure : d.srgb.verdict;
  return d;
}

}  // namespace relief
