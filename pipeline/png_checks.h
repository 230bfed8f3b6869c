// Checks of a whole PNG file that every loader runs before stb_image decodes it (the layer
// textures, scene_resources.h; the terrain sketch, sketch_resources.cc), and stb's failure
// reason read reliably.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/limits.h"
#include "image/png_header.h"

namespace relief {

// The PNG header of `bytes`, or SceneError(path, "scene: FIELD is not a PNG image ...").
PngHeader png_header_or_throw(const std::vector<unsigned char>& bytes, const std::string& field,
                              const std::string& path);

// The whole PNG file `file_name` (at most `max_bytes`), its header passed to `check_header`
// before the rest is read, so that a file refused by its header is not read whole. A file that
// cannot be read throws SceneError naming `field`.
std::vector<unsigned char> read_png_file(
    const std::string& file_name, const std::string& field, const std::string& path,
    const std::function<void(const std::vector<unsigned char>&)>& check_header,
    std::uintmax_t max_bytes = limits::kMaxTextureFileBytes);

// Throws SceneError(path, "scene: FIELD ...") unless the file's chunks are well-formed
// (png_layout.h) and its image data inflates to at most the size its header gives.
// Precondition: parse_png_header accepted `png`.
void check_png_image_data(const std::vector<unsigned char>& png, const std::string& field,
                          const std::string& path);

// A grey PNG's levels as 16-bit values (8-bit levels scaled by 257, as stb does), after
// check_png_image_data (and at most `max_bytes`, below 2^31: stb takes an int size); throws
// SceneError(path, "scene: FIELD could not be decoded: ...") when stb fails or its size disagrees
// with the header. Precondition: parse_png_header accepted `png` and it has one channel.
struct Grey16Image {
  int width = 0, height = 0;
  std::vector<std::uint16_t> levels;  // row-major
};
Grey16Image decode_grey16_png(const std::vector<unsigned char>& png, const std::string& field,
                              const std::string& path,
                              std::uintmax_t max_bytes = limits::kMaxTextureFileBytes);

// The header of a PNG named as a scene names one ("builtin:NAME", a PNG shipped inside the
// binary: builtin_sketches.h, or a file) and the file's size, for memory estimates before
// anything is read whole; header nullopt when the file cannot be opened or is not a PNG
// (loading the scene reports why).
struct PngPeek {
  std::optional<PngHeader> header;
  std::uintmax_t file_bytes = 0;
};
PngPeek peek_png(const std::string& name, std::uintmax_t max_bytes = limits::kMaxTextureFileBytes);

// stb's failure reason is a global that some failures leave as it was: reset it before a
// call, then read it with a fallback for "none given".
void reset_stb_failure_reason();
std::string stb_failure_reason_or(const char* fallback);

}  // namespace relief
