// The terrain sampled on a regular grid over a world rectangle, for `relief export`: heights,
// normals and the shading's layer weights at every sample, of the procedural terrain, a sketch
// or a height field alike.
//
// Sample (i, j) of a W x H region [x0, x1] x [z0, z1] sits at its texel centre,
//   x = x0 + (i + 1/2) (x1 - x0) / W,   z = z0 + (j + 1/2) (z1 - z0) / H,
// the convention terrain.heightfield reads its samples by (core/height_sketch.h), so that an
// exported map with extent [x0, z0, x1, z1] lies where it was taken from.
//
// Each sample is evaluated as a frame's vertex with the grid spacing of the samples would be
// (stages 2 and 3 in double, core/fbm.h and core/height_sketch.h): §4.1's octave count (or a
// height field's level) for spacing sigma = max(cell_x, cell_z), so the octaves finer than the
// samples can carry (Nyquist) are left out instead of aliased. The coordinate forms of the
// octaves are chosen once for the whole region, so the samples do not depend on how the work is
// split. Normals and slopes: central differences of neighbouring samples (a one-sample margin
// beyond the region is evaluated, so borders are central too and adjacent exports agree),
// normal = normalise(-dh/dx, 1, -dh/dz), slope = |grad h|. Layer weights: §4.2's weighting
// (core/layer_weights.h) at the sample's height and slope, without the per-pixel dither,
// quantised to bytes that sum to 255 (largest remainders).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/scene/scene.h"
#include "pipeline/scene_resources.h"

namespace relief {

struct SampleRegion {
  std::array<double, 4> rect = {0, 0, 1, 1};  // [x0, z0, x1, z1], x1 > x0, z1 > z0
  int width = 2, height = 2;                  // samples along x and z
};

struct TerrainSampleRequest {
  bool normals = false;  // float normals (3 per sample)
  bool weights = false;  // the layer weights as bytes
};

struct TerrainSamples {
  int width = 0, height = 0;
  std::vector<float> heights;         // world heights, row j (along z, z0 first) at j * width
  std::vector<float> normals;         // x, y, z per sample when requested
  int layers = 0;                     // scene.shading.layers
  std::vector<std::uint8_t> weights;  // `layers` bytes per sample summing to 255, when requested
  double low = 0, high = 0;           // extremes of `heights`
  // The scene's height bounds (core/height_bounds.h): what a null shading.gradient.range
  // spans, which an exported scene must keep (its field has bounds of its own).
  double bound_low = 0, bound_high = 0;
};

// Bytes a sampling of `region` holds at its peak (outputs and working rows).
std::uintmax_t terrain_samples_bytes(const Scene& scene, const SampleRegion& region,
                                     const TerrainSampleRequest& request);

// Precondition: a validated scene on the plane (not a planet), its resources, a region as
// above with finite corners within +-limits::kMaxCameraCoordinate. `progress(done, total)` is
// called with rows done (from one thread at a time). Runs on the caller's oneTBB arena; the
// samples are the same for any thread count.
TerrainSamples sample_terrain(const Scene& scene, const SceneResources& resources,
                              const SampleRegion& region, const TerrainSampleRequest& request,
                              const std::function<void(int, int)>& progress = {});

}  // namespace relief
