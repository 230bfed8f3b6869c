// Checks of a whole PNG file that every loader runs before stb_image decodes it (the layer
// textures, scene_resources.h; the terrain sketch, sketch_resources.cc), and stb's failure
// reason read reliably.
#pragma once

#include <string>
#include <vector>

namespace relief {

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
