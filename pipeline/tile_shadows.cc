#include "pipeline/tile_shadows.h"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <type_traits>

#include "simd/sky_share.h"
#include "simd/sun_share.h"

namespace relief {

namespace {

// Writes `share` at every covered pixel of `vis`: 1 where the effect is off (and only where
// the portable shade reads it), else `highway(a)` in float where that kernel is chosen, else
// `portable(k)` pixel by pixel (the same bits either way). `highway` takes the attributes as
// a generic parameter, so that the double backends never instantiate its float kernel.
template <class Real, class Highway, class Portable>
void tile_shares(bool on, KernelKind kind, bool highway_shade, const raster::TileVisibility& vis,
                 TileAttributes<Real>& a, Real* share, Highway&& highway, Portable&& portable) {
  if (!on) {
    if (!highway_shade) {  // the portable shade reads the share of every covered pixel
      std::fill(share, share + TileAttributes<Real>::kPixels, Real(1));
    }
    return;
  }
  if constexpr (std::is_same_v<Real, float>) {
    if (kind == KernelKind::kHighway) {
      highway(a);
      return;
    }
  }
  for (int py = vis.y0; py < vis.y0 + vis.height; ++py) {
    for (int px = vis.x0; px < vis.x0 + vis.width; ++px) {
      const std::size_t k = vis.index(px, py);
      if (vis.primitive[k] != raster::kNoPrimitive) {
        share[k] = portable(k);
      }
    }
  }
}

constexpr std::size_t kTilePixels = TileAttributes<float>::kPixels;

}  // namespace

template <class Real>
void tile_sun_shares(const TileShadows<Real>& shadows, KernelKind kind, bool highway_shade,
                     const raster::TileVisibility& vis, TileAttributes<Real>& a, ShadowWork& work) {
  tile_shares(
      shadows.params != nullptr, kind, highway_shade, vis, a, a.sun,
      [&](auto& f) {
        simd::sun_shares(*shadows.params, *shadows.cache, {vis.primitive, kTilePixels},
                         {f.dx, kTilePixels}, {f.height, kTilePixels}, {f.dz, kTilePixels},
                         vis.width, vis.height, raster::kTileSize, {f.sun, kTilePixels}, work);
      },
      [&](std::size_t k) {
        return sun_visibility<Real>(*shadows.params, *shadows.cache, a.dx[k], a.height[k], a.dz[k],
                                    work);
      });
}

template <class Real>
void tile_water_sun_shares(const TileShadows<Real>& shadows, const ShadeParams<Real>& shade,
                           KernelKind kind, bool highway_shade, const raster::TileVisibility& vis,
                           TileAttributes<Real>& a, ShadowWork& work) {
  if (!shade.water_enabled || !shade.terrain_water) {
    return;  // no pixel has water in front
  }
  if (shadows.params == nullptr) {
    if (!highway_shade) {  // the portable shade reads the share of every pixel with water
      std::fill(a.water_sun, a.water_sun + TileAttributes<Real>::kPixels, Real(1));
    }
    return;
  }
  // One row at a time: the surface points (core/shade.cc: the view ray meets the water at
  // distance level / view.y, at position * (level / height)), pixels with no water in front
  // masked out. Both negative there (height < level < 0: water_enabled means the camera is
  // above the water), so the ratio lies in (0, 1): a point between the camera and the ground.
  constexpr int kRow = raster::kTileSize;
  const Real level = shade.water_level;
  for (int py = vis.y0; py < vis.y0 + vis.height; ++py) {
    const std::size_t row = vis.index(vis.x0, py);
    std::uint32_t water[kRow];
    Real sx[kRow] = {}, sy[kRow] = {}, sz[kRow] = {}, share[kRow];
    std::fill(std::begin(water), std::end(water), raster::kNoPrimitive);
    for (int i = 0; i < vis.width; ++i) {
      const std::size_t k = row + std::size_t(i);
      share[i] = Real(1);
      if (vis.primitive[k] == raster::kNoPrimitive || !(a.height[k] < level)) {
        continue;
      }
      const Real t = level / a.height[k];
      water[i] = vis.primitive[k];
      sx[i] = a.dx[k] * t;
      sy[i] = level;
      sz[i] = a.dz[k] * t;
    }
    bool highway = false;
    if constexpr (std::is_same_v<Real, float>) {
      if (kind == KernelKind::kHighway) {
        simd::sun_shares(*shadows.params, *shadows.cache, {water, kRow}, {sx, kRow}, {sy, kRow},
                         {sz, kRow}, vis.width, 1, kRow, {share, kRow}, work);
        highway = true;
      }
    }
    for (int i = 0; !highway && i < vis.width; ++i) {
      if (water[i] != raster::kNoPrimitive) {
        share[i] = sun_visibility<Real>(*shadows.params, *shadows.cache, sx[i], sy[i], sz[i], work);
      }
    }
    std::copy(share, share + vis.width, a.water_sun + row);
  }
}

template <class Real>
void tile_sky_shares(const TileShadows<Real>& shadows, KernelKind kind, bool highway_shade,
                     const raster::TileVisibility& vis, TileAttributes<Real>& a, SkyWork& work) {
  tile_shares(
      shadows.sky != nullptr, kind, highway_shade, vis, a, a.sky,
      [&](auto& f) {
        simd::sky_shares(*shadows.sky, *shadows.cache, {vis.primitive, kTilePixels},
                         {f.dx, kTilePixels}, {f.dz, kTilePixels}, vis.width, vis.height,
                         raster::kTileSize, {f.sky, kTilePixels}, work);
      },
      [&](std::size_t k) {
        return sky_visibility<Real>(*shadows.sky, *shadows.cache, a.dx[k], a.dz[k], work);
      });
}

template void tile_sun_shares<float>(const TileShadows<float>&, KernelKind, bool,
                                     const raster::TileVisibility&, TileAttributes<float>&,
                                     ShadowWork&);
template void tile_sun_shares<double>(const TileShadows<double>&, KernelKind, bool,
                                      const raster::TileVisibility&, TileAttributes<double>&,
                                      ShadowWork&);

template void tile_water_sun_shares<float>(const TileShadows<float>&, const ShadeParams<float>&,
                                           KernelKind, bool, const raster::TileVisibility&,
                                           TileAttributes<float>&, ShadowWork&);
template void tile_water_sun_shares<double>(const TileShadows<double>&, const ShadeParams<double>&,
                                            KernelKind, bool, const raster::TileVisibility&,
                                            TileAttributes<double>&, ShadowWork&);

template void tile_sky_shares<float>(const TileShadows<float>&, KernelKind, bool,
                                     const raster::TileVisibility&, TileAttributes<float>&,
                                     SkyWork&);
template void tile_sky_shares<double>(const TileShadows<double>&, KernelKind, bool,
                                      const raster::TileVisibility&, TileAttributes<double>&,
                                      SkyWork&);

}  // namespace relief
