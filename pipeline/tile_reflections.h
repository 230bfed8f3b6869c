// The terrain reflected in the water in a tile (tile_pass.h): after the shadows, at each
// covered pixel whose view ray meets the water before its ground, the reflected ray's terrain
// (core/water_reflection.h): the rays set up through the Highway kernel (simd/reflection_rays.h)
// or the portable step, the same bits either way, then one scalar march per pixel in every
// backend (the same bits for the simd backend's shade, which reads them as attributes).
#pragma once

#include "core/shade.h"
#include "core/stage_params.h"
#include "core/water_reflection.h"
#include "pipeline/kernel_kind.h"
#include "pipeline/tile_pass.h"
#include "raster/bins.h"

namespace relief {

// Writes attributes.reflection_* at every covered pixel of `visibility` that the shade reads
// them at: the radiance and weight 1 where the reflected ray meets the terrain, weight 0 (and
// radiance 0) elsewhere. Without reflections (`shadows.reflections` null) nothing is written
// for a Highway shade (which then reads none) and weight 0 everywhere for the portable one;
// nothing at all without terrain under water.
// `kind`: the rays' set-up (TileKernels::reflect), Highway in float only; the march is portable.
template <class Real>
void tile_water_reflections(const TileShadows<Real>& shadows, const ShadeParams<Real>& shade,
                            const ShadeResources& resources, KernelKind kind, bool highway_shade,
                            const raster::TileVisibility& visibility,
                            TileAttributes<Real>& attributes, ReflectionWork& work,
                            ShadeWork& shade_work);

}  // namespace relief
