#include "image/image_metadata.h"

#include <string>

#include "core/scene/scene_json.h"

namespace relief {

std::vector<ImageText> software_metadata() {
  return {{std::string(kSoftwareKey), "relief " RELIEF_IMAGE_SOFTWARE_VERSION}};
}

std::vector<ImageText> scene_metadata(const Scene& scene) {
  std::vector<ImageText> text = software_metadata();
  text.push_back({std::string(kSceneKey), scene_json_text(scene)});
  return text;
}

}  // namespace relief
