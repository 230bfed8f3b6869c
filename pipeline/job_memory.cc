#include "pipeline/job_memory.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "core/grid_buffers.h"
#include "core/heightfield/field_mesh.h"
#include "core/input_file.h"
#include "core/limits.h"
#include "core/sun_horizons.h"
#include "core/water_reflection.h"
#include "image/png_header.h"
#include "pipeline/basis_resources.h"
#include "pipeline/heightfield_files.h"
#include "pipeline/png_checks.h"
#include "raster/raster_types.h"
#include "raster/triangle_setup.h"

namespace relief {

namespace {

// Bytes per element of the arrays each job holds at its peak.
constexpr std::uintmax_t kGridVertexBytes = 10 * 4 + 1;  // GridBuffers<float>: 10 planes + valid
constexpr std::uintmax_t kClipVertexBytes = 4 * 4;       // clip x, y, z, w
// In double: 10 planes of 8 bytes and valid, clip coordinates in double and their float copy
// for the rasteriser.
constexpr std::uintmax_t kDoubleVertexBytes = 10 * 8 + 1 + 4 * 8 + 4 * 4;
// The tile-fused back end keeps no per-pixel attribute: per pixel only the sRGB bytes (3) and
// their PNG encoding (filtered rows, deflate output and the copy handed to the writer: at most
// 13), plus each requested output and its encoding (twice its size: the PFM copy).
constexpr std::uintmax_t kRenderPixelBytes = 3 + 13;
// A set-up triangle, twice over for the growth of its chunk's vector.
// raster::PreparedVertices per vertex: flags and outcode, floor x, y, z, fx, fy, window x, y
// and the passes' bits.
constexpr std::uintmax_t kPreparedVertexBytes = 1 + 1 + 3 * 4 + 2 * 4 + 2 * 4 + 4;
constexpr std::uintmax_t kSetupTriangleBytes = 2 * sizeof(raster::RasterTriangle);
// Texture texels: float RGB (12) and the mip chain's third (4); PNG files decode through
// 3 bytes a texel.
constexpr std::uintmax_t kTexelBytes = 16;
constexpr std::uintmax_t kDecodedTexelBytes = 3;
// A parsed soup triangle: 3 vertices of 4 floats and 3 indices, twice over for vector growth.
constexpr std::uintmax_t kSoupTriangleBytes = 2 * (3 * 16 + 3 * 4);
// The shortest soup triangle line, "0 0 0 0 0 0 0 0 0\n".
constexpr std::uintmax_t kMinSoupLineBytes = 18;
// raster: visibility 8, barycentrics 12, the id/barycentric/coverage arrays 19, and the largest
// encoding at a time (the barycentric PFM) 12.
constexpr std::uintmax_t kRasterPixelBytes = 8 + 12 + 19 + 12;
// stages: one field's picture (3), its PNG (13) and its raw channels with their PFM (24).
constexpr std::uintmax_t kStagesVertexBytes = 3 + 13 + 24;
// A planet's stages add its four bent streams (in double, and their float copy) and the bent
// and drop files: two PNGs (13 each) and four raw channels (4 each).
constexpr std::uintmax_t kStagesBentVertexBytes = 4 * 8 + 4 * 4 + 2 * 13 + 4 * 4;

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// A PNG layer's memory: its file, decoded bytes and float texels; nullopt when the file or its
// header is unreadable (loading the scene reports why).
std::optional<std::uintmax_t> png_layer_bytes(const std::string& path) {
  const PngPeek peek = peek_png(path);
  if (peek.header && peek.header->width <= std::uint32_t(limits::kMaxTextureSize)) {
    const std::uintmax_t side = peek.header->width;
    return peek.file_bytes + side * side * (kTexelBytes + kDecodedTexelBytes);
  }
  return std::nullopt;
}

// A height sketch's memory (§3's low-frequency base): its PNG bytes, held whole while they are
// decoded, the decoded 16-bit texels and their float heights; 0 when its header is unreadable
// or too large (loading the scene reports why).
std::uintmax_t sketch_bytes(const SketchSettings& sketch) {
  const PngPeek peek = peek_png(sketch.image);
  const std::optional<PngHeader>& png = peek.header;
  if (!png || png->width > std::uint32_t(limits::kMaxSketchSize) ||
      png->height > std::uint32_t(limits::kMaxSketchSize)) {
    return 0;
  }
  const std::uintmax_t texels = std::uintmax_t(png->width) * png->height;
  return peek.file_bytes + texels * (sizeof(std::uint16_t) + sizeof(float));
}

// The sketch's or the height field's memory, under one name (memory_budget.cc's remedy).
void add_height_field(const TerrainSettings& terrain, MemoryEstimate& estimate) {
  if (terrain.heightfield) {
    const std::optional<HeightFieldPeek> peek = peek_height_field(*terrain.heightfield);
    estimate.add("height field", peek ? height_field_load_bytes(*peek) : 0);
    if (peek && terrain.heightfield->geomipmap) {  // its lattice and tiles (field_mesh.h)
      const int cells = terrain.heightfield->geomipmap->tile_cells;
      const std::uintmax_t vertices =
          field_mesh_vertices(int(peek->width), int(peek->height), cells);
      // Per tile: its bounds with up to 9 errors, the quadtree's nodes (under 4/3 a tile), and
      // a frame's selection (its level and flags, 8 bytes).
      const std::uintmax_t tiles = vertices / (std::uintmax_t(cells) * cells) + 1;
      estimate.add("GeoMipMap lattice",
                   vertices * FieldMesh::kBytesPerVertex +
                       tiles * (sizeof(geomipmap::TileBounds) + 9 * sizeof(double) + 16 + 8));
    }
  } else if (terrain.sketch) {
    estimate.add("height sketch", sketch_bytes(*terrain.sketch));
  }
}

void add_resources(const Scene& scene, MemoryEstimate& estimate) {
  const std::uintmax_t lattice = std::uintmax_t(scene.terrain.lattice_size);
  estimate.add("noise lattice " + size_text(scene.terrain.lattice_size, scene.terrain.lattice_size),
               lattice * lattice * sizeof(float));
  std::uintmax_t textures = 0;
  // Gradient shading reads no texture: none is built (load_scene_resources).
  const bool textured = scene.shading.mode == ShadingMode::kTextures;
  for (const MaterialLayer& layer :
       textured ? scene.shading.layers : std::vector<MaterialLayer>{}) {
    if (layer.texture.rfind("builtin:", 0) == 0) {
      const std::uintmax_t side = std::uintmax_t(scene.shading.texture_size);
      textures += side * side * kTexelBytes;
    } else {
      textures += png_layer_bytes(layer.texture).value_or(0);
    }
  }
  estimate.add("textures", textures);
  add_height_field(scene.terrain, estimate);
  if (scene.sky.skybox) {
    // Each face as a layer's texture: its file, decoded bytes and float texels (no mip chain,
    // so this counts a third more than the faces keep).
    std::uintmax_t faces = 0;
    for (const std::string& face : scene.sky.skybox->faces) {
      faces += png_layer_bytes(face).value_or(0);
    }
    estimate.add("skybox faces", faces);
  }
  if (scene.terrain.basis) {
    estimate.add("basis images and their composed grid", basis_memory_bytes(scene));
  }
}

std::uintmax_t grid_vertices(const Scene& scene) {
  return make_grid_layout(scene.grid.width, scene.grid.height).size();
}

// Cast shadows', sky light's and the reflections' horizon cache (core/sun_horizons.h): the
// levels the scene lays out, N^2 samples each with a height, the sun's two values (with the sun
// up) and the sky's one in the backend's precision, and the reflections' block maxima; a frame
// builds those its pixels read (the GL backend refuses all three).
void add_shadow_cache(const Scene& scene, Backend backend, MemoryEstimate& estimate) {
  const int levels = shadow_cache_levels(scene);
  if (levels == 0 || backend == Backend::kGl) {
    return;
  }
  const std::uintmax_t n = std::uintmax_t(scene.lighting.shadow_resolution);
  const std::uintmax_t value =
      backend != Backend::kReferenceDouble ? sizeof(float) : sizeof(double);
  const bool sun =
      scene.lighting.shadows && scene.lighting.sun_elevation_deg + scene.sky.sun_disc_deg > 0.0;
  const std::uintmax_t values = 1 + (sun ? 2 : 0) + (scene.lighting.sky_occlusion ? 1 : 0);
  estimate.add("shadow cache " + size_text(int(n), int(n)) + " x " + std::to_string(levels),
               n * n * std::uintmax_t(levels) * values * value);
  if (scene.water.reflect_terrain && scene.terrain.water_level) {  // water_reflection.h
    std::uintmax_t blocks = (n - 1 + kReflectionBlock - 1) / kReflectionBlock, maxima = 0;
    for (int tier = 0; tier < kMaxReflectionTiers; ++tier, blocks = (blocks + 1) / 2) {
      maxima += blocks * blocks;  // an overestimate by the tiers not built (< 1/3)
    }
    estimate.add("reflections' block maxima", maxima * std::uintmax_t(levels) * value);
  }
}

}  // namespace

MemoryEstimate estimate_scene_resources_memory(const Scene& scene) {
  MemoryEstimate estimate;
  add_resources(scene, estimate);
  return estimate;
}

MemoryEstimate estimate_rows_render_memory(const Scene& scene, Backend backend,
                                           const FrameOutputs& outputs, int rows) {
  if (backend == Backend::kGl) {
    return estimate_render_memory(scene, backend, outputs);
  }
  // The per-pixel parts scale with the rows; the shadow cache's levels are laid out from the
  // whole viewport (its pixel angle and corner), as the band's frame lays them out.
  Scene band = scene;
  band.viewport.height = std::max(1, std::min(rows, scene.viewport.height));
  MemoryEstimate estimate = estimate_render_memory(band, backend, outputs);
  std::erase_if(estimate.parts,
                [](const auto& part) { return part.first.rfind("shadow cache", 0) == 0; });
  add_shadow_cache(scene, backend, estimate);
  return estimate;
}

std::string render_memory_advice(const Scene& scene) {
  return shadow_cache_levels(scene) > 0
             ? "Lower viewport.width/height, grid.width/height or lighting.shadow_resolution"
             : "Lower viewport.width/height or grid.width/height";
}

MemoryEstimate estimate_render_memory(const Scene& scene, Backend backend,
                                      const FrameOutputs& outputs) {
  MemoryEstimate estimate;
  add_resources(scene, estimate);
  const std::uintmax_t vertices = grid_vertices(scene);
  // A planet frame adds its four bent streams (x, y, z, drop: core/grid_buffers.h).
  const bool planet = scene.terrain.planet && scene.terrain.planet->radius != 0.0;
  // Gradient shading adds each vertex's Lambert term (stage 5: core/vertex_transform.h).
  const bool gouraud = scene.shading.mode == ShadingMode::kGradient;
  const std::uintmax_t real_bytes =
      backend != Backend::kReferenceDouble ? sizeof(float) : sizeof(double);
  const std::uintmax_t vertex_bytes =
      (backend != Backend::kReferenceDouble ? kGridVertexBytes + kClipVertexBytes
                                            : kDoubleVertexBytes) +
      (planet ? 4 * real_bytes : 0) + (gouraud ? real_bytes : 0);
  // The set-up triangles are not counted here: culling, clipping and the coverage test leave
  // few of a fine grid's triangles at a small viewport (a 4096^2 grid at 256 x 192 sets up
  // 173,349 of 33.5 million), so their worst case refused jobs that fit; the backend counts
  // them with the bins once set up, against what this estimate leaves of the budget.
  estimate.add("grid " + size_text(scene.grid.width, scene.grid.height), vertices * vertex_bytes);
  add_shadow_cache(scene, backend, estimate);
  // Set-up's per-thread scratch (raster::PreparedVertices, kept between frames): every vertex
  // one chunk of kSetupChunk triangles spans, padded rows included, 34 bytes each. A narrow
  // grid's chunk spans many rows: on a 2 x 8192 grid 2,049 rows of 16, 1.1 MiB a thread.
  if (backend != Backend::kGl) {
    const GridLayout layout = make_grid_layout(scene.grid.width, scene.grid.height);
    const std::uintmax_t cells_per_row = std::uintmax_t(std::max(layout.width - 1, 1));
    const std::uintmax_t rows =
        std::min<std::uintmax_t>(layout.height, raster::kSetupChunk / (2 * cells_per_row) + 2);
    const auto threads = std::uintmax_t(
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    estimate.add("set-up scratch",
                 threads * rows * std::uintmax_t(layout.pitch) * kPreparedVertexBytes);
  }
  const std::uintmax_t pixels = std::uintmax_t(scene.viewport.width) * scene.viewport.height;
  // Floats per pixel of the requested outputs; the primitive ids are written without a copy.
  const std::uintmax_t output_floats = 3 * outputs.linear + outputs.depth + 3 * outputs.normal +
                                       outputs.world_height + outputs.octaves;
  estimate.add("image " + size_text(scene.viewport.width, scene.viewport.height),
               pixels * (kRenderPixelBytes + 2 * 4 * output_floats + 4 * outputs.primitive));
  if (backend == Backend::kGl) {
    // The GL side's copies (host memory under llvmpipe, the GPU's otherwise: counted either
    // way): per pixel the render targets (RGBA32F linear and normal 32, RGBA8UI sRGB 4, R32UI
    // primitive 4, RG32F height and octaves 8, DEPTH32F 4), the read-back staging (RGBA32F 16,
    // RGBA8 4, RG32F 8) and every output read back (43); per vertex the eleven float streams
    // (44), a planet's four bent ones (16: gpu/gl_streams.h), the index buffer of its two
    // triangles (24) and the driver's transformed vertices (llvmpipe keeps the vertex shader's
    // outputs of a draw: measured 147 bytes a vertex on a 1872^2 grid, counted as 192).
    // The streams hold padded rows (V); the indices and the transformed vertices only the
    // grid's own vertices.
    constexpr std::uintmax_t kGlPixelBytes = 52 + 28 + 43;
    constexpr std::uintmax_t kGlStreamBytes = 44;
    constexpr std::uintmax_t kGlDrawnVertexBytes = 24 + 192;
    constexpr std::uintmax_t kGlBentVertexBytes = 16;
    const std::uintmax_t grid_own = std::uintmax_t(scene.grid.width) * scene.grid.height;
    estimate.add("GL targets, read-back and buffers",
                 pixels * kGlPixelBytes +
                     vertices * (kGlStreamBytes + (planet ? kGlBentVertexBytes : 0)) +
                     grid_own * kGlDrawnVertexBytes);
  }
  return estimate;
}

MemoryEstimate estimate_ground_truth_memory(const Scene& supersampled, int band_rows, int width,
                                            int height) {
  FrameOutputs linear;
  linear.linear = true;
  MemoryEstimate frame = estimate_render_memory(supersampled, Backend::kReferenceDouble, linear);
  MemoryEstimate estimate;
  for (auto& part : frame.parts) {
    if (part.first.rfind("image ", 0) != 0) {  // the whole supersampled image is never held
      estimate.add(std::move(part.first), part.second);
    }
  }
  const std::uintmax_t band = std::uintmax_t(supersampled.viewport.width) *
                              std::uintmax_t(std::min(band_rows, supersampled.viewport.height));
  estimate.add("band of " +
                   size_text(supersampled.viewport.width,
                             std::min(band_rows, supersampled.viewport.height)) +
                   " samples",
               band * (3 + 12));
  // Linear radiance 12, sRGB 3 and its PNG 13, the float file's encoding 2 x 12.
  estimate.add("image " + size_text(width, height),
               std::uintmax_t(width) * std::uintmax_t(height) * (12 + kRenderPixelBytes + 24));
  return estimate;
}

MemoryEstimate estimate_stages_memory(const Scene& scene, Backend backend) {
  MemoryEstimate estimate;
  const std::uintmax_t lattice = std::uintmax_t(scene.terrain.lattice_size);
  estimate.add("noise lattice", lattice * lattice * sizeof(float));
  add_height_field(scene.terrain, estimate);
  if (scene.terrain.basis) {
    estimate.add("basis images and their composed grid", basis_memory_bytes(scene));
  }
  const std::uintmax_t grid_bytes =
      backend != Backend::kReferenceDouble ? kGridVertexBytes : 10 * 8 + 1;
  estimate.add("grid " + size_text(scene.grid.width, scene.grid.height),
               grid_vertices(scene) * (grid_bytes + kStagesVertexBytes));
  if (scene.terrain.planet && scene.terrain.planet->radius != 0.0) {
    estimate.add("the bend (bent positions and drop)",
                 grid_vertices(scene) * kStagesBentVertexBytes);
  }
  return estimate;
}

MemoryEstimate estimate_soup_memory(std::uintmax_t file_bytes) {
  MemoryEstimate estimate;
  estimate.add("parsed soup", (file_bytes / kMinSoupLineBytes + 1) * kSoupTriangleBytes);
  return estimate;
}

MemoryEstimate estimate_raster_memory(std::uintmax_t triangles, int width, int height) {
  MemoryEstimate estimate;
  estimate.add("soup and set-up", triangles * (kSoupTriangleBytes + kSetupTriangleBytes));
  estimate.add("framebuffer " + size_text(width, height),
               std::uintmax_t(width) * height * kRasterPixelBytes);
  return estimate;
}

}  // namespace relief
