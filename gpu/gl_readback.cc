// GlTerrainDraw's read-back (gl_shading.h): each requested target read with glReadPixels in its
// own format (RGBA for the four-channel targets, RG for the height/octave pair), then unpacked
// into the GlFrameImage's fields. Reading a format the target does not have (GL_RGB_INTEGER of
// the RGBA8UI sRGB target, GL_RGB of an RGBA32F one) leaves the unpacking to the driver, which
// on NVIDIA is slower than this loop: measured on an H200 (driver 580.159.04), the default
// frame's sRGB image read as GL_RGB_INTEGER took 7 to 12 ms more than as GL_RGBA_INTEGER and
// unpacked here, the same bytes (the float targets follow the same rule, not measured apart).
#include <chrono>
#include <cstdint>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/gl_checks.h"
#include "gpu/gl_shading.h"

namespace relief::gpu {

namespace {

// The first `channels` of every `stride` values of `from`, in order.
template <class T>
void keep_channels(const T* from, std::size_t pixels, int stride, int channels,
                   std::vector<T>& into) {
  into.resize(pixels * static_cast<std::size_t>(channels));
  T* out = into.data();
  for (std::size_t k = 0; k < pixels; ++k) {
    for (int c = 0; c < channels; ++c) {
      out[static_cast<std::size_t>(channels) * k + static_cast<std::size_t>(c)] =
          from[static_cast<std::size_t>(stride) * k + static_cast<std::size_t>(c)];
    }
  }
}

}  // namespace

GlFrameImage GlTerrainDraw::read_back(int width, int height, const GlReadback& readback) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  GlFrameImage image;
  image.width = width;
  image.height = height;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);  // into client memory
  const auto read = [&](int target, GLenum format, GLenum type, void* out) {
    glNamedFramebufferReadBuffer(framebuffer_, GL_COLOR_ATTACHMENT0 + target);
    glReadPixels(0, 0, width, height, format, type, out);
  };
  // The sRGB bytes through a staging buffer kept from frame to frame (4 bytes a pixel; a new
  // one would cost its page faults every frame).
  srgb_staging_.resize(4 * pixels);
  read(1, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, srgb_staging_.data());
  keep_channels(srgb_staging_.data(), pixels, 4, 3, image.srgb);
  if (readback.linear || readback.normal) {
    std::vector<float> rgba(4 * pixels);
    if (readback.linear) {
      read(0, GL_RGBA, GL_FLOAT, rgba.data());
      keep_channels(rgba.data(), pixels, 4, 3, image.linear);
    }
    if (readback.normal) {
      read(3, GL_RGBA, GL_FLOAT, rgba.data());
      keep_channels(rgba.data(), pixels, 4, 3, image.normal);
    }
  }
  if (readback.primitive) {
    image.primitive.resize(pixels);
    read(2, GL_RED_INTEGER, GL_UNSIGNED_INT, image.primitive.data());
  }
  if (readback.world_height || readback.octaves) {
    std::vector<float> pairs(2 * pixels);
    read(4, GL_RG, GL_FLOAT, pairs.data());
    if (readback.world_height) {
      keep_channels(pairs.data(), pixels, 2, 1, image.world_height);
    }
    if (readback.octaves) {
      keep_channels(pairs.data() + 1, pixels, 2, 1, image.octaves);
    }
  }
  if (readback.depth) {
    image.depth.resize(pixels);
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, image.depth.data());
  }
  check_gl("read back");
  image.readback_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace relief::gpu
