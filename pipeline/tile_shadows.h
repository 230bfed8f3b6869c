// Cast shadows and sky light in a tile (tile_pass.h): after the resolve, each covered pixel's
// share of the sun disc (core/sun_visibility.h), through the Highway kernel (simd/sun_share.h)
// or the portable step, the same bits either way, and its share of the sky
// (core/sky_horizons.h).
#pragma once

#include "core/stage_params.h"
#include "core/sun_visibility.h"
#include "pipeline/kernel_kind.h"
#include "pipeline/tile_pass.h"
#include "raster/bins.h"

namespace relief {

// Writes `attributes.sun` at every covered pixel of `visibility`: the share with `shadows`
// (params non-null), else 1. Without shadows and with a Highway shade (which then reads no
// share, tile_pass.cc) nothing is written. `kind`: the sun's kernel (TileKernels::sun), Highway
// in float only.
template <class Real>
void tile_sun_shares(const TileShadows<Real>& shadows, KernelKind kind, bool highway_shade,
                     const raster::TileVisibility& visibility, TileAttributes<Real>& attributes,
                     ShadowWork& work);

// Writes `attributes.water_sun` at every covered pixel of `visibility` whose view ray meets the
// water surface before its ground (the test of core/shade.cc, with `shade`'s camera-relative
// water level): the sun disc's share at that surface point, pixel position times level /
// height, through the sun's kernel as tile_sun_shares; 1 at the other covered pixels. Without
// cast shadows 1 everywhere (nothing with a Highway shade, which then reads no share); nothing
// without terrain under water.
template <class Real>
void tile_water_sun_shares(const TileShadows<Real>& shadows, const ShadeParams<Real>& shade,
                           KernelKind kind, bool highway_shade,
                           const raster::TileVisibility& visibility,
                           TileAttributes<Real>& attributes, ShadowWork& work);

// Writes `attributes.sky` at every covered pixel of `visibility`: the sky's open share with
// sky light (`shadows.sky` non-null), else 1 (nothing written with a Highway shade, as above).
// `kind`: the sky's kernel (TileKernels::sky, simd/sky_share.h), Highway in float only.
template <class Real>
void tile_sky_shares(const TileShadows<Real>& shadows, KernelKind kind, bool highway_shade,
                     const raster::TileVisibility& visibility, TileAttributes<Real>& attributes,
                     SkyWork& work);

}  // namespace relief
