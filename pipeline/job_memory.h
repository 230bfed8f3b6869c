// Estimated peak memory of each command's job, from the sizes of the buffers it allocates
// (docs/using-relief.md, "Memory"). The figures are per element of the arrays the code holds at
// its peak, rounded up; they are checked against a budget (memory_budget.h) before the job
// starts.
#pragma once

#include <string>

#include <cstdint>

#include "core/scene/scene.h"
#include "pipeline/frame.h"
#include "pipeline/memory_budget.h"

namespace relief {

// What to lower when a frame of `scene` does not fit: "Lower viewport.width/height or
// grid.width/height", and lighting.shadow_resolution where the scene has cast shadows.
std::string render_memory_advice(const Scene& scene);

// `relief render`: scene resources (lattice, textures with their mip chains), grid buffers
// and clip coordinates in the backend's precision, and per pixel the sRGB image, its PNG
// encoding and each requested output with its encoding. The tile-fused back end keeps no
// per-pixel attribute planes (tile_pass.h). The rasteriser's set-up triangles and bins depend
// on the frame's triangles (how many survive culling, clipping and the coverage test, and
// their sizes) and are checked against what the estimate leaves once they are counted.
MemoryEstimate estimate_render_memory(const Scene& scene, Backend backend,
                                      const FrameOutputs& outputs);

// estimate_render_memory of a frame whose image holds `rows` rows alone (render_frame_rows;
// the GL backend still draws the whole frame).
MemoryEstimate estimate_rows_render_memory(const Scene& scene, Backend backend,
                                           const FrameOutputs& outputs, int rows);

// The scene's resources alone (scene_resources.h): the lattice, the textures, the sketch and
// the basis images. `relief scene` loads them to validate the scene as render does.
MemoryEstimate estimate_scene_resources_memory(const Scene& scene);

// `relief reference` (ground_truth.h): the resources, the grid of `supersampled` (the scene
// with its viewport and grid enlarged) in double with its set-up triangles, one band of
// `band_rows` supersampled rows (sRGB and linear radiance), and the output image of
// width x height pixels (linear radiance, sRGB, the PNG's encoding and the float file's).
MemoryEstimate estimate_ground_truth_memory(const Scene& supersampled, int band_rows, int width,
                                            int height);

// `relief stages`: the lattice, the grid buffers, and one field's picture and raw file at a
// time.
MemoryEstimate estimate_stages_memory(const Scene& scene, Backend backend);

// `relief raster`, before parsing: the parsed form of a soup file of `file_bytes` bytes.
MemoryEstimate estimate_soup_memory(std::uintmax_t file_bytes);

// `relief raster`, after parsing: the soup, the set-up triangles, and per pixel the visibility
// buffer, the barycentrics and the four output files.
MemoryEstimate estimate_raster_memory(std::uintmax_t triangles, int width, int height);

}  // namespace relief
