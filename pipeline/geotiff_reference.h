// terrain.heightfield.georeferenced: a GeoTIFF's own placement as the field's extent.
//
// The GeoTIFF 1.1 specification (OGC 19-008r4) places a raster by tags of its first image
// file directory: ModelPixelScale (33550: Sx, Sy, Sz) with one ModelTiePoint (33922: raster
// point I, J, K at model point X, Y, Z), so that raster point (i, j) lies at
// X + (i - I) Sx, Y - (j - J) Sy; the GeoKeyDirectory (34735) says what the model space is.
// Relief takes a projected model space in metres or feet (GTModelTypeGeoKey 1, or 3 for
// geocentric is refused; ProjLinearUnitsGeoKey 9001 metre, 9002 foot, 9003 US survey foot,
// absent: metres) and refuses the rest naming why: a geographic space (degrees: a field is
// flat, so it would need a map projection first), a ModelTransformation (33920: rotation or
// shear), several tie points (a warp), a scale that is not positive and finite, vertical
// units other than metres (VerticalUnitsGeoKey 4099), and a key Relief reads whose value is
// stored outside the directory. An absent ProjLinearUnitsGeoKey is taken as metres.
// Raster space: with PixelIsArea (GTRasterTypeGeoKey 1025 = 1, the default) raster point
// (0, 0) is the top-left pixel's corner, so the extent's corners are raster points (0, 0) and
// (W, H); with PixelIsPoint (2) it is the first pixel's centre, half a pixel further in.
// World axes: x east = X, z = -Y (Relief's north is -z: row 0, the top, at z0).
// The tags are read with the file's byte order from classic TIFF (BigTIFF refused) without
// any image library.
#pragma once

#include <array>

#include "core/scene/scene.h"

namespace relief {

// The world extent [x0, z0, x1, z1] of the width x height samples of `settings.image` (a
// .tif / .tiff file), in metres. Throws SceneError naming terrain.heightfield.georeferenced
// and the reason when the file holds no usable georeferencing.
std::array<double, 4> georeferenced_extent(const HeightFieldSettings& settings, int width,
                                           int height);

}  // namespace relief
