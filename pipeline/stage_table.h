// The frame as a table: every stage in order, what it reads and writes, and its unit of
// parallel work. The frame runner (frame.cc) walks this table and nothing else decides the
// order of the stages; a backend (frame_backend.h) supplies the work of each entry.
//
// Stages 6 to 9 after binning are fused per 64 x 64 screen tile, as GPUs and llvmpipe do:
// each tile is rasterised, resolved (2 x 2 quads, derivatives), shaded and encoded in tile-local
// buffers that stay in cache, and only finished pixels are written to the frame. No per-pixel
// attribute makes a round trip through memory.
#pragma once

#include <cstddef>

namespace relief {

enum class StageId {
  kProjectedDomain,  // stages 1-2
  kOutcodes,         // which frustum planes each vertex's height range lies outside
  kVertexNeeds,      // which vertices a possibly visible triangle needs
  kFractal,          // stage 3
  kDrawOutcodes,     // the same from each vertex's own height
  kDrawNeeds,        // which vertices a possibly visible triangle draws
  kSurface,          // stage 4
  kShadowHeights,    // cast shadows: stage 3's heights on the horizon cache's levels
  kSunHorizons,      // cast shadows, sky light: each cache sample's horizons along its row
  kSkyHorizons,      // sky light: each cache sample's horizons along its column; the sky open
  kVertexTransform,  // stage 5
  kTriangleSetup,    // stage 6, first half: clip, snap, cull, edge functions
  kBinning,          // stage 6: triangles into screen tiles
  kTiles,            // stages 6-9 per tile: rasterise, resolve, shade, encode
};

enum class WorkUnit {
  kGridRows,        // rows of the projected grid
  kVertices,        // grid vertices, flat
  kTriangleChunks,  // fixed chunks of kSetupChunk triangles
  kScreenTiles,     // 64 x 64 tiles of the image
  kCacheRows,       // rows (or columns) of the shadows' horizon cache, level after level
};

// Where a stage is implemented, tested and documented. Each implementation is a repository
// path, or "none: " and the reason there is none; the doc is "FILE#HEADING". A test
// (tests/pipeline/stage_table_test.cc) checks that every path exists, that every "none" has a
// reason and that every heading is in its file.
struct StageHomes {
  const char* portable;  // core/ or raster/: float and double (the reference backends)
  const char* highway;   // simd/: float (the simd backend; cpu_kernels_highway.cc)
  const char* glsl;      // gpu/shaders: the GL backend
  const char* test;      // the test that checks the stage against its oracle
  const char* doc;       // where the stage is explained
};

struct StageInfo {
  StageId id;
  const char* name;    // as the timing reports print it
  const char* number;  // the stages of docs/stages.md's table it covers
  const char* reads;
  const char* writes;
  WorkUnit unit;
  std::size_t grain;  // units per task: fixed, so results never depend on the thread count
  StageHomes homes;
};

// Grains: the outcodes and needs of 16 rows take ~20 us (the needs read two rows around
// their range); a 512-vertex row makes ~40 us of fBm, so 4 rows amortise the scheduling while
// leaving 128 tasks to balance; 16384 vertices transform in ~20 us; a chunk of 4096 triangles
// sets up in ~0.3 ms; a tile takes 0.1 to 2 ms.
// The GL backend culls no vertex: its triangle list (gpu/shaders/triangles.comp) holds every
// triangle of valid vertices, and the GPU's clipper drops what lies outside the frustum.
inline constexpr const char* kGlDrawsEveryTriangle =
    "none: the GL backend draws every valid triangle and the GPU's clipper drops the unseen";

// Cast shadows and sky light are not built on the GL side yet: the GL backend refuses
// lighting.shadows and lighting.sky_occlusion.
inline constexpr const char* kGlHasNoShadows =
    "none: not built yet; the GL backend refuses a scene with lighting.shadows or "
    "lighting.sky_occlusion";

// A height field drawn by GeoMipMapping (terrain.heightfield.geomipmap) runs the same table:
// stage 2's entry selects the tiles and stitches the mesh on the CPU (pipeline/frame_mesh.h),
// and lays the mesh's vertices out in the grid buffers (or streams) in rows; stages 3 and 4 read
// the field at them (core/heightfield/field_mesh.cc, portable in every CPU backend,
// pipeline/cpu_backend_mesh.cc; on the GL side gpu/shaders/mesh.comp, pipeline/gl_frame_mesh.h);
// the outcodes have no work (the quadtree culled the tiles), and set-up onwards (the GL draw)
// draws the mesh's index list.

inline constexpr StageInfo kFrameStages[] = {
    {StageId::kProjectedDomain,
     "projected domain",
     "1-2",
     "camera, projector, LOD rule",
     "dx, dz, sigma, nu, valid",
     WorkUnit::kGridRows,
     4,
     {"core/projected_domain.cc", "simd/projected_domain-inl.h", "gpu/shaders/domain.comp",
      "tests/core/projected_grid_test.cc", "docs/architecture.md#The frame, stage by stage"}},
    {StageId::kOutcodes,
     "vertex outcodes (height bounds)",
     "2",
     "dx, dz, valid; frustum, height bounds",
     "outcode",
     WorkUnit::kGridRows,
     16,
     {"core/vertex_culling.cc", "simd/vertex_outcodes-inl.h", kGlDrawsEveryTriangle,
      "tests/pipeline/skip_test.cc", "docs/stages.md#Skipped work"}},
    {StageId::kVertexNeeds,
     "vertex needs (height bounds)",
     "2",
     "outcodes, valid",
     "need (evaluate, draw)",
     WorkUnit::kGridRows,
     16,
     {"core/vertex_culling.cc", "none: byte flags over neighbouring rows, about 1% of the frame",
      kGlDrawsEveryTriangle, "tests/pipeline/skip_test.cc", "docs/stages.md#Skipped work"}},
    {StageId::kFractal,
     "fractal",
     "3",
     "dx, dz, nu, need; lattice",
     "height",
     WorkUnit::kGridRows,
     4,
     {"core/fbm.cc", "simd/fbm-inl.h", "gpu/shaders/fbm.comp", "tests/core/fbm_test.cc",
      "docs/terrain-spec.md#6. The sum and the LOD weights (§2.1 Eq. 1, §4.1)"}},
    {StageId::kDrawOutcodes,
     "vertex outcodes (heights)",
     "3",
     "dx, dz, height, valid; frustum",
     "outcode",
     WorkUnit::kGridRows,
     16,
     {"core/vertex_culling.cc", "simd/vertex_outcodes-inl.h", kGlDrawsEveryTriangle,
      "tests/pipeline/skip_test.cc", "docs/stages.md#Skipped work"}},
    {StageId::kDrawNeeds,
     "vertex needs (heights)",
     "3",
     "outcodes, valid, need",
     "need (draw)",
     WorkUnit::kGridRows,
     16,
     {"core/vertex_culling.cc", "none: byte flags over neighbouring rows, about 1% of the frame",
      kGlDrawsEveryTriangle, "tests/pipeline/skip_test.cc", "docs/stages.md#Skipped work"}},
    {StageId::kSurface,
     "surface",
     "4",
     "dx, dz, height, valid, need",
     "nx, ny, nz, slope, water depth",
     WorkUnit::kGridRows,
     4,
     {"core/surface.cc", "simd/surface-inl.h", "gpu/shaders/surface.comp",
      "tests/core/surface_test.cc", "docs/architecture.md#The frame, stage by stage"}},
    {StageId::kShadowHeights,
     "shadow heights",
     "3 (shadows)",
     "shadow plan; lattice, sketch texels",
     "cache heights",
     WorkUnit::kCacheRows,
     4,
     {"core/sun_horizons.cc", "simd/fbm-inl.h", kGlHasNoShadows, "tests/core/sun_horizons_test.cc",
      "docs/stages.md#Cast shadows"}},
    {StageId::kSunHorizons,
     "sun horizons",
     "4 (shadows, sky light)",
     "cache heights",
     "cache horizon slopes, runs; the rows' sky openness",
     WorkUnit::kCacheRows,
     8,
     {"core/sun_horizons.cc", "none: a stack per row whose pushes and pops depend on the heights",
      kGlHasNoShadows, "tests/core/sun_horizons_test.cc", "docs/stages.md#Cast shadows"}},
    {StageId::kSkyHorizons,
     "sky horizons",
     "4 (sky light)",
     "cache heights; the rows' openness",
     "cache sky openness",
     WorkUnit::kCacheRows,
     8,
     {"core/sky_horizons.cc",
      "none: a stack per column whose pushes and pops depend on the heights", kGlHasNoShadows,
      "tests/core/sky_horizons_test.cc", "docs/stages.md#Sky light"}},
    {StageId::kVertexTransform,
     "vertex transform",
     "5",
     "dx, dz, height; normals in gradient mode",
     "clip x, y, z, w; lambert in gradient mode (Gouraud)",
     WorkUnit::kVertices,
     16384,
     {"core/vertex_transform.cc", "simd/vertex_transform-inl.h", "gpu/shaders/terrain.vert.in",
      "tests/simd/simd_test.cc", "docs/architecture.md#The frame, stage by stage"}},
    {StageId::kTriangleSetup,
     "triangle setup",
     "6",
     "clip coordinates, valid",
     "set-up triangles per chunk",
     WorkUnit::kTriangleChunks,
     1,
     {"raster/triangle_setup.cc", "simd/vertex_snap-inl.h", "none: the GPU's fixed-function set-up",
      "tests/raster/raster_test.cc", "docs/rasteriser.md#The rasteriser's rules"}},
    {StageId::kBinning,
     "binning",
     "6",
     "set-up triangles",
     "tile bins per chunk",
     WorkUnit::kTriangleChunks,
     1,
     {"raster/bins.cc", "none: integer bounding boxes into per-chunk bins, memory-bound",
      "none: the GPU's fixed-function rasteriser bins its own way", "tests/raster/raster_test.cc",
      "docs/rasteriser.md#The rasteriser's rules"}},
    {StageId::kTiles,
     "tiles: raster, resolve, shade, encode",
     "6-9",
     "bins, vertex streams, textures",
     "sRGB image, requested outputs",
     WorkUnit::kScreenTiles,
     1,
     {"raster/rasterize.cc", "simd/raster_tile-inl.h", "gpu/shaders/terrain.frag",
      "tests/pipeline/frame_test.cc", "docs/stages.md#Shading (stage 8)"}},
};

inline constexpr std::size_t kFrameStageCount = sizeof(kFrameStages) / sizeof(kFrameStages[0]);

}  // namespace relief
