// Types and fixed formats of the software rasteriser (stages 6-7 of docs/architecture.md), which
// follows OpenGL's rules so that a GPU's output can be compared with it pixel by pixel.
//
// Conventions: glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), window origin bottom-left, y up,
// pixel (px, py) has its centre at (px + 0.5, py + 0.5). Window coordinates are snapped to
// 16.8 fixed point (1/256 px, D3D11's and GL hardware's 8 sub-pixel bits; Mesa's llvmpipe
// snaps the same way, rounding half to even). In the fixed frame pixel centres sit at integer
// multiples of 256: X = round((x_window - 0.5) * 256).
#pragma once

#include <cstdint>
#include <span>

#include "core/grid_buffers.h"
#include "core/limits.h"

namespace relief::raster {

inline constexpr int kSubpixelBits = 8;
inline constexpr int kSubpixelScale = 1 << kSubpixelBits;

// Screen tiles rasterised independently, one task each. 64 px rows are four 16-lane vectors
// (AVX-512 floats), and a 64 x 64 tile of ids and depths (32 KiB) stays in L1/L2.
inline constexpr int kTileSize = 64;
static_assert(kTileSize % limits::kRowAlignFloats == 0,
              "tile rows must be whole vectors of the widest SIMD target");

// Guard band: vertices within +-2^21 px of the origin are rasterised without x/y clipping.
// Snapped coordinates then stay below 2^29 in magnitude, edge coefficients below 2^30 and edge
// functions below 2^61: exact in int64. Only triangles reaching beyond it are clipped in x/y.
inline constexpr double kGuardBandPixels = 2097152.0;

// Triangles are set up in fixed chunks (the unit of parallel work of the setup pass);
// results never depend on which thread set up which chunk.
inline constexpr std::uint32_t kSetupChunk = 4096;

inline constexpr std::uint32_t kNoPrimitive = 0xffffffffu;

// glViewport(x, y, width, height): it may be larger than the framebuffer (and is, in the GL
// cross-check, so that llvmpipe does not clip in float at the framebuffer's edge).
struct Viewport {
  double x = 0, y = 0, width = 0, height = 0;
};

enum class CullMode { kNone, kBack, kFront };
enum class FrontFace { kCounterClockwise, kClockwise };  // GL's default is CCW
enum class DepthTest { kGreater, kGreaterEqual, kLess, kLessEqual, kEqual, kAlways, kNever };

struct RasterState {
  int width = 0;  // framebuffer
  int height = 0;
  Viewport viewport;  // pixels are drawn inside viewport and framebuffer only
  CullMode cull = CullMode::kNone;
  FrontFace front_face = FrontFace::kCounterClockwise;
  DepthTest depth_test = DepthTest::kGreater;  // reverse-Z: nearer is greater
  float depth_clear = 0.0f;                    // reverse-Z: infinitely far
};

// Stage 6's output: which primitive covers each pixel, and its depth (docs/architecture.md).
struct VisibilityBuffer {
  int width = 0;
  int height = 0;
  AlignedVector<std::uint32_t> primitive;  // row 0 = bottom; kNoPrimitive where uncovered
  AlignedVector<float> depth;

  std::size_t index(int px, int py) const {
    return static_cast<std::size_t>(py) * width + static_cast<std::size_t>(px);
  }
};

VisibilityBuffer make_visibility_buffer(const RasterState& state);

// Clip-space vertex positions (SoA).
struct ClipVertices {
  std::span<const float> x, y, z, w;
};

// Vertices already in window coordinates (x, y in pixels, z the depth in [0, 1]), as a GPU
// would produce them from w = 1 clip coordinates: no clipping, no perspective.
struct WindowVertices {
  std::span<const float> x, y, z;
};

}  // namespace relief::raster
