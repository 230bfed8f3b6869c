#include "fuzz/fuzz_inputs.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "core/scene/scene_json.h"
#include "pipeline/scene_resources.h"
#include "tools/soup.h"

namespace relief::fuzz {

namespace {

// A scene that passed validation prints as a scene file that loads back to the same scene
// (scene_json.h, scene_to_json); a SceneError here is a finding, not bad input.
void check_round_trip(const Scene& scene) {
  const std::string text = scene_json_text(scene);
  std::string again;
  try {
    again = scene_json_text(resolve_scene_text(text, "round-trip.json", "/fuzz", {}));
  } catch (const SceneError& e) {
    throw Finding(std::string("the printed scene does not load back: ") + e.what() + "\n" + text);
  }
  if (again != text) {
    throw Finding("the printed scene loads back as another scene:\n" + text + "\nversus\n" + again);
  }
}

}  // namespace

bool scene_input(std::string_view bytes) {
  Scene scene;
  try {
    // An absolute base directory: relative texture paths become absolute without the file
    // system being asked (no texture is opened while a scene is resolved).
    scene = resolve_scene_text(bytes, "fuzz.json", "/fuzz", {});
  } catch (const SceneError&) {
    return false;
  }
  check_round_trip(scene);
  return true;
}

bool override_input(std::string_view bytes) {
  if (bytes.empty()) {
    return false;
  }
  static const std::vector<std::string> presets = preset_names();
  const std::string& preset = presets[static_cast<unsigned char>(bytes[0]) % presets.size()];
  std::vector<std::string> overrides;
  const std::string_view rest = bytes.substr(1);
  for (std::size_t start = 0; !rest.empty() && start <= rest.size();) {
    const std::size_t end = std::min(rest.find('\n', start), rest.size());
    overrides.emplace_back(rest.substr(start, end - start));
    start = end + 1;
  }
  Scene scene;
  try {
    scene = resolve_scene(preset, overrides);
  } catch (const SceneError&) {
    return false;
  }
  check_round_trip(scene);
  return true;
}

bool soup_input(std::string_view bytes) {
  TriangleSoup soup;
  try {
    soup = parse_triangle_soup(bytes, "fuzz.txt");
  } catch (const SoupError&) {
    return false;
  }
  if (soup.width < 1 || soup.height < 1 || soup.width > 16384 || soup.height > 16384) {
    throw Finding("framebuffer " + std::to_string(soup.width) + "x" + std::to_string(soup.height));
  }
  const std::size_t vertices = soup.x.size();
  if (soup.y.size() != vertices || soup.z.size() != vertices || soup.w.size() != vertices ||
      soup.indices.size() != vertices || vertices % 3 != 0) {
    throw Finding("vertex streams of different lengths");
  }
  for (std::size_t k = 0; k < vertices; ++k) {
    if (soup.indices[k] != k) {
      throw Finding("index " + std::to_string(k) + " is " + std::to_string(soup.indices[k]));
    }
    for (const float v : {soup.x[k], soup.y[k], soup.z[k], soup.w[k]}) {
      if (!std::isfinite(v)) {
        throw Finding("vertex " + std::to_string(k) + " has a non-finite coordinate");
      }
    }
    if (!soup.clip_coordinates && (soup.z[k] < 0.0f || soup.z[k] > 1.0f || soup.w[k] != 1.0f)) {
      throw Finding("window vertex " + std::to_string(k) + " has z outside [0, 1] or w != 1");
    }
  }
  return true;
}

bool texture_input(std::string_view bytes) {
  const std::vector<unsigned char> png(bytes.begin(), bytes.end());
  RgbImage image;
  try {
    image = decode_texture_png(png, "shading.layers[0].texture = \"fuzz.png\"",
                               "shading.layers[0].texture");
  } catch (const SceneError&) {
    return false;
  }
  if (image.size < 4 || image.size > 4096 || !std::has_single_bit(unsigned(image.size))) {
    throw Finding("accepted a texture of side " + std::to_string(image.size));
  }
  if (image.rgb.size() != 3 * std::size_t(image.size) * std::size_t(image.size)) {
    throw Finding("texture of side " + std::to_string(image.size) + " holds " +
                  std::to_string(image.rgb.size()) + " values");
  }
  for (const float v : image.rgb) {
    if (!(v >= 0.0f && v <= 1.0f)) {
      throw Finding("texture value " + std::to_string(v) + " outside [0, 1]");
    }
  }
  return true;
}

}  // namespace relief::fuzz
