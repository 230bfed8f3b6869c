#include "pipeline/heightfield_checks.h"

#include <cmath>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"

namespace relief::heightfield_checks {

std::string field_text(const HeightFieldSettings& s) {
  return std::string(kPath) + " = \"" + brief_text(s.image) + "\"";
}

[[noreturn]] void refuse(const HeightFieldSettings& s, const std::string& why, const char* path) {
  throw SceneError(path, "scene: " + field_text(s) + " " + why);
}

std::string size_text(std::uint64_t width, std::uint64_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

void check_side(const HeightFieldSettings& s, std::uint64_t width, std::uint64_t height,
                const std::string& unit) {
  const std::uint64_t lo = limits::kMinSketchSize, hi = limits::kMaxHeightFieldSize;
  if (width < lo || width > hi || height < lo || height > hi) {
    refuse(s, "is " + size_text(width, height) + " " + unit + "; allowed " + std::to_string(lo) +
                  " to " + std::to_string(hi) + " on each side");
  }
}

std::uintmax_t file_size(const HeightFieldSettings& s, std::uintmax_t max_bytes) {
  try {
    return InputFile(s.image, max_bytes).size();
  } catch (const InputFileError& e) {
    refuse(s, e.what());
  }
}

// Every sample finite and its world height within the scene's range.
void check_samples(const HeightFieldSettings& s, std::span<const float> values, int width) {
  const double lo = s.height[0], hi = s.height[1];
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double world = lo + (hi - lo) * double(values[k]);
    if (!std::isfinite(values[k]) || !(std::abs(world) <= limits::kMaxBaseHeight)) {
      refuse(s, "has sample " + format_number(values[k]) + " at column " +
                    std::to_string(k % std::size_t(width)) + ", row " +
                    std::to_string(k / std::size_t(width)) + " (from the top), world height " +
                    format_number(world) +
                    " with terrain.heightfield.height; allowed: finite "
                    "samples whose world heights lie within ±" +
                    format_number(limits::kMaxBaseHeight));
    }
  }
}

}  // namespace relief::heightfield_checks
