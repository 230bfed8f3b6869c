// How far a GL frame (gpu/gl_shading.h) lies from the CPU's frame (pipeline/frame.h): the
// figures docs/gl-shading.md reports and tests/gl/gl_shading_test.cc bounds.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <ostream>
#include <vector>

#include "core/srgb.h"
#include "gpu/gl_shading.h"
#include "pipeline/frame.h"
#include "tests/oracles/gl_interpolation_bound.h"

namespace relief::test {

// The background (sky, fog, open water) relative to the CPU's: llvmpipe reproduces it bit for
// bit; GLSL allows 2.5-3 ulps for a division and a square root (docs/gl-shading.md).
inline constexpr double kBackgroundRelative = 1e-5;

struct FrameDifference {
  std::size_t pixels = 0;
  std::size_t covered_cpu = 0, covered_gl = 0;  // pixels with terrain
  std::size_t primitive_differs = 0;            // another triangle (or coverage) won
  std::size_t unexplained = 0;                  // ... where `explained` says it must not
  std::size_t background = 0;                   // uncovered in both
  std::size_t background_exact = 0;             // ... with bit-identical linear radiance
  std::size_t same_primitive = 0;               // covered in both by the same triangle
  std::size_t same_primitive_exact = 0;         // ... with bit-identical linear radiance
  // sRGB codes over every channel of every pixel: largest difference, RMS, PSNR (peak 255).
  int srgb_max = 0;
  double srgb_rms = 0, srgb_psnr = 0;
  // Stage 9 alone: channels whose GL code is not srgb_byte of GL's own linear value.
  std::size_t encode_mismatches = 0;
  // What the linear bound allows in codes (the codes of the CPU's value moved by its linear
  // tolerance, either way): channels beyond it, and the PSNR if every channel used it all.
  std::size_t srgb_beyond = 0;
  double srgb_allowed_psnr = 0;
  // Linear radiance, every channel: largest absolute and RMS difference; relative to
  // max(|cpu|, 1e-3): the largest over pixels with the same triangle, and over the background.
  double linear_max = 0, linear_rms = 0, linear_relative = 0, background_relative = 0;
  // Pixels with the same triangle: depth relative to the CPU's, normal (absolute), world height
  // relative to the camera-relative height GL interpolates, octave count (absolute).
  double depth_relative = 0, normal_max = 0, height_relative = 0, octaves_max = 0;
  // The same differences over their tolerances (tests/oracles/gl_interpolation_bound.h; linear
  // radiance: a 1/256-px shift of the CPU's image plus 4 ulps), largest over pixels with the same
  // triangle: <= 1 is within the bound.
  double depth_ratio = 0, height_ratio = 0, normal_ratio = 0, octaves_ratio = 0;
  double linear_ratio = 0;
  // Where linear_ratio is largest: the pixel (x, y from the bottom), channel, both values, the
  // tolerance, and the pixel's normal and octave differences there (where a difference comes
  // from).
  int worst_x = -1, worst_y = -1, worst_channel = -1;
  double worst_cpu = 0, worst_gl = 0, worst_allowed = 0, worst_normal = 0, worst_octaves = 0;

  double primitive_share() const { return pixels ? double(primitive_differs) / pixels : 0.0; }
};

// Per pixel of the CPU's frame with terrain, how far GL's value may lie from it
// (tests/oracles/gl_interpolation_bound.h): depth, camera-relative height, the three normal
// components (3 per pixel), the octave count; and the position's arithmetic part.
struct ReferenceTolerances {
  std::vector<double> depth, height, normal, octaves;
  // The arithmetic part of the position's bound (attribute_rounding): camera-relative x, z
  // and height, the box the cloud layer's envelope spans (gl_cloud_envelope.h).
  std::vector<double> dx_rounding, dz_rounding, height_rounding;
};

// |d/dx| + |d/dy| of each channel of the CPU's linear image, from its neighbours (the larger
// difference each way; the trilinear filter keeps the image smooth at the pixel scale, and a
// discontinuity shows as a large difference).
inline double linear_slope(const FrameImage& cpu, std::size_t k, int c) {
  const int width = cpu.width, height = cpu.height;
  const int x = int(k % std::size_t(width)), y = int(k / std::size_t(width));
  const auto at = [&](int px, int py) {
    return double(cpu.linear[3 * (std::size_t(py) * width + px) + c]);
  };
  const double here = at(x, y);
  double sx = 0, sy = 0;
  for (int d : {-1, 1}) {
    if (x + d >= 0 && x + d < width) {
      sx = std::max(sx, std::abs(at(x + d, y) - here));
    }
    if (y + d >= 0 && y + d < height) {
      sy = std::max(sy, std::abs(at(x, y + d) - here));
    }
  }
  return sx + sy;
}

// Under GL_LINEAR_MIPMAP_NEAREST (shading.texture_filter = bilinear) a texture's level is
// round(lambda), a step. The shader computes lambda itself from the dFdxFine / dFdyFine of the
// interpolated texture coordinates (gl-shading.md, "Derivatives"), so a GL whose interpolants
// differ from the CPU's within their bound (its sub-pixel snapping) differs in lambda too, and
// where lambda lies near n + 1/2 it may take the other level: the colour jumps by
// |L(n+1) - L(n)|. The CPU's frame with trilinear filtering sizes that jump, as relief
// crosscheck does (tools/crosscheck.h): |trilinear - bilinear| = min(f, 1 - f) |L(n+1) - L(n)|
// with f = frac(lambda), and a pixel within crosscheck's margin of 1/16 level of the switch
// (lambda measured within 4e-4 of the CPU's on llvmpipe) has min(f, 1 - f) >= 7/16, so
// |L(n+1) - L(n)| <= |trilinear - bilinear| / (7/16) there: the envelope added to each
// channel's tolerance, on every GL: llvmpipe's interpolants lie within their bound of the
// CPU's too, not on its bits, and it takes the other level at a few channels of the presets at
// 1280 x 1024 (glFramesAtTheReadmeSize; relief crosscheck, docs/gl-backend.md).
inline std::vector<double> level_switch_envelope(const FrameImage& bilinear,
                                                 const FrameImage& trilinear) {
  std::vector<double> envelope(bilinear.linear.size());
  for (std::size_t i = 0; i < envelope.size(); ++i) {
    envelope[i] = std::abs(double(trilinear.linear[i]) - double(bilinear.linear[i])) / (7.0 / 16);
  }
  return envelope;
}

// `explained(k)`: whether a different winning triangle at pixel k has a reason (the test's
// rule: an edge within rounding distance, or the framebuffer's border).
// `level_envelope` (bilinear filtering: level_switch_envelope), per channel of each pixel, is
// added to the linear tolerance of pixels with terrain; empty: none.
inline FrameDifference compare_frames(const FrameImage& cpu, const gpu::GlFrameImage& gl,
                                      double camera_y, const ReferenceTolerances& tolerance,
                                      const std::function<bool(std::size_t)>& explained,
                                      const std::vector<double>& level_envelope = {}) {
  FrameDifference d;
  d.pixels = std::size_t(cpu.width) * cpu.height;
  double srgb_sq = 0, linear_sq = 0, allowed_sq = 0;
  for (std::size_t k = 0; k < d.pixels; ++k) {
    const bool covered = cpu.primitive[k] != 0xffffffffu;
    d.covered_cpu += covered;
    d.covered_gl += gl.primitive[k] != 0xffffffffu;
    const bool same = cpu.primitive[k] == gl.primitive[k];
    if (!same) {
      ++d.primitive_differs;
      d.unexplained += !explained(k);
    }
    bool exact = true;
    double relative = 0;
    for (int c = 0; c < 3; ++c) {
      const std::size_t i = 3 * k + c;
      const int ds = std::abs(int(cpu.srgb[i]) - int(gl.srgb[i]));
      d.srgb_max = std::max(d.srgb_max, ds);
      srgb_sq += double(ds) * ds;
      d.encode_mismatches += gl.srgb[i] != srgb_byte(gl.linear[i]);
      const double dl = std::abs(double(cpu.linear[i]) - double(gl.linear[i]));
      d.linear_max = std::max(d.linear_max, dl);
      linear_sq += dl * dl;
      exact = exact && cpu.linear[i] == gl.linear[i];
      relative = std::max(relative, dl / std::max(std::abs(double(cpu.linear[i])), 1e-3));
      // The linear tolerance: a shifted sample of the CPU's image (twice the shift where
      // another triangle won: the pixel lies within two snapping units of their edge), or the
      // background's relative bound.
      const double value = cpu.linear[i];
      const double shift = (same ? 1.0 : 2.0) * kSampleShift;
      const double envelope = covered && !level_envelope.empty() ? level_envelope[i] : 0.0;
      const double allowed =
          covered || !same ? 4.0 * float_ulp(value) + shift * linear_slope(cpu, k, c) + envelope
                           : kBackgroundRelative * std::abs(value);
      if (same && covered) {
        if (dl / allowed > d.linear_ratio) {
          d.worst_x = int(k % std::size_t(cpu.width));
          d.worst_y = int(k / std::size_t(cpu.width));
          d.worst_channel = c;
          d.worst_cpu = value;
          d.worst_gl = gl.linear[i];
          d.worst_allowed = allowed;
          d.worst_normal = 0;
          for (int n = 0; n < 3; ++n) {
            d.worst_normal = std::max(
                d.worst_normal, std::abs(double(cpu.normal[3 * k + n]) - gl.normal[3 * k + n]));
          }
          d.worst_octaves = std::abs(double(cpu.octaves[k]) - double(gl.octaves[k]));
        }
        d.linear_ratio = std::max(d.linear_ratio, dl / allowed);
        const double dn = std::abs(double(cpu.normal[i]) - double(gl.normal[i]));
        d.normal_max = std::max(d.normal_max, dn);
        d.normal_ratio = std::max(d.normal_ratio, dn / tolerance.normal[i]);
      }
      const int code = cpu.srgb[i];
      const int up = srgb_byte(static_cast<float>(value + allowed)) - code;
      const int down = code - srgb_byte(static_cast<float>(value - allowed));
      const int allowed_codes = std::max(up, down);
      d.srgb_beyond += ds > allowed_codes;
      allowed_sq += double(allowed_codes) * allowed_codes;
    }
    if (!same) {
      continue;
    }
    if (!covered) {
      ++d.background;
      d.background_exact += exact;
      d.background_relative = std::max(d.background_relative, relative);
      continue;
    }
    ++d.same_primitive;
    d.same_primitive_exact += exact;
    d.linear_relative = std::max(d.linear_relative, relative);
    const double depth = cpu.depth[k];
    d.depth_relative = std::max(d.depth_relative, std::abs(depth - double(gl.depth[k])) / depth);
    d.depth_ratio =
        std::max(d.depth_ratio, std::abs(depth - double(gl.depth[k])) / tolerance.depth[k]);
    // The world height is float(camera y + h) on both sides: an ulp of it besides h's bound.
    const double h = double(cpu.world_height[k]);
    const double dh = std::abs(h - double(gl.world_height[k]));
    d.height_relative = std::max(d.height_relative, dh / std::max(std::abs(h - camera_y), 1.0));
    d.height_ratio = std::max(d.height_ratio, dh / (tolerance.height[k] + float_ulp(h)));
    const double dnu = std::abs(double(cpu.octaves[k]) - double(gl.octaves[k]));
    d.octaves_max = std::max(d.octaves_max, dnu);
    d.octaves_ratio = std::max(d.octaves_ratio, dnu / tolerance.octaves[k]);
  }
  const double channels = 3.0 * double(d.pixels);
  d.srgb_rms = std::sqrt(srgb_sq / channels);
  d.srgb_psnr = d.srgb_rms > 0 ? 20.0 * std::log10(255.0 / d.srgb_rms) : INFINITY;
  const double allowed_rms = std::sqrt(allowed_sq / channels);
  d.srgb_allowed_psnr = allowed_rms > 0 ? 20.0 * std::log10(255.0 / allowed_rms) : INFINITY;
  d.linear_rms = std::sqrt(linear_sq / channels);
  return d;
}

inline std::ostream& operator<<(std::ostream& out, const FrameDifference& d) {
  return out << d.pixels << " pixels, covered " << d.covered_cpu << " (CPU) " << d.covered_gl
             << " (GL); triangle differs at " << d.primitive_differs << " ("
             << 100.0 * d.primitive_share() << "%), unexplained " << d.unexplained
             << "; bit-identical linear: background " << d.background_exact << "/" << d.background
             << ", terrain " << d.same_primitive_exact << "/" << d.same_primitive << "; sRGB max "
             << d.srgb_max << ", RMS " << d.srgb_rms << ", PSNR " << d.srgb_psnr
             << " dB (the bound allows " << d.srgb_allowed_psnr << " dB), channels beyond it "
             << d.srgb_beyond << ", encoding mismatches " << d.encode_mismatches << "; linear max "
             << d.linear_max << ", RMS " << d.linear_rms << ", relative " << d.linear_relative
             << " (background " << d.background_relative << "); depth relative " << d.depth_relative
             << "; normal " << d.normal_max << "; height relative " << d.height_relative
             << "; octaves " << d.octaves_max << "; over their tolerances: depth " << d.depth_ratio
             << ", height " << d.height_ratio << ", normal " << d.normal_ratio << ", octaves "
             << d.octaves_ratio << ", linear " << d.linear_ratio << " (worst at (" << d.worst_x
             << ", " << d.worst_y << ") channel " << d.worst_channel << ": CPU " << d.worst_cpu
             << ", GL " << d.worst_gl << ", allowed " << d.worst_allowed << ", normal difference "
             << d.worst_normal << ", octaves " << d.worst_octaves << ")";
}

}  // namespace relief::test
