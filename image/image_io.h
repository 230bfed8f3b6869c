// Encoders for the images Relief writes. 8-bit images are sRGB-encoded PNG (png_encoder.h),
// float buffers are PFM. Both take rows bottom-to-top, as every buffer in Relief is stored
// (GL's window convention); PNG rows are flipped to top-to-bottom only here, when written.
// (EXR is written by the command line alone, through OpenImageIO: tools/float_image_file.h;
// the library links no image library beyond stb, for reading, and libdeflate.)
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "image/png_text.h"

namespace relief {

// `rgb`: width * height * 3 bytes, row 0 = bottom row. `text`: text chunks placed after IHDR
// (png_text.h; image_metadata.h says what Relief's images carry).
std::vector<unsigned char> encode_png_rgb(int width, int height, std::span<const std::uint8_t> rgb,
                                          std::span<const ImageText> text = {});

// 16-bit grey, `levels` row 0 = the top row; `text` as above.
std::vector<unsigned char> encode_png_grey16_with_text(int width, int height,
                                                       std::span<const std::uint16_t> levels,
                                                       std::span<const ImageText> text = {});

// PFM (Portable Float Map): ASCII header "Pf" (1 channel) or "PF" (3 channels), then
// "width height", then "-1" (negative: little-endian), each on its own line, then
// width * height * channels IEEE-754 binary32 values, rows bottom-to-top, channels interleaved.
// `values` has row 0 = bottom row, `stride` floats between row starts.
std::vector<unsigned char> encode_pfm(int width, int height, int channels,
                                      std::span<const float> values, std::size_t stride);

// The header encode_pfm writes before the values.
std::string pfm_header(int width, int height, int channels);

}  // namespace relief
