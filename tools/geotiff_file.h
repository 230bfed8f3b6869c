// A height map as a GeoTIFF, for `relief export -o FILE.tif`: one float32 channel (world
// heights) in one uncompressed strip, placed by the GeoTIFF 1.1 tags terrain.heightfield's
// `georeferenced` reads back (pipeline/geotiff_reference.h): ModelPixelScale (cell_x, cell_z,
// 0) and one ModelTiePoint at raster point (0, 0), the top-left pixel's corner (PixelIsArea),
// model point (x0, -z0): x east, northing -z. Relief's world has no datum: the projected
// coordinate system is user-defined (ProjectedCSTypeGeoKey 32767), in metres. Written by hand
// from TIFF 6.0 (little-endian, classic TIFF: files below 4 GiB, which a 16385² field is).
#pragma once

#include <array>
#include <span>
#include <vector>

namespace relief {

// `heights`: width x height values, row 0 = z0 (the file's top row). Empty when out of memory.
std::vector<unsigned char> encode_geotiff(int width, int height, std::span<const float> heights,
                                          const std::array<double, 4>& rect);

}  // namespace relief
