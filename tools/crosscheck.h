// relief crosscheck's figures: the same frame by a CPU backend and by the GL backend, compared
// stage by stage (eval/frame_comparison.h), and the final images as idiff compares them
// (image_compare.h). docs/gl-backend.md says why the two may differ and by how much.
//
// The verdict must hold on every conforming GL, so it judges colour only where the two frames
// agree on what is drawn. A conforming GL snaps vertices to its sub-pixel grid and breaks ties
// on edges by its own rule, so a pixel whose centre lies within a sub-pixel step of an edge may
// be won by the triangle across it; its colour is then another surface's and no colour bound
// holds there. Such a pixel's centre lies within delta < 1/2 px of an edge of its CPU triangle
// t; of its eight neighbours the one most nearly along the edge's outward normal d lies at
// d . n >= cos(22.5 deg) > delta beyond the edge's line, outside t. So a pixel may change
// triangle only where the CPU's frame shows a triangle boundary: an 8-neighbour drawn by
// another triangle (or by none), or the framebuffer's border. Those pixels are left out of the
// idiff comparison; a change anywhere else fails the crosscheck.
//
// Under GL_LINEAR_MIPMAP_NEAREST (shading.texture_filter = bilinear) a texture's level is
// round(lambda), a step: where lambda lies near n + 1/2, the LOD's last rounding (GL computes
// log2 of float derivatives, docs/gl-shading.md "Derivatives") picks level n or n + 1, and the
// colour jumps by the levels' difference |L(n+1) - L(n)|. The CPU's frame with trilinear
// filtering tells that difference where it matters: there the trilinear value is
// (1 - f) L(n) + f L(n+1) with f = frac(lambda), so |trilinear - bilinear| = min(f, 1 - f)
// |L(n+1) - L(n)|, and a pixel within kLodTolerance levels of the switch has min(f, 1 - f) >=
// 1/2 - kLodTolerance. A GL channel within the CPU's value +- |trilinear - bilinear| /
// (1/2 - kLodTolerance) (and one sRGB code) is the other level's, and compares as equal.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "eval/frame_comparison.h"
#include "pipeline/frame.h"
#include "tools/image_compare.h"

namespace relief {

// How far GL's LOD may lie from the CPU's, in mip levels, for a level switch to be explained:
// the documented float difference is 4e-4 of a level; 1/16 leaves room for a GL's own log2.
inline constexpr double kLodTolerance = 1.0 / 16;

// How far apart, in float ulps of the camera-relative height, the CPU's and GL's heights may
// lie for a shoreline step to be explained: llvmpipe's interpolated heights lie up to 24 ulps
// from the CPU's (docs/gl-shading.md, "Interpolated outputs"), and a GL's plane set-up of its
// own may round a few more times.
inline constexpr double kShorelineUlps = 64;

// The water's level and the camera's height (world units): where a pixel is water.
struct Shoreline {
  double water_level = 0;
  double camera_y = 0;
};

struct FrameDifference {
  PixelDifference pixels;
  // Channels of same-triangle pixels that differ by more than one sRGB code but lie within the
  // mip-level switch's envelope (bilinear filtering only): compared as equal.
  std::uint64_t level_switch_channels = 0;
  // Same-triangle pixels whose CPU and GL heights lie on both sides of the water level and
  // within kShorelineUlps of each other: water on one side, dry ground on the other (a step
  // at the shoreline no interpolation bound makes small): compared as equal.
  std::uint64_t water_edge_pixels = 0;
  // Pixels whose triangle differs although no 8-neighbour in the CPU's frame has another
  // triangle and the pixel is not on the border: what no sub-pixel snapping explains.
  std::uint64_t unexplained_changes = 0;
  // Pixels on a triangle boundary of the CPU's frame (where a change may happen).
  std::uint64_t boundary_pixels = 0;
  // The sRGB images as values / 255 over the pixels both frames give the same triangle (or
  // none): idiff's verdict, the verdict crosscheck exits with unless unexplained_changes > 0.
  CompareResult srgb;
  CompareResult srgb_all;  // every pixel, as idiff compares the files: figures
  CompareResult linear;    // linear radiance, every pixel: figures only
  CompareVerdict verdict = CompareVerdict::kPass;
  std::vector<float> srgb_difference;  // per pixel, the largest channel difference (rows as stored)
};

// `cpu_trilinear`: the CPU's frame of the scene with trilinear filtering (linear radiance),
// for a scene that filters bilinearly; null otherwise. `all_pixels`: judge every pixel as idiff
// judges the two PNG files (no exception where the triangle or the mip level changed; not a
// verdict that holds on every GL). `shoreline`: the scene's water level and camera height, in
// world units (as the frames' world_height output holds heights); none: no water, no
// shoreline explained.
FrameDifference compare_frames(const FrameImage& cpu, const FrameImage& gl,
                               const CompareThresholds& thresholds,
                               const FrameImage* cpu_trilinear = nullptr, bool all_pixels = false,
                               std::optional<Shoreline> shoreline = std::nullopt);

}  // namespace relief
