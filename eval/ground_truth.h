// The ground-truth render (relief reference; docs/ground-truth.md): the scene's frame by the
// reference stages in double, with
//   - octaves summed until their amplitude is below `octave_epsilon` of a pixel's footprint
//     (DistanceLod, eval/distance_lod.h), not the real-time LOD rule of §4.1, capped by the scene's
//     own octaves (terrain.last_octave, at most limits::kMaxOctaves);
//   - a projected grid `grid_scale` times finer along each axis;
//   - N x N samples per pixel (a viewport N times larger each way), averaged with a box filter
//     in linear radiance, then encoded to sRGB.
// The supersampled frame is rendered in bands of rows (render_frame_bands), so the per-pixel
// memory is one band's, and each band is reduced to output pixels as it comes. Deterministic:
// the same bits for every run and thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "core/scene/scene.h"
#include "eval/distance_lod.h"
#include "pipeline/frame.h"
#include "pipeline/memory_budget.h"
#include "pipeline/scene_resources.h"

namespace relief {

// Bounds of the settings: 16 x 16 samples and a 16 times finer grid are far past where the
// error stops changing (docs/ground-truth.md, "Convergence"); the viewport and grid limits of
// core/limits.h bound them further for a given scene. Epsilon: an octave below 1e-6 of a pixel
// is far below any float's resolution of the height; above one pixel the reference would be
// coarser than the real-time rule at its own grid.
inline constexpr int kMaxSupersample = 16;
inline constexpr int kMaxGridScale = 16;
inline constexpr double kMinOctaveEpsilon = 1e-6;
inline constexpr double kMaxOctaveEpsilon = 1.0;
// The supersampled pixels of one band hold 15 bytes each (sRGB 3, linear radiance 12): bands
// of at most 64 MiB of them keep the default reference (5120 x 4096 samples) in 5 bands.
inline constexpr std::uintmax_t kGroundTruthBandBytes = std::uintmax_t{64} << 20;
// Points per cloud path in the truth (core/clouds.h): the midpoint rule over the layer, whose
// density varies over the scale of its finest octave along a path.
inline constexpr int kGroundTruthCloudSteps = 16;

struct GroundTruthSettings {
  int supersample = 4;            // N: N x N samples per pixel
  int grid_scale = 4;             // grid vertices per axis: the scene's times this
  double octave_epsilon = 0.125;  // of a pixel's footprint at the vertex's distance
  int band_rows = 0;              // supersampled rows per band; 0: from kGroundTruthBandBytes
  bool distances = false;         // also GroundTruthImage::distance (convergence.h's bands)
};

// A setting out of range, alone or for this scene (bad input, exit code 2): the message names
// the option, its value and the allowed range.
class GroundTruthError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws GroundTruthError unless every setting is in range for `scene`.
void validate_ground_truth(const Scene& scene, const GroundTruthSettings& settings);

// The scene that is rendered: viewport N times, grid `grid_scale` times the scene's.
Scene supersampled_scene(const Scene& scene, const GroundTruthSettings& settings);

// Supersampled rows per band: settings.band_rows, or the most rows whose pixels fit
// kGroundTruthBandBytes, at least one multiple of lcm(kTileSize, N).
int ground_truth_band_rows(const Scene& scene, const GroundTruthSettings& settings);

// The octave rule (frame.h, DistanceLod) of the ground truth for `scene` (the original scene:
// its viewport sets the pixel). Octave k (amplitude A r^(-k H)) is summed while
// A r^(-k H) >= epsilon p d, with p the smallest angle a pixel subtends (at the image corner)
// and d a lower bound of the vertex's distance (horizontal distance, and the camera's height
// above the highest possible terrain). `cap_distance`: below this distance the rule asks for
// more octaves than the scene has, and all of them are summed (the cap binds).
struct GroundTruthLod {
  DistanceLod lod;
  double cap_distance = 0;
};
GroundTruthLod ground_truth_lod(const Scene& scene, const SceneResources& resources,
                                double octave_epsilon);

// Output rows per step of a shard of the ground truth (relief reference --shard, tools/shard.h):
// lcm(raster::kTileSize, N) / N for N x N samples, so that a shard's supersampled rows are
// whole tiles (render_frame_bands) and whole output pixels. supersample: 1 to kMaxSupersample.
int ground_truth_shard_unit(int supersample);

// Peak memory (job_memory.h, estimate_ground_truth_memory, for the supersampled scene), the
// output image holding `output_rows` (render_ground_truth).
MemoryEstimate ground_truth_memory(const Scene& scene, const GroundTruthSettings& settings,
                                   FrameRows output_rows = {});

struct GroundTruthImage {
  int width = 0, height = 0;       // the scene's viewport, or its width and the rows rendered
  int first_row = 0;               // the framebuffer row of the image's bottom row
  std::vector<float> linear;       // RGB per pixel, rows bottom to top: the box-filtered radiance
  std::vector<std::uint8_t> srgb;  // 3 per pixel: srgb_byte of `linear`
  // With settings.distances, 1 per pixel: the mean distance along the view axis of the pixel's
  // samples that see terrain (near / depth of each), or 0 where fewer than half of them do.
  std::vector<float> distance;
  FrameStats stats;  // of the supersampled frame
  GroundTruthLod lod;
  int bands = 0;
};

// Called after each band with (bands done, bands in all).
using BandProgress = std::function<void(int, int)>;

// Renders the ground truth of a validated scene (validate_ground_truth passed) with resources
// built from it. `max_bin_bytes`: the rasteriser bins' share of the budget (frame.h).
// `output_rows`: the framebuffer rows of the output image to render, [begin, end), begin a
// multiple of ground_truth_shard_unit below the viewport's top, end above it and a multiple
// of it or at or past the top (std::invalid_argument otherwise); each row bit-identical to
// the same row of the whole image.
GroundTruthImage render_ground_truth(const Scene& scene, const SceneResources& resources,
                                     const GroundTruthSettings& settings,
                                     std::uint64_t max_bin_bytes = UINT64_MAX,
                                     const BandProgress& progress = {}, FrameRows output_rows = {});

}  // namespace relief
