#include "pipeline/image_metadata.h"

#include <string>

#include "core/scene/scene_json.h"
#include "pipeline/build_info.h"

namespace relief {

std::vector<ImageText> software_metadata() {
  return {{std::string(kSoftwareKey), "relief " + std::string(relief_version())}};
}

std::vector<ImageText> scene_metadata(const Scene& scene) {
  std::vector<ImageText> text = software_metadata();
  text.push_back({std::string(kSceneKey), scene_json_text(scene)});
  return text;
}

}  // namespace relief
