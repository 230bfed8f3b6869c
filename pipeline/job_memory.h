// Estimated peak memory of each command's job, from the sizes of the buffers it allocates
// (README.md, "Memory"). The figures are per element of the arrays the code holds at its peak,
// rounded up; they are checked against a budget (memory_budget.h) before the job starts.
#pragma once

#include <cstdint>

#include "core/scene/scene.h"
#include "pipeline/memory_budget.h"

namespace relief {

// `relief render`: scene resources (lattice, textures with their mip chains), grid buffers
// and clip coordinates, the rasteriser's set-up triangles, and per pixel the visibility
// buffer, the resolved attributes, the linear and sRGB images and the encoded outputs. The
// rasteriser's bins depend on the triangles' sizes and are checked when they are counted.
MemoryEstimate estimate_render_memory(const Scene& scene, bool float_output);

// `relief stages`: the lattice, the grid buffers, and one field's picture and raw file at a
// time.
MemoryEstimate estimate_stages_memory(const Scene& scene);

// `relief raster`, before parsing: the parsed form of a soup file of `file_bytes` bytes.
MemoryEstimate estimate_soup_memory(std::uintmax_t file_bytes);

// `relief raster`, after parsing: the soup, the set-up triangles, and per pixel the visibility
// buffer, the barycentrics and the four output files.
MemoryEstimate estimate_raster_memory(std::uintmax_t triangles, int width, int height);

}  // namespace relief
