// The float outputs of relief render and relief stages (linear radiance, depth, normals,
// heights, octave counts, the stage buffers) in the format their file name asks for:
//
// - .pfm: Portable Float Map (image/image_io.h), rows bottom to top as Relief stores them;
//   no metadata.
// - .exr: OpenEXR through OpenImageIO, 32-bit float channels (not half: half's 11-bit
//   significand and 65504 maximum would round away the very values these files exist to give
//   exactly, world heights up to 1e7 and reverse-Z depths near 0; the file holds the PFM's
//   bits), lossless ZIP compression, rows top to bottom as EXR viewers show them (the same
//   picture as the PNG), channels R, G, B (three) or Y (one), and the image metadata
//   (image/image_metadata.h) as string attributes.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "image/png_text.h"

namespace relief {

enum class FloatFormat { kPfm, kExr };

// The format a file name ends in (.pfm or .exr, any letter case), or nullopt.
std::optional<FloatFormat> float_format_of(std::string_view name);

std::string_view float_extension(FloatFormat format);  // ".pfm", ".exr"

// A file's bytes. `values`: width * height * channels (1 or 3) floats, row 0 = the bottom row,
// `stride` floats between row starts. Throws OutputError (tools/atomic_file.h) if OpenImageIO
// cannot encode the EXR.
std::vector<unsigned char> encode_float_image(FloatFormat format, int width, int height,
                                              int channels, std::span<const float> values,
                                              std::size_t stride,
                                              std::span<const ImageText> metadata);

}  // namespace relief
