#include "pipeline/tile_shadows.h"

#include <algorithm>
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

template void tile_sky_shares<float>(const TileShadows<float>&, KernelKind, bool,
                                     const raster::TileVisibility&, TileAttributes<float>&,
                                     SkyWork&);
template void tile_sky_shares<double>(const TileShadows<double>&, KernelKind, bool,
                                      const raster::TileVisibility&, TileAttributes<double>&,
                                      SkyWork&);

}  // namespace relief
