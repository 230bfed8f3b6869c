// The same triangles through real OpenGL, for cross-checking the software rasteriser: clip
// coordinates drawn with glDrawElements(GL_TRIANGLES) under glClipControl(GL_LOWER_LEFT,
// GL_ZERO_TO_ONE), a fragment shader that writes gl_PrimitiveID to an R32UI target, and a
// GL_DEPTH_COMPONENT32F depth buffer; both read back bottom row first.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpu/headless_gl.h"

namespace relief::gpu {

enum class GlCull { kNone, kBack, kFront };
enum class GlDepthFunc { kGreater, kGreaterEqual, kLess, kLessEqual, kEqual, kAlways, kNever };

struct GlDraw {
  int width = 0;  // framebuffer
  int height = 0;
  int viewport[4] = {0, 0, 0, 0};     // glViewport
  std::span<const float> x, y, z, w;  // clip coordinates per vertex
  std::span<const std::uint32_t> indices;
  GlCull cull = GlCull::kNone;
  bool front_face_ccw = true;
  GlDepthFunc depth_func = GlDepthFunc::kGreater;
  float depth_clear = 0.0f;
};

struct GlImage {
  std::vector<std::uint32_t> primitive;  // 0xffffffff where uncovered
  std::vector<float> depth;
};

// Requires the context to be current on this thread. Throws std::runtime_error with the GL
// error or the shader log on failure.
GlImage draw_with_gl(const HeadlessGl& gl, const GlDraw& draw);

}  // namespace relief::gpu
