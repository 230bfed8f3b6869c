#include "pipeline/tile_pass.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/srgb.h"
#include "pipeline/tile_reflections.h"
#include "pipeline/tile_shadows.h"
#include "raster/resolve.h"
#include "simd/raster_tile.h"
#include "simd/resolve.h"
#include "simd/shade.h"
#include "simd/srgb.h"

namespace relief {

namespace {

using Clock = std::chrono::steady_clock;

std::int64_t nanoseconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count();
}

// A tile's scratch buffers: visibility, attributes and linear radiance (about 0.8 MB in
// double), allocated per tile so that concurrent tiles never share them.
template <class Real>
struct TileScratch {
  raster::TileVisibility visibility;
  TileAttributes<Real> attributes;
  Real rgb[3 * raster::kTileSize * raster::kTileSize];
};

// The simd resolve's triangle slots (simd/resolve.h): one per run of pixels a triangle wins,
// at most one per pixel.
struct ResolveScratch {
  static constexpr int kPixels = raster::kTileSize * raster::kTileSize;
  // A direct-mapped cache from primitive to slot, so that a triangle's pixels on several rows
  // share one slot (one plane and one record) where they are not separated by a collision.
  static constexpr std::uint32_t kCacheEntries = 1024;
  std::int32_t slot[kPixels];
  double k[3][kPixels], ku[3][kPixels], kv[3][kPixels];
  std::int32_t vertex[3][kPixels];
  float records[kPixels * simd::kSlotRecordFloats];
  std::uint32_t cached_primitive[kCacheEntries];
  std::int32_t cached_slot[kCacheEntries];
};

// Calls visit(px, py, k, primitive) for each pixel of the tile a triangle covers, row by row
// (the order both resolves set their planes up in), counting them in work.covered_pixels.
template <class Visit>
void for_each_covered_pixel(const raster::TileVisibility& visibility, TileWork& work,
                            Visit&& visit) {
  for (int py = visibility.y0; py < visibility.y0 + visibility.height; ++py) {
    for (int px = visibility.x0; px < visibility.x0 + visibility.width; ++px) {
      const std::size_t k = visibility.index(px, py);
      const std::uint32_t primitive = visibility.primitive[k];
      if (primitive != raster::kNoPrimitive) {
        ++work.covered_pixels;
        visit(px, py, k, primitive);
      }
    }
  }
}

}  // namespace

void rasterize_tile_simd(std::span<const raster::SetupChunk> chunks, const raster::TileGrid& tiles,
                         int tile, const raster::RasterState& state, raster::TileVisibility& out) {
  static_assert(int(raster::DepthTest::kGreater) == int(simd::DepthCompare::kGreater) &&
                int(raster::DepthTest::kGreaterEqual) == int(simd::DepthCompare::kGreaterEqual) &&
                int(raster::DepthTest::kLess) == int(simd::DepthCompare::kLess) &&
                int(raster::DepthTest::kLessEqual) == int(simd::DepthCompare::kLessEqual) &&
                int(raster::DepthTest::kEqual) == int(simd::DepthCompare::kEqual) &&
                int(raster::DepthTest::kAlways) == int(simd::DepthCompare::kAlways) &&
                int(raster::DepthTest::kNever) == int(simd::DepthCompare::kNever));
  raster::clear_tile(tiles, tile, state, out);
  const int tx = tile % tiles.columns * raster::kTileSize;
  const int ty = tile / tiles.columns * raster::kTileSize;
  std::vector<simd::EdgeTriangle> list;
  list.reserve(raster::tile_entry_count(chunks, tile));
  for (const raster::SetupChunk& chunk : chunks) {
    for (std::uint32_t e = chunk.tile_start[tile]; e < chunk.tile_start[tile + 1]; ++e) {
      // Clipped to the tile as raster's draw_in_tile clips it.
      const raster::RasterTriangle& t = chunk.triangles[chunk.entries[e]];
      list.push_back({t.c, t.a, t.b, std::max(t.x0, tx), std::min(t.x1, tx + raster::kTileSize - 1),
                      std::max(t.y0, ty), std::min(t.y1, ty + raster::kTileSize - 1), t.z0, t.dzdx,
                      t.dzdy, t.primitive});
    }
  }
  simd::draw_triangles(list.data(), list.size(), simd::DepthCompare(int(state.depth_test)),
                       {out.x0, out.y0, out.depth, out.primitive});
}

template <class Real>
TilePass<Real>::TilePass(const raster::RasterState& state, const raster::FrameTriangles& triangles,
                         VertexStreams<Real> streams, const ShadeParams<Real>& shade,
                         const ShadeResources& resources, const FrameOutputs& outputs,
                         double camera_y, FrameImage& image, TileKernels kernels, int first_row,
                         TileShadows<Real> shadows)
    : state_(state),
      triangles_(triangles),
      streams_(streams),
      shade_(shade),
      resources_(resources),
      outputs_(outputs),
      camera_y_(camera_y),
      image_(image),
      kernels_(std::is_same_v<Real, float> ? kernels : TileKernels{}),
      first_row_(first_row),
      shadows_(shadows),
      scale_x_(state.viewport.width * 0.5),
      scale_y_(state.viewport.height * 0.5),
      translate_x_(state.viewport.x + state.viewport.width * 0.5),
      translate_y_(state.viewport.y + state.viewport.height * 0.5) {}

// Homogeneous window position (X, Y, W) of a vertex: raster::VertexPositions' formula.
template <class Real>
void TilePass<Real>::position(std::uint32_t vertex, double& x, double& y, double& w) const {
  w = streams_.clip_w[vertex];
  x = streams_.clip_x[vertex] * scale_x_ + w * translate_x_;
  y = streams_.clip_y[vertex] * scale_y_ + w * translate_y_;
}

// Stage 7 for one tile: raster::resolve's arithmetic (resolve.h), pixel for pixel. Values are
// interpolated in double and rounded once to Real; derivatives are GL's dFdxFine/dFdyFine from
// the winning triangle at the quad partners (helper pixels), zero where undefined.
template <class Real>
void TilePass<Real>::resolve(const raster::TileVisibility& visibility, TileAttributes<Real>& out,
                             TileWork& work) const {
  std::uint32_t cached = raster::kNoPrimitive;
  std::uint32_t v[3] = {0, 0, 0};
  const double zero[3] = {0, 0, 0};
  raster::PerspectivePlane plane(zero, zero, zero);
  const VertexStreams<Real>& s = streams_;
  const bool with_nu = outputs_.octaves && !s.nu.empty();
  // No terrain under water in view: the depth is not interpolated (stage 8 does not read it).
  const bool with_water = shade_.terrain_water != 0;
  for_each_covered_pixel(
      visibility, work, [&](int px, int py, std::size_t k, std::uint32_t primitive) {
        // Neighbouring pixels mostly share their triangle: set its plane up once per run.
        if (primitive != cached) {
          cached = primitive;
          triangles_.vertices(primitive, v);
          double x[3], y[3], w[3];
          for (int i = 0; i < 3; ++i) {
            position(v[i], x[i], y[i], w[i]);
          }
          plane = raster::PerspectivePlane(x, y, w);
        }
        const raster::QuadWeights q = raster::quad_weights(plane, px, py);
        const auto at = [&](std::span<const Real> a, const double weights[3]) {
          return raster::QuadWeights::at(weights, a[v[0]], a[v[1]], a[v[2]]);
        };
        const auto with_derivatives = [&](std::span<const Real> a, Real& value, Real& ddx,
                                          Real& ddy) {
          const double centre = at(a, q.b);
          value = static_cast<Real>(centre);
          ddx = q.has_x ? static_cast<Real>(q.sign_x * (at(a, q.bx) - centre)) : Real(0);
          ddy = q.has_y ? static_cast<Real>(q.sign_y * (at(a, q.by) - centre)) : Real(0);
        };
        with_derivatives(s.dx, out.dx[k], out.dx_ddx[k], out.dx_ddy[k]);
        with_derivatives(s.dz, out.dz[k], out.dz_ddx[k], out.dz_ddy[k]);
        with_derivatives(s.height, out.height[k], out.height_ddx[k], out.height_ddy[k]);
        out.nx[k] = static_cast<Real>(at(s.nx, q.b));
        out.ny[k] = static_cast<Real>(at(s.ny, q.b));
        out.nz[k] = static_cast<Real>(at(s.nz, q.b));
        out.slope[k] = static_cast<Real>(at(s.slope, q.b));
        out.water_depth[k] = with_water ? static_cast<Real>(at(s.water_depth, q.b)) : Real(0);
        out.drop[k] = s.drop.empty() ? Real(0) : static_cast<Real>(at(s.drop, q.b));
        out.lambert[k] = s.lambert.empty() ? Real(0) : static_cast<Real>(at(s.lambert, q.b));
        if (with_nu) {
          out.nu[k] = static_cast<Real>(at(s.nu, q.b));
        }
      });
}

// Stage 7 with the simd kernels (simd/resolve.h): a slot per run of pixels a triangle wins, as
// resolve() sets a plane up per run; the slots' planes, then every pixel, in double lanes.
template <class Real>
void TilePass<Real>::resolve_simd(const raster::TileVisibility& visibility,
                                  TileAttributes<Real>& out, TileWork& work) const {
  if constexpr (std::is_same_v<Real, float>) {
    thread_local const std::unique_ptr<ResolveScratch> scratch(new ResolveScratch);  // as run()'s
    std::fill(std::begin(scratch->slot), std::end(scratch->slot), -1);
    std::fill(std::begin(scratch->cached_primitive), std::end(scratch->cached_primitive),
              raster::kNoPrimitive);
    int slots = 0;
    for_each_covered_pixel(visibility, work, [&](int, int, std::size_t k, std::uint32_t primitive) {
      const std::uint32_t entry = primitive % ResolveScratch::kCacheEntries;
      if (scratch->cached_primitive[entry] != primitive) {
        scratch->cached_primitive[entry] = primitive;
        scratch->cached_slot[entry] = slots;
        std::uint32_t v[3];
        triangles_.vertices(primitive, v);
        for (int i = 0; i < 3; ++i) {
          scratch->vertex[i][slots] = static_cast<std::int32_t>(v[i]);
        }
        ++slots;
      }
      scratch->slot[k] = scratch->cached_slot[entry];
    });
    if (slots == 0) {
      return;
    }
    // The slots' planes (raster::PerspectivePlane from VertexPositions), in double lanes.
    const std::int32_t* const vertex[3] = {scratch->vertex[0], scratch->vertex[1],
                                           scratch->vertex[2]};
    double* const k[3] = {scratch->k[0], scratch->k[1], scratch->k[2]};
    double* const ku[3] = {scratch->ku[0], scratch->ku[1], scratch->ku[2]};
    double* const kv[3] = {scratch->kv[0], scratch->kv[1], scratch->kv[2]};
    simd::set_up_planes(streams_.clip_x.data(), streams_.clip_y.data(), streams_.clip_w.data(),
                        {scale_x_, scale_y_, translate_x_, translate_y_}, vertex,
                        static_cast<std::size_t>(slots), k, ku, kv);
    const VertexStreams<Real>& s = streams_;
    const bool with_nu = outputs_.octaves && !s.nu.empty();
    const simd::ResolveStreams streams{s.dx.data(),
                                       s.dz.data(),
                                       s.height.data(),
                                       s.nx.data(),
                                       s.ny.data(),
                                       s.nz.data(),
                                       s.slope.data(),
                                       shade_.terrain_water != 0 ? s.water_depth.data() : nullptr,
                                       with_nu ? s.nu.data() : nullptr,
                                       s.lambert.empty() ? nullptr : s.lambert.data(),
                                       s.drop.empty() ? nullptr : s.drop.data()};
    simd::gather_slot_records(streams, vertex, static_cast<std::size_t>(slots), scratch->records);
    const simd::ResolveSlots table{{scratch->k[0], scratch->k[1], scratch->k[2]},
                                   {scratch->ku[0], scratch->ku[1], scratch->ku[2]},
                                   {scratch->kv[0], scratch->kv[1], scratch->kv[2]},
                                   scratch->records};
    const simd::ResolveTargets targets{
        out.dx,     out.dz,          out.height,     out.dx_ddx,  out.dx_ddy, out.dz_ddx,
        out.dz_ddy, out.height_ddx,  out.height_ddy, out.nx,      out.ny,     out.nz,
        out.slope,  out.water_depth, out.nu,         out.lambert, out.drop};
    simd::resolve_rect(table, streams, scratch->slot, visibility.x0, visibility.y0,
                       visibility.width, visibility.height, raster::kTileSize, targets);
  }
}

template <class Real>
void TilePass<Real>::run(std::span<const raster::SetupChunk> chunks, const raster::TileGrid& tiles,
                         int tile, TileTimes& times, bool skip_empty) const {
  // One scratch per thread, kept from tile to tile: a tile runs on one thread from start to
  // end (no parallel construct inside), and a fresh 0.8 MB block per tile left the memory a
  // frame holds to the allocator (a freed block not reused in place keeps two resident in a
  // thread's arena: the stress suite measured 0.9 MiB more in some runs than in others) and
  // its page faults to every tile. Default-initialised once: every field a pixel reads is
  // written first.
  thread_local const std::unique_ptr<TileScratch<Real>> scratch(new TileScratch<Real>);
  raster::TileVisibility& vis = scratch->visibility;
  TileWork work;
  const Clock::time_point start = Clock::now();
  const std::uint64_t entries = raster::tile_entry_count(chunks, tile);
  const bool drawn = entries > 0 || !skip_empty;
  if (drawn && kernels_.raster == KernelKind::kHighway) {
    rasterize_tile_simd(chunks, tiles, tile, state_, vis);
  } else if (drawn) {
    raster::rasterize_tile(chunks, tiles, tile, state_, vis);
  } else {
    raster::clear_tile(tiles, tile, state_, vis);  // nothing binned: nothing covered
  }
  const Clock::time_point rasterised = Clock::now();
  if (drawn) {
    if (kernels_.resolve == KernelKind::kHighway) {
      resolve_simd(vis, scratch->attributes, work);
    } else {
      resolve(vis, scratch->attributes, work);
    }
    ++work.tiles_drawn;
    work.tile_triangles += entries;
  }
  const Clock::time_point resolved = Clock::now();

  // Cast shadows and sky light: each covered pixel's share of the sun disc and of the sky
  // (tile_shadows.h).
  if (drawn) {
    const bool highway_shade =
        std::is_same_v<Real, float> && kernels_.shade == KernelKind::kHighway;
    tile_sun_shares(shadows_, kernels_.sun, highway_shade, vis, scratch->attributes, work.shadow);
    tile_sky_shares(shadows_, kernels_.sky, highway_shade, vis, scratch->attributes, work.sky);
    tile_water_sun_shares(shadows_, shade_, kernels_.sun, highway_shade, vis, scratch->attributes,
                          work.water_shadow);
    tile_water_reflections(shadows_, shade_, resources_, kernels_.reflect, highway_shade, vis,
                           scratch->attributes, work.reflection, work.shade);
  }
  const Clock::time_point shadowed = Clock::now();

  // Stage 8: every pixel of the tile, radiance times the exposure; pixels no triangle covers
  // get the background and no terrain shading.
  bool shaded_simd = false;
  if constexpr (std::is_same_v<Real, float>) {
    if (kernels_.shade == KernelKind::kHighway) {
      const bool water_sun =
          shadows_.params != nullptr && shade_.water_enabled && shade_.terrain_water;
      const ShadingInputs in = scratch->attributes.inputs(
          vis.primitive, {!streams_.drop.empty(), shadows_.params != nullptr,
                          shadows_.sky != nullptr, !streams_.lambert.empty(), water_sun,
                          shadows_.reflections != nullptr && shade_.terrain_reflections != 0});
      simd::shade_rect(shade_, resources_, in, vis.x0, vis.y0, vis.width, vis.height,
                       raster::kTileSize, std::span<float>(scratch->rgb), work.shade);
      shaded_simd = true;
    }
  }
  for (int py = vis.y0; !shaded_simd && py < vis.y0 + vis.height; ++py) {
    for (int px = vis.x0; px < vis.x0 + vis.width; ++px) {
      const std::size_t k = vis.index(px, py);
      const Vec3<Real> radiance =
          vis.primitive[k] != raster::kNoPrimitive
              ? terrain_radiance<Real>(shade_, resources_, scratch->attributes.at(k), work.shade)
              : background_radiance<Real>(shade_, resources_, px, py, work.shade);
      scratch->rgb[3 * k] = radiance.x * shade_.exposure;
      scratch->rgb[3 * k + 1] = radiance.y * shade_.exposure;
      scratch->rgb[3 * k + 2] = radiance.z * shade_.exposure;
    }
  }
  const Clock::time_point shaded = Clock::now();

  // Stage 9: finished pixels only, into the frame's image and the requested outputs.
  const int width = image_.width;
  for (int py = vis.y0; py < vis.y0 + vis.height; ++py) {
    const std::size_t first = vis.index(vis.x0, py);
    const std::size_t pixel = static_cast<std::size_t>(py - first_row_) * width + vis.x0;
    const std::size_t values = 3 * static_cast<std::size_t>(vis.width);
    if constexpr (std::is_same_v<Real, float>) {
      if (kernels_.encode == KernelKind::kHighway) {
        simd::encode_srgb(std::span<const float>(scratch->rgb + 3 * first, values),
                          std::span<std::uint8_t>(image_.srgb.data() + 3 * pixel, values));
        continue;
      }
    }
    for (std::size_t c = 0; c < values; ++c) {
      image_.srgb[3 * pixel + c] = srgb_byte(static_cast<float>(scratch->rgb[3 * first + c]));
    }
  }
  const FrameOutputs& o = outputs_;
  const bool any_output =
      o.linear || o.depth || o.primitive || o.normal || o.world_height || o.octaves;
  for (int py = vis.y0; any_output && py < vis.y0 + vis.height; ++py) {
    for (int px = vis.x0; px < vis.x0 + vis.width; ++px) {
      const std::size_t k = vis.index(px, py);
      const std::size_t pixel = static_cast<std::size_t>(py - first_row_) * width + px;
      if (outputs_.linear) {
        for (int c = 0; c < 3; ++c) {
          image_.linear[3 * pixel + c] = static_cast<float>(scratch->rgb[3 * k + c]);
        }
      }
      const bool covered = vis.primitive[k] != raster::kNoPrimitive;
      if (outputs_.depth) {
        image_.depth[pixel] = vis.depth[k];
      }
      if (outputs_.primitive) {
        image_.primitive[pixel] = vis.primitive[k];
      }
      if (!covered) {
        continue;  // the other outputs keep their cleared zeros
      }
      const TileAttributes<Real>& a = scratch->attributes;
      if (outputs_.normal) {
        // The normal shading used: renormalised, (0, 1, 0) where undefined.
        const Vec3<Real> n = normalize_or(Vec3<Real>{a.nx[k], a.ny[k], a.nz[k]},
                                          Vec3<Real>{Real(0), Real(1), Real(0)});
        image_.normal[3 * pixel] = static_cast<float>(n.x);
        image_.normal[3 * pixel + 1] = static_cast<float>(n.y);
        image_.normal[3 * pixel + 2] = static_cast<float>(n.z);
      }
      if (outputs_.world_height) {
        image_.world_height[pixel] = static_cast<float>(camera_y_ + double(a.height[k]));
      }
      if (outputs_.octaves && !streams_.nu.empty()) {
        image_.octaves[pixel] = static_cast<float>(a.nu[k]);
      }
    }
  }
  const Clock::time_point encoded = Clock::now();
  times.raster_ns += nanoseconds_between(start, rasterised);
  times.resolve_ns += nanoseconds_between(rasterised, resolved);
  times.shadow_ns += nanoseconds_between(resolved, shadowed);
  times.shade_ns += nanoseconds_between(shadowed, shaded);
  times.encode_ns += nanoseconds_between(shaded, encoded);
  times.add(work);
}

template class TilePass<float>;
template class TilePass<double>;

}  // namespace relief
