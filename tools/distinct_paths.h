// The files one command reads and writes must be distinct: an output written over an input
// (relief error keep.png ref.exr --map keep.png) or over another output (--json x.png --diff
// x.png) destroys data with exit 0. Two paths name the same file when they resolve to it after
// links (symbolic and hard) are followed, whether or not it exists yet. Inputs may name the
// same file as each other (comparing an image with itself is a comparison).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace relief {

struct CommandPath {
  std::string option;  // as the user gave it: "--json", "TEST", "-o"
  std::filesystem::path path;
  bool output = true;
};

// Whether a and b name the same file: std::filesystem::equivalent where both exist, else their
// absolute paths with every existing link resolved (std::filesystem::weakly_canonical).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// The first pair of `paths`, one of them an output, that names the same file, as the message
// of a refusal ("--json x.png and --diff x.png name the same file; ..."); nullopt when none
// does. Empty paths (an output not asked for) are skipped.
std::optional<std::string> same_file_conflict(const std::vector<CommandPath>& paths);

// The files a scene reads, as inputs: the scene file (when `scene_arg` names one rather than a
// preset), the layers' textures, the sketch or height field, the basis images and their weight
// images, the skybox's faces ("builtin:" names are none).
std::vector<CommandPath> scene_input_paths(const std::string& scene_arg, const Scene& scene);

}  // namespace relief
