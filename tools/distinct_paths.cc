#include "tools/distinct_paths.h"

#include <system_error>

#include "core/scene/json_input.h"

namespace relief {

namespace fs = std::filesystem;

namespace {

// The path with every existing component's links resolved; the path made absolute when even
// that fails (a component that is not a directory, no permission): then only spelling decides.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) {
    absolute = path;
  }
  const fs::path canonical = fs::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : canonical;
}

}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code error;
  const bool equivalent = fs::equivalent(a, b, error);
  if (!error) {
    return equivalent;  // both exist: the same inode (hard links and symbolic links included)
  }
  return resolved(a) == resolved(b);
}

std::optional<std::string> same_file_conflict(const std::vector<CommandPath>& paths) {
  for (std::size_t i = 0; i < paths.size(); ++i) {
    for (std::size_t j = i + 1; j < paths.size(); ++j) {
      const CommandPath &a = paths[i], &b = paths[j];
      if ((!a.output && !b.output) || a.path.empty() || b.path.empty() ||
          !same_file(a.path, b.path)) {
        continue;
      }
      const auto kind = [](const CommandPath& p) { return p.output ? "output" : "input"; };
      return a.option + " " + brief_text(a.path.string()) + " and " + b.option + " " +
             brief_text(b.path.string()) + " name the same file (" + kind(a) + " and " + kind(b) +
             "); one would overwrite the other. Give distinct files";
    }
  }
  return std::nullopt;
}

std::vector<CommandPath> scene_input_paths(const std::string& scene_arg, const Scene& scene) {
  std::vector<CommandPath> inputs;
  std::error_code error;
  if (!scene_arg.empty() && fs::is_regular_file(scene_arg, error)) {
    inputs.push_back({"SCENE", scene_arg, false});
  }
  const auto add = [&](const std::string& field, const std::string& name) {
    if (!name.empty() && name.rfind("builtin:", 0) != 0) {
      inputs.push_back({field, name, false});
    }
  };
  for (std::size_t k = 0; k < scene.shading.layers.size(); ++k) {
    add("shading.layers[" + std::to_string(k) + "].texture", scene.shading.layers[k].texture);
  }
  if (scene.terrain.sketch) {
    add("terrain.sketch.image", scene.terrain.sketch->image);
  }
  if (scene.terrain.heightfield) {
    add("terrain.heightfield.file", scene.terrain.heightfield->image);
  }
  if (scene.terrain.basis) {
    for (std::size_t k = 0; k < scene.terrain.basis->images.size(); ++k) {
      const std::string field = "terrain.basis.images[" + std::to_string(k) + "]";
      add(field + ".image", scene.terrain.basis->images[k].image);
      add(field + ".weight_image", scene.terrain.basis->images[k].weight_image);
    }
  }
  if (scene.sky.skybox) {
    for (std::size_t k = 0; k < scene.sky.skybox->faces.size(); ++k) {
      add("sky.skybox.faces[" + std::to_string(k) + "]", scene.sky.skybox->faces[k]);
    }
  }
  return inputs;
}

}  // namespace relief
