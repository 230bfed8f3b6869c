// Checks of a whole PNG file that every loader runs before stb_image decodes it (the layer
// textures, scene_resources.h; the terrain sketch, sketch_resources.cc), and stb's failure
// reason read reliably.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "pipeline/png_header.h"

namespace relief {

// The PNG header of `bytes`, or SceneError(path, "scene: FIELD is not a PNG image ...").
PngHeader png_header_or_throw(const std::vector<unsigned char>& bytes, const std::string& field,
                              const std::string& path);

// The whole PNG file `file_name` (at most limits::kMaxTextureFileBytes), its header passed to
// `check_header` before the rest is read, so that a file refused by its header is not read
// whole. A file that cannot be read throws SceneError naming `field`.
std::vector<unsigned char> read_png_file(
    const std::string& file_name, const std::string& field, const std::string& path,
    const std::function<void(const std::vector<unsigned char>&)>& check_header);

// Throws SceneError(path, "scene: FIELD ...") unless the file's chunks are well-formed
// (png_layout.h) and its image data inflates to at most the size its header gives.
// Precondition: parse_png_header accepted `png`.
void check_png_image_data(const std::vector<unsigned char>& png, const std::string& field,
                          const std::string& path);

// stb's failure reason is a global that some failures leave as it was: reset it before a
// call, then read it with a fallback for "none given".
void reset_stb_failure_reason();
std::string stb_failure_reason_or(const char* fallback);

}  // namespace relief
