// Height maps as files, for the commands that write them (relief generate, relief export): a
// 16-bit grey PNG or RAW16 holding levels from the lowest height (0) to the highest (65535), or
// a one-channel PFM or EXR holding the heights as floats. terrain.heightfield reads each back
// (pipeline/heightfield_files.h): row 0 at z0, the file's top.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "image/png_text.h"

namespace relief {

// kGeoTiff: float heights placed in the world (tools/geotiff_file.h), for relief export alone.
enum class HeightFormat { kPng16, kPfm, kExr, kRaw16, kGeoTiff };

// By the file name's extension (.png, .pfm, .exr, .r16 or .raw, .tif or .tiff, any letter
// case), or nullopt.
std::optional<HeightFormat> height_format(const std::string& name);

// Whether the format holds 16-bit levels (the heights then map to [low, high]).
inline bool holds_levels(HeightFormat format) {
  return format == HeightFormat::kPng16 || format == HeightFormat::kRaw16;
}

// The level of `height` in [low, high]: round((height - low) 65535 / (high - low)), 0 where
// high <= low (a flat map), clamped to [0, 65535].
std::uint16_t height_level(double height, double low, double high);

// The file's bytes: `heights` width x height values, row 0 = z0 (the file's top row). `text`
// goes into a PNG's text chunks or an EXR's attributes (PFM and RAW16 have none). Empty when
// the encoder ran out of memory. Not for kGeoTiff (encode_geotiff). Throws OutputError
// (tools/atomic_file.h) if OpenImageIO cannot encode the EXR.
std::vector<unsigned char> encode_heights(HeightFormat format, int width, int height,
                                          std::span<const float> heights, double low, double high,
                                          std::span<const ImageText> text);

}  // namespace relief
