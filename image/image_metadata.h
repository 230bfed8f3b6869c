// The text every image Relief writes carries, so that an image says what made it: "Software"
// (the PNG keyword registered for it, ISO/IEC 15948 §11.3.4.2) = "relief VERSION", and for
// the images of a scene "relief:scene" = the effective scene as `relief scene` prints it
// (defaults, preset or file, then the --set overrides), which `relief render` loads back
// (docs/using-relief.md, "Image metadata"). PNG files carry them as text chunks (png_text.h),
// EXR files as string attributes of the same names (tools/float_image_file.h).
#pragma once

#include <string_view>
#include <vector>

#include "core/scene/scene.h"
#include "image/png_text.h"

namespace relief {

inline constexpr std::string_view kSoftwareKey = "Software";
inline constexpr std::string_view kSceneKey = "relief:scene";

// "Software" alone: an image that no scene made (relief raster's coverage, compare's diff).
std::vector<ImageText> software_metadata();

// "Software" and "relief:scene".
std::vector<ImageText> scene_metadata(const Scene& scene);

}  // namespace relief
