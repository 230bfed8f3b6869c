// The frame: a scene's stages run in order by a backend, with the outputs a caller asks for.
//
// This is the seam every backend plugs into (pipeline/stage_table.h lists the stages): the
// reference backend in float, the same in double, the simd backend (the float reference with
// Highway kernels; all three the CPU backend with another kernel table, cpu_kernels.h) and GL
// (the GLSL twins, pipeline/gl_backend.h). A frame renders
// bit-identically for every thread count; the float and double backends differ by the float
// error that docs/architecture.md measures.
#pragma once

#include <climits>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/frame_plan.h"
#include "core/grid_buffers.h"
#include "core/scene/scene.h"
#include "pipeline/frame_skips.h"
#include "pipeline/scene_resources.h"
#include "raster/rasterize.h"

namespace relief {

enum class Backend {
  kReference,        // the scalar reference stages in float: the product's images
  kReferenceDouble,  // the same stages in double, for accuracy comparisons
  kSimd,             // the float stages with Highway kernels: bit-identical to kReference
  kGl,  // the GLSL twins of the stages on OpenGL 4.5 (gl_backend.h): within documented bounds
};

// "reference", "reference-double", "simd", "gl".
std::string_view backend_name(Backend backend);
std::optional<Backend> backend_from_name(std::string_view name);
std::vector<std::string_view> backend_names();

// Per-pixel outputs a caller may ask for beside the sRGB image. Rows bottom to top, like
// every buffer of Relief. Pixels without terrain hold 0 (primitive: kNoPrimitive, depth: the
// cleared far value 0).
struct FrameOutputs {
  bool linear = false;        // linear radiance after the exposure, RGB
  bool depth = false;         // window depth of the terrain, reverse-Z (1 near, 0 at infinity)
  bool primitive = false;     // the winning triangle of the projected grid
  bool normal = false;        // interpolated unit normal, RGB = (nx, ny, nz)
  bool world_height = false;  // terrain height: camera y + the camera-relative height, in float
  bool octaves = false;       // interpolated octave count nu (stage 2)
};

// A rule that replaces stage 2's octave count nu over a range of grid rows, run by the CPU
// backends right after stage 2 on those rows. The ground truth installs its distance rule
// (eval/distance_lod.h); the frame knows nothing of it. Called concurrently for disjoint rows.
class OctaveCountRule {
 public:
  virtual ~OctaveCountRule() = default;
  virtual void apply(RowRange rows, GridBuffers<float>& grid) const = 0;
  virtual void apply(RowRange rows, GridBuffers<double>& grid) const = 0;
};

struct FrameRequest {
  Backend backend = Backend::kReference;
  FrameOutputs outputs;
  FrameSkips skips;
  // The CPU backends only (reference, reference-double, simd); the GL backend ignores it.
  // Null: stage 2's own LOD rule (§4.1).
  std::shared_ptr<const OctaveCountRule> octave_count_rule;
  // Points the cloud layer reads along each path (core/clouds.h): 1 in a frame; the ground
  // truth takes more. The CPU backends only, 1 ... kMaxCloudSteps (render_frame throws
  // std::invalid_argument outside).
  int cloud_steps = 1;
  // Memory the rasteriser's bins may take (raster/rasterize.h); a frame whose bins need more
  // throws MemoryLimitError.
  std::uint64_t max_bin_bytes = UINT64_MAX;
};

struct FrameImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> srgb;        // 3 per pixel, always
  std::vector<float> linear;             // 3 per pixel, when requested
  std::vector<float> depth;              // 1 per pixel, when requested
  std::vector<std::uint32_t> primitive;  // 1 per pixel, when requested
  std::vector<float> normal;             // 3 per pixel, when requested
  std::vector<float> world_height;       // 1 per pixel, when requested
  std::vector<float> octaves;            // 1 per pixel, when requested
};

// A count of work a stage did (vertices evaluated, texture fetches, ...).
struct WorkCounter {
  std::string name;
  std::uint64_t value = 0;
};

// Wall time of one stage of the table (or one group of fused stages), whether it ran at all,
// and the work it did.
struct StageTime {
  std::string name;
  double ms = 0;
  bool ran = true;
  std::vector<WorkCounter> counters;
};

// One kernel of a CPU frame and the kind that ran it (cpu_kernels.h); the GL backend's frames
// have none.
struct KernelReport {
  std::string stage;           // the stage table's name
  std::string kernel;          // "vertex outcodes", "tile resolve", ...
  std::string implementation;  // "Highway (AVX3)", "portable loop (float)"
  std::string reason;          // why it is not the backend's own kind; empty otherwise
};

struct FrameStats {
  std::vector<StageTime> stages;      // in the order they ran (frame plan, then the stage table)
  std::vector<KernelReport> kernels;  // the CPU backends' kernel table, in stage order
  // The parts of the fused tile stage, as CPU time summed over the threads that ran tiles.
  std::vector<StageTime> tile_parts;
  // The GL backend's passes in the order they ran: each compute dispatch and draw's GPU time
  // from GL timer queries, then "read-back (CPU wall time)"; empty for the CPU backends, and
  // without the GPU times where the GL has no timer (gpu/gl_pass_timer.h).
  std::vector<StageTime> gpu_passes;
  double total_ms = 0;  // the frame, start to end
  raster::RasterStats raster;
};

struct Frame {
  FrameImage image;
  FrameStats stats;
};

// Renders one frame of a validated scene with resources built from it (scene_resources.h).
// Throws MemoryLimitError when the rasteriser's bins exceed request.max_bin_bytes.
Frame render_frame(const Scene& scene, const SceneResources& resources,
                   const FrameRequest& request);

// The frame's image in bands of `band_rows` framebuffer rows (a positive multiple of
// raster::kTileSize), bottom band first: stages 1-6 up to binning run once, then the tiles of
// each band, whose image (width x its rows, rows bottom to top, the last band possibly lower)
// is handed to `consume(band, first_row)` and then dropped, so that the per-pixel memory is
// one band's. The bands together are bit-identical to render_frame's image. CPU backends only
// (throws std::invalid_argument for the GL backend). Returns the frame's statistics.
// `rows`: the framebuffer rows banded, [begin, end) (a shard of relief reference): begin a
// multiple of raster::kTileSize below the viewport's top, end above begin and a multiple of it
// or at or past the top (then up to the top); std::invalid_argument otherwise.
struct FrameRows {
  int begin = 0;
  int end = INT_MAX;
};
// Whether `rows` are whole steps of `step` rows of an image `height` rows high: begin a multiple
// of step below the top, end above begin and a multiple of step or at or past the top.
bool whole_steps(FrameRows rows, int height, int step);

FrameStats render_frame_bands(const Scene& scene, const SceneResources& resources,
                              const FrameRequest& request, int band_rows,
                              const std::function<void(const FrameImage&, int)>& consume,
                              FrameRows rows = {});

// Framebuffer rows [first_row, first_row + rows) of the frame alone (relief render --shard):
// first_row a multiple of raster::kTileSize, rows positive and a multiple of it or reaching the
// viewport's top (else std::invalid_argument). The image holds those rows, bottom to top,
// bit-identical to the same rows of render_frame's image; the per-pixel memory is theirs.
// Stages 1-6 up to binning run for the whole frame, the tiles of those rows alone. The GL
// backend draws the whole frame and keeps the rows.
Frame render_frame_rows(const Scene& scene, const SceneResources& resources,
                        const FrameRequest& request, int first_row, int rows);

// The frame rendered `repeat` (>= 1) times, for a time that the machine's noise does not
// decide: the last frame, and in `median_ms` the median of the wall times.
Frame render_frame_repeated(const Scene& scene, const SceneResources& resources,
                            const FrameRequest& request, int repeat, double& median_ms);

// Stages 1-4 alone (relief stages), by `backend` (reference or simd in float, reference-double
// in double): the frame's plan, the grid buffers and the time of each stage. `lattice` is
// stage 3's grid: SceneResources::terrain_values() (the basis grid of a terrain.basis scene).
template <class Real>
struct TerrainRun {
  FramePlan plan;
  GridBuffers<Real> grid;
  std::vector<StageTime> stages;
};

template <class Real>
TerrainRun<Real> run_terrain_stages(const Scene& scene, const NoiseLattice& lattice,
                                    Backend backend = std::is_same_v<Real, float>
                                                          ? Backend::kReference
                                                          : Backend::kReferenceDouble,
                                    const HeightSketch* sketch = nullptr);

}  // namespace relief
