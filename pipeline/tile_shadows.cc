#include "pipeline/tile_shadows.h"

#include <algorithm>
#include <type_traits>

#include "simd/sky_share.h"
#include "simd/sun_share.h"

namespace relief {

template <class Real>
void tile_sun_shares(const TileShadows<Real>& shadows, KernelKind kind, bool highway_shade,
                     const raster::TileVisibility& vis, TileAttributes<Real>& a, ShadowWork& work) {
  if (shadows.params == nullptr) {
    if (!highway_shade) {  // the portable shade reads the share of every covered pixel
      std::fill(a.sun, a.sun + TileAttributes<Real>::kPixels, Real(1));
    }
    return;
  }
  if constexpr (std::is_same_v<Real, float>) {
    if (kind == KernelKind::kHighway) {
      constexpr std::size_t n = TileAttributes<float>::kPixels;
      simd::sun_shares(*shadows.params, *shadows.cache, {vis.primitive, n}, {a.dx, n},
                       {a.height, n}, {a.dz, n}, vis.width, vis.height, raster::kTileSize,
                       {a.sun, n}, work);
      return;
    }
  }
  for (int py = vis.y0; py < vis.y0 + vis.height; ++py) {
    for (int px = vis.x0; px < vis.x0 + vis.width; ++px) {
      const std::size_t k = vis.index(px, py);
      if (vis.primitive[k] != raster::kNoPrimitive) {
        a.sun[k] = sun_visibility<Real>(*shadows.params, *shadows.cache, a.dx[k], a.height[k],
                                        a.dz[k], work);
      }
    }
  }
}

template <class Real>
void tile_sky_shares(const TileShadows<Real>& shadows, KernelKind kind, bool highway_shade,
                     const raster::TileVisibility& vis, TileAttributes<Real>& a, SkyWork& work) {
  if (shadows.sky == nullptr) {
    if (!highway_shade) {  // the portable shade reads the share of every covered pixel
      std::fill(a.sky, a.sky + TileAttributes<Real>::kPixels, Real(1));
    }
    return;
  }
  if constexpr (std::is_same_v<Real, float>) {
    if (kind == KernelKind::kHighway) {
      constexpr std::size_t n = TileAttributes<float>::kPixels;
      simd::sky_shares(*shadows.sky, *shadows.cache, {vis.primitive, n}, {a.dx, n}, {a.dz, n},
                       vis.width, vis.height, raster::kTileSize, {a.sky, n}, work);
      return;
    }
  }
  for (int py = vis.y0; py < vis.y0 + vis.height; ++py) {
    for (int px = vis.x0; px < vis.x0 + vis.width; ++px) {
      const std::size_t k = vis.index(px, py);
      if (vis.primitive[k] != raster::kNoPrimitive) {
        a.sky[k] = sky_visibility<Real>(*shadows.sky, *shadows.cache, a.dx[k], a.dz[k], work);
      }
    }
  }
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
