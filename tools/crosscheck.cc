#include "tools/crosscheck.h"

namespace relief {

namespace {

FloatImage srgb_image(const FrameImage& frame) {
  FloatImage image{frame.width, frame.height, 3, {}, std::vector<float>(frame.srgb.size())};
  for (std::size_t k = 0; k < frame.srgb.size(); ++k) {
    image.pixels[k] = float(frame.srgb[k]) / 255.0f;
  }
  return image;
}

}  // namespace

FrameDifference compare_frames(const FrameImage& cpu, const FrameImage& gl,
                               const CompareThresholds& thresholds) {
  FrameDifference d;
  const FloatImage cpu_srgb = srgb_image(cpu), gl_srgb = srgb_image(gl);
  d.srgb = compare_images(cpu_srgb, gl_srgb, thresholds);
  if (cpu.width != gl.width || cpu.height != gl.height) {
    return d;
  }
  d.srgb_difference = largest_channel_difference(cpu_srgb, gl_srgb);
  d.linear = compare_images(FloatImage{cpu.width, cpu.height, 3, {}, cpu.linear},
                            FloatImage{gl.width, gl.height, 3, {}, gl.linear}, thresholds);
  d.pixels = compare_pixels(cpu, gl);
  return d;
}

}  // namespace relief
