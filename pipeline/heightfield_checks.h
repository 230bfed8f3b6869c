// The refusals terrain.heightfield's loader shares between its formats (heightfield_files.cc):
// each names the field, the value and what is allowed, as SceneError.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "core/scene/scene.h"

namespace relief::heightfield_checks {

inline constexpr const char* kPath = "terrain.heightfield.file";

// terrain.heightfield.file = "NAME", for messages.
std::string field_text(const HeightFieldSettings& s);

// Throws SceneError(path, "scene: " + field_text(s) + " " + why).
[[noreturn]] void refuse(const HeightFieldSettings& s, const std::string& why,
                         const char* path = kPath);

std::string size_text(std::uint64_t width, std::uint64_t height);  // "WxH"

// Refuses a side outside 2 to limits::kMaxHeightFieldSize (`unit`: "samples", "pixels").
void check_side(const HeightFieldSettings& s, std::uint64_t width, std::uint64_t height,
                const std::string& unit);

// The size of a regular file of at most max_bytes (core/input_file.h), or the refusal why not.
std::uintmax_t file_size(const HeightFieldSettings& s, std::uintmax_t max_bytes);

// Refuses a sample that is not finite or whose world height lies beyond +-kMaxBaseHeight,
// naming its column and row (from the top).
void check_samples(const HeightFieldSettings& s, std::span<const float> values, int width);

}  // namespace relief::heightfield_checks
