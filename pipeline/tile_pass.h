// The fused back end of a frame, one 64 x 64 screen tile at a time (stage_table.h, kTiles):
//   rasterise (stage 6) into a tile-local visibility buffer,
//   resolve (stage 7) the winning triangle's attributes and their quad derivatives into
//     tile-local structure-of-arrays buffers with named fields,
//   shade (stage 8) every pixel, and
//   encode (stage 9) it to sRGB in the frame's image, plus the outputs the caller asked for.
// Quads start at even coordinates and tiles at multiples of 64, so no quad crosses a tile: a
// tile needs nothing from its neighbours. The arithmetic is raster::resolve's and
// shade_pixels'; the images are bit-identical to running the stages one after another over
// the whole frame (tests/pipeline/frame_test.cc,
// tileFusedFramesEqualTheStagesRunOverTheWholeFrame...).
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <type_traits>

#include "core/shade.h"
#include "core/sky_horizons.h"
#include "core/stage_params.h"
#include "core/sun_visibility.h"
#include "core/water_reflection.h"
#include "pipeline/frame.h"
#include "pipeline/kernel_kind.h"
#include "raster/bins.h"
#include "raster/topology.h"

namespace relief {

// Per grid vertex, what the resolve interpolates: the positions (clip x, y, w) and the
// attribute streams of stages 2-4, in the backend's precision. `nu` may be empty (then the
// octave-count output is not available).
template <class Real>
struct VertexStreams {
  std::span<const Real> clip_x, clip_y, clip_w;
  std::span<const Real> dx, dz, height, nx, ny, nz, slope, water_depth, nu;
  // A planet's curvature drop (planet_bend.h); empty on the plane, where neither resolve
  // interpolates it.
  std::span<const Real> drop = {};
  // Gradient mode's per-vertex Lambert term (stage 5, gradient_shade.h); empty otherwise.
  std::span<const Real> lambert = {};
};

// Stage 7's output for one tile: one named array per field, kTileSize x kTileSize each, row-
// major from the tile's bottom row. Only covered pixels are written.
template <class Real>
struct TileAttributes {
  static constexpr int kPixels = raster::kTileSize * raster::kTileSize;
  Real dx[kPixels], dz[kPixels], height[kPixels];
  Real dx_ddx[kPixels], dx_ddy[kPixels], dz_ddx[kPixels], dz_ddy[kPixels];
  Real height_ddx[kPixels], height_ddy[kPixels];
  Real nx[kPixels], ny[kPixels], nz[kPixels];
  Real slope[kPixels], water_depth[kPixels], nu[kPixels];
  Real drop[kPixels];     // a planet's; 0 on the plane (unwritten by the simd resolve there)
  Real sun[kPixels];      // the sun disc's visible share (sun_visibility.h); 1 without shadows
  Real sky[kPixels];      // the sky's open share (sky_horizons.h); 1 without sky light
  Real lambert[kPixels];  // gradient mode's interpolated Lambert term (gradient_shade.h)
  // The sun's share at the water surface in front of the pixel's ground (tile_shadows.h); 1
  // without cast shadows, and where no water lies in front.
  Real water_sun[kPixels];
  // There too, the terrain the reflected ray meets and its weight (tile_reflections.h); weight
  // 0 without reflections, and where no water lies in front.
  Real reflection_r[kPixels], reflection_g[kPixels], reflection_b[kPixels];
  Real reflection_weight[kPixels];

  PixelAttributes<Real> at(std::size_t k) const {
    return {dx[k],
            dz[k],
            height[k],
            dx_ddx[k],
            dx_ddy[k],
            dz_ddx[k],
            dz_ddy[k],
            height_ddx[k],
            height_ddy[k],
            nx[k],
            ny[k],
            nz[k],
            slope[k],
            water_depth[k],
            drop[k],
            sun[k],
            sky[k],
            lambert[k],
            water_sun[k],
            reflection_r[k],
            reflection_g[k],
            reflection_b[k],
            reflection_weight[k]};
  }

  // The tile as stage 8's Highway kernel reads it (core/shade.h's ShadingInputs), the optional
  // fields empty where the frame has none (read as their constants there).
  struct Present {
    bool drop, sun, sky, lambert, water_sun, reflection;
  };
  ShadingInputs inputs(const std::uint32_t* primitive,
                       Present present) const requires std::is_same_v<Real, float> {
    constexpr std::size_t n = kPixels;
    const auto optional = [](bool on, const float* field) {
      return on ? std::span<const float>(field, n) : std::span<const float>{};
    };
    return {{primitive, n},
            {dx, n},
            {dz, n},
            {height, n},
            {dx_ddx, n},
            {dx_ddy, n},
            {dz_ddx, n},
            {dz_ddy, n},
            {height_ddx, n},
            {height_ddy, n},
            {nx, n},
            {ny, n},
            {nz, n},
            {slope, n},
            {water_depth, n},
            optional(present.drop, drop),
            optional(present.sun, sun),
            optional(present.sky, sky),
            optional(present.lambert, lambert),
            optional(present.water_sun, water_sun),
            optional(present.reflection, reflection_r),
            optional(present.reflection, reflection_g),
            optional(present.reflection, reflection_b),
            optional(present.reflection, reflection_weight)};
  }
};

// The work of the tiles (docs/stages.md, "Skipped work"), summed over all tiles.
struct TileWork {
  std::uint64_t tiles_drawn = 0;     // tiles with a triangle binned: rasterised and resolved
  std::uint64_t tile_triangles = 0;  // (triangle, tile) pairs rasterised
  std::uint64_t covered_pixels = 0;  // pixels a triangle covers: attributes resolved
  ShadeWork shade;
  ShadowWork shadow;          // cast shadows' lookups (sun_visibility.h)
  SkyWork sky;                // sky light's lookups (sky_horizons.h)
  ShadowWork water_shadow;    // cast shadows' lookups at water surfaces (tile_shadows.h)
  ReflectionWork reflection;  // the reflected rays (core/water_reflection.h)

  TileWork& operator+=(const TileWork& o) {
    tiles_drawn += o.tiles_drawn;
    tile_triangles += o.tile_triangles;
    covered_pixels += o.covered_pixels;
    shade += o.shade;
    shadow += o.shadow;
    sky += o.sky;
    water_shadow += o.water_shadow;
    reflection += o.reflection;
    return *this;
  }
};

// CPU time spent in each part of the fused stage, summed over all threads, and the work done
// (sums of integers: the same whichever threads ran which tiles).
struct TileTimes {
  std::atomic<std::int64_t> raster_ns{0}, resolve_ns{0}, shadow_ns{0}, shade_ns{0}, encode_ns{0};
  std::mutex mutex;
  TileWork work;  // guarded by mutex

  void add(const TileWork& tile) {
    const std::lock_guard<std::mutex> lock(mutex);
    work += tile;
  }
};

// raster::rasterize_tile with the simd kernel of its inner loop (simd/raster_tile.h): the
// same visibility, bit for bit.
void rasterize_tile_simd(std::span<const raster::SetupChunk> chunks, const raster::TileGrid& tiles,
                         int tile, const raster::RasterState& state, raster::TileVisibility& out);

// Cast shadows and sky light for the tiles: the frame's parameters and its swept horizon
// cache (sun_horizons.h, sky_horizons.h); null params: no shadows, every pixel sees the whole
// sun; null sky: no sky light, every pixel sees the whole sky.
template <class Real>
struct TileShadows {
  const ShadowParams<Real>* params = nullptr;
  const SunHorizonCache<Real>* cache = nullptr;
  const ShadowParams<Real>* sky = nullptr;
  // With the water's reflections (water.reflect_terrain): the cache's layout and its blocks'
  // maxima (core/water_reflection.h); null without.
  const ShadowParams<Real>* reflections = nullptr;
  const HeightBlockMaxima<Real>* maxima = nullptr;
};

template <class Real>
class TilePass {
 public:
  // `image` must be sized (width, height, srgb, and each requested output) before run().
  // `kernels`: each part's kind (cpu_kernels.h); Highway parts in float only, the same bytes.
  // `first_row`: the framebuffer row that is the image's row 0, for an image holding a band of
  // rows (render_frame_bands, frame.h); only tiles inside the band may then be run.
  TilePass(const raster::RasterState& state, const raster::FrameTriangles& triangles,
           VertexStreams<Real> streams, const ShadeParams<Real>& shade,
           const ShadeResources& resources, const FrameOutputs& outputs, double camera_y,
           FrameImage& image, TileKernels kernels = {}, int first_row = 0,
           TileShadows<Real> shadows = {});

  // Renders tile `tile`; tiles may run concurrently (each writes only its own pixels). With
  // `skip_empty`, a tile no triangle is binned to is not rasterised or resolved.
  void run(std::span<const raster::SetupChunk> chunks, const raster::TileGrid& tiles, int tile,
           TileTimes& times, bool skip_empty = true) const;

 private:
  void resolve(const raster::TileVisibility& visibility, TileAttributes<Real>& out,
               TileWork& work) const;
  void resolve_simd(const raster::TileVisibility& visibility, TileAttributes<Real>& out,
                    TileWork& work) const;
  void position(std::uint32_t vertex, double& x, double& y, double& w) const;

  const raster::RasterState& state_;
  raster::FrameTriangles triangles_;
  VertexStreams<Real> streams_;
  const ShadeParams<Real>& shade_;
  ShadeResources resources_;
  FrameOutputs outputs_;
  double camera_y_;
  FrameImage& image_;
  TileKernels kernels_;
  int first_row_;
  TileShadows<Real> shadows_;
  double scale_x_, scale_y_, translate_x_, translate_y_;  // viewport, as VertexPositions
};

}  // namespace relief
