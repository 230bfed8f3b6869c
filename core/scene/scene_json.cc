#include "core/scene/scene_json.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <utility>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_presets.h"
#include "core/scene/scene_sections.h"

namespace relief {

namespace {

std::string read_scene_file(const std::filesystem::path& file) {
  try {
    InputFile in(file, limits::kMaxSceneFileBytes);
    return in.read_rest();
  } catch (const InputFileError& e) {
    throw SceneError("", "scene file " + brief_text(file.string()) + ": " + e.what());
  }
}

// Which forms of the view direction a layer gives (camera.look_at, camera.yaw_deg/pitch_deg).
struct DirectionForms {
  bool look_at = false;
  bool angles = false;
};

DirectionForms direction_forms(const json& layer) {
  DirectionForms forms;
  if (layer.is_object() && layer.contains("camera") && layer["camera"].is_object()) {
    const json& camera = layer["camera"];
    forms.look_at = camera.contains("look_at");
    forms.angles = camera.contains("yaw_deg") || camera.contains("pitch_deg");
  }
  return forms;
}

// The --set overrides in order, then validate_scene (resolve_scene, resolve_scene_text).
void apply_overrides_and_validate(Scene& scene, const std::vector<std::string>& overrides) {
  // The overrides together are one source, like a file: they may give the view direction in
  // one form only. A look_at among them is resolved against the final camera.position, as it
  // is within a file, whatever the order of the --set options.
  const std::string* look_at_override = nullptr;
  const std::string* angles_override = nullptr;
  json look_at_layer;
  for (const std::string& assignment : overrides) {
    json layer = parse_override(assignment);
    const DirectionForms forms = direction_forms(layer);
    if (forms.look_at) {  // applied once the position is final, below
      look_at_override = &assignment;
      look_at_layer = json{{"camera", {{"look_at", layer["camera"]["look_at"]}}}};
      layer["camera"].erase("look_at");
    }
    angles_override = forms.angles ? &assignment : angles_override;
    if (look_at_override && angles_override) {
      throw SceneError("camera.look_at", "--set " + brief_text(*look_at_override) + " and --set " +
                                             brief_text(*angles_override) +
                                             " both set the view direction; give one or the other");
    }
    apply_scene_layer(scene, layer, "--set " + brief_text(assignment));
  }
  if (look_at_override) {
    apply_scene_layer(scene, look_at_layer, "--set " + brief_text(*look_at_override));
  }
  validate_scene(scene);
}

}  // namespace

void apply_scene_layer(Scene& scene, const json& layer, std::string_view source,
                       const std::filesystem::path& base_dir) {
  const LayerReader in(source);
  scene_schema().apply(LayerContext{in, base_dir}, layer, "", scene);
}

void validate_scene(const Scene& scene) {
  auto fail = [](const std::string& path, const std::string& message) {
    throw SceneError(path, "scene: " + message);
  };
  const TerrainSettings& t = scene.terrain;
  if (t.last_octave < t.first_octave) {
    fail("terrain.last_octave",
         "terrain.last_octave = " + std::to_string(t.last_octave) +
             " is below terrain.first_octave = " + std::to_string(t.first_octave) +
             "; allowed terrain.first_octave <= terrain.last_octave");
  }
  if (t.last_octave - t.first_octave + 1 > limits::kMaxOctaves) {
    fail("terrain.last_octave", "terrain.last_octave - terrain.first_octave + 1 = " +
                                    std::to_string(t.last_octave - t.first_octave + 1) +
                                    " octaves; allowed at most " +
                                    std::to_string(limits::kMaxOctaves));
  }
  // Octave frequencies r^k must stay representable in float lattice coordinates.
  const double max_log2_frequency = t.last_octave * std::log2(t.r);
  if (max_log2_frequency > 40.0) {
    fail("terrain.last_octave", "terrain.last_octave = " + std::to_string(t.last_octave) +
                                    " with terrain.r = " + format_number(t.r) +
                                    " gives octave frequencies up to 2^" +
                                    format_number(std::round(max_log2_frequency)) +
                                    "; allowed terrain.last_octave * log2(terrain.r) <= 40");
  }
  const GridSettings& g = scene.grid;
  const int min_side = 2 * g.margin + 2;
  if (g.width < min_side || g.height < min_side) {
    fail(g.width < min_side ? "grid.width" : "grid.height",
         "grid " + std::to_string(g.width) + "x" + std::to_string(g.height) +
             " is too small for grid.margin = " + std::to_string(g.margin) +
             "; allowed grid.width and grid.height >= 2 * grid.margin + 2 = " +
             std::to_string(min_side));
  }
  const CameraSettings& c = scene.camera;
  if (!(c.near < c.far)) {
    fail("camera.far", "camera.far = " + format_number(c.far) + " is not beyond camera.near = " +
                           format_number(c.near) + "; allowed camera.near < camera.far");
  }
  const double aspect = static_cast<double>(scene.viewport.width) / scene.viewport.height;
  const double horizontal_fov_deg =
      2.0 * std::atan(std::tan(c.fov_y_deg * M_PI / 360.0) * aspect) * 180.0 / M_PI;
  // The horizontal field has the vertical one's limits: narrower than a degree, neighbouring
  // grid rays round to the same float footprint (docs/scene-limits.md, "Field of view").
  if (horizontal_fov_deg > limits::kMaxHorizontalFovDeg ||
      horizontal_fov_deg < limits::kMinFovDeg) {
    fail("camera.fov_y_deg",
         "camera.fov_y_deg = " + format_number(c.fov_y_deg) + " with viewport " +
             std::to_string(scene.viewport.width) + "x" + std::to_string(scene.viewport.height) +
             " gives a horizontal field of view of " + format_number(horizontal_fov_deg) +
             " degrees; allowed " + format_number(limits::kMinFovDeg) + " to " +
             format_number(limits::kMaxHorizontalFovDeg));
  }
  // Float bounds across fields (core/limits.h, docs/scene-limits.md).
  const double log2_r = std::log2(t.r);
  if (t.lod.criterion == LodCriterion::kAmplitude && t.H * log2_r < 0.5 / limits::kMaxLodGain) {
    std::string message = "terrain.H = ";
    message.append(format_number(t.H))
        .append(" with terrain.r = ")
        .append(format_number(t.r))
        .append(
            " makes the amplitude LOD rule change the octave count by 0.5 / (terrain.H * "
            "log2(terrain.r)) = ")
        .append(format_number(0.5 / (t.H * log2_r)))
        .append(" per doubling of sigma^2, more than ")
        .append(format_number(limits::kMaxLodGain))
        .append(
            " (float then no longer keeps nu within 1/256 octave); allowed terrain.H * "
            "log2(terrain.r) >= ")
        .append(format_number(0.5 / limits::kMaxLodGain))
        .append(", here terrain.H >= ")
        .append(format_number(0.5 / limits::kMaxLodGain / log2_r))
        .append(" (or a larger terrain.r, or terrain.lod.criterion = nyquist)");
    fail("terrain.H", message);
  }
  // The farthest footprint stage 2 keeps: kMaxFootprintFactor times the farthest frustum corner
  // at the far plane (projector.cc), for any view direction.
  const double tan_y = std::tan(c.fov_y_deg * M_PI / 360.0);
  const double tan_x = tan_y * aspect;
  const double farthest_footprint =
      limits::kMaxFootprintFactor * c.far * std::sqrt(1.0 + tan_x * tan_x + tan_y * tan_y);
  const double period = t.lattice_size;
  const double coarsest_frequency = std::pow(t.r, t.first_octave);  // <= 2^40 (checked above)
  const double min_horizontal_scale =
      coarsest_frequency * farthest_footprint / (limits::kMaxLatticeCoordinate - period);
  if (t.sketch && t.heightfield) {
    fail("terrain.heightfield",
         "terrain.heightfield and terrain.sketch are both given; allowed one of them (a "
         "heightfield with \"fractal\": true is a sketch of any size and format)");
  }
  if (t.heightfield && t.heightfield->georeferenced &&
      !has_extension(t.heightfield->image, ".tif") &&
      !has_extension(t.heightfield->image, ".tiff")) {
    fail(
        "terrain.heightfield.georeferenced",
        std::string("terrain.heightfield.georeferenced = true with terrain.heightfield.file = \"") +
            brief_text(t.heightfield->image) + "\": allowed only for a GeoTIFF (.tif, .tiff)");
  }
  if (t.heightfield && t.heightfield->fractal && t.heightfield->level_of_detail) {
    fail("terrain.heightfield.level_of_detail",
         "terrain.heightfield.level_of_detail = true with terrain.heightfield.fractal = true: the "
         "levels are read from stage 2's octave count, which the fractal then needs; allowed: "
         "level_of_detail with the fractal off");
  }
  if (t.heightfield && t.heightfield->geomipmap) {
    validate_geomipmap(scene);
  }
  if (t.basis) {
    validate_basis(*t.basis, coarsest_frequency * farthest_footprint);
  } else if (t.horizontal_scale < min_horizontal_scale) {
    std::string message = "terrain.horizontal_scale = ";
    message.append(format_number(t.horizontal_scale))
        .append(" with camera.far = ")
        .append(format_number(c.far))
        .append(" puts the farthest footprint (")
        .append(format_number(farthest_footprint))
        .append(" units away) at lattice coordinate ")
        .append(format_number(
            std::round(period + coarsest_frequency * farthest_footprint / t.horizontal_scale)))
        .append(" of the coarsest octave, beyond ")
        .append(format_number(limits::kMaxLatticeCoordinate))
        .append(
            " (2^24), where float no longer holds every cell and the terrain turns into a "
            "constant; allowed terrain.horizontal_scale >= ")
        .append(format_number(min_horizontal_scale))
        .append(
            " for this camera.far, camera.fov_y_deg, viewport aspect, terrain.lattice_size, "
            "terrain.first_octave and terrain.r (or a smaller camera.far)");
    fail("terrain.horizontal_scale", message);
  }
  const std::vector<MaterialLayer>& layers = scene.shading.layers;
  for (std::size_t a = 0; a < layers.size(); ++a) {
    for (std::size_t b = a + 1; b < layers.size(); ++b) {
      if (layers[a].name == layers[b].name) {
        fail("shading.layers", "shading.layers[" + std::to_string(a) + "] and [" +
                                   std::to_string(b) + "] are both named '" + layers[a].name +
                                   "'; layer names must be unique");
      }
    }
  }
  validate_planet(scene);
  const WarpSettings& w = scene.terrain.warp;
  if (w.r0[0] == 0.0 && w.r0[1] == 0.0) {
    fail("terrain.warp.r0",
         "terrain.warp.r0 = [0, 0] has no direction; allowed any non-zero vector");
  }
}

std::string scene_json_text(const Scene& scene) {
  std::string text = scene_to_json(scene).dump(2, ' ', false, json::error_handler_t::replace);
  text.push_back('\n');
  return text;
}

json scene_to_json(const Scene& scene) {
  return scene_schema().write(scene);
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names{"default"};
  for (const ScenePreset& preset : scene_presets()) {
    names.emplace_back(preset.name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool is_preset(std::string_view name) {
  const auto names = preset_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene resolve_scene(std::string_view scene_arg, const std::vector<std::string>& overrides) {
  const std::string name = scene_arg.empty() ? std::string("default") : std::string(scene_arg);
  const std::filesystem::path file(name);
  std::error_code ec;
  // A regular file comes first, then a preset of that name; anything else that exists under
  // the name (a directory, a FIFO, a device) is refused by read_scene_file with the reason.
  if (std::filesystem::is_regular_file(file, ec) ||
      (!is_preset(name) && std::filesystem::exists(file, ec))) {
    return resolve_scene_text(read_scene_file(file), name, file.parent_path(), overrides);
  }
  Scene scene;
  if (name == "default") {
    // The defaults are the member initialisers of scene.h.
  } else if (is_preset(name)) {
    for (const ScenePreset& preset : scene_presets()) {
      if (preset.name == name) {
        apply_scene_layer(scene, parse_json_strictly(preset.json, "preset " + name),
                          "preset " + name);
      }
    }
  } else {
    throw SceneError("", "scene '" + brief_text(name) +
                             "' is neither a readable file nor a preset; presets: " +
                             join(preset_names(), ", "));
  }
  apply_overrides_and_validate(scene, overrides);
  return scene;
}

Scene resolve_scene_text(std::string_view text, std::string_view file_name,
                         const std::filesystem::path& base_dir,
                         const std::vector<std::string>& overrides) {
  const std::string source = "scene file " + brief_text(file_name);
  Scene scene;
  apply_scene_layer(scene, parse_json_strictly(text, source), source, base_dir);
  apply_overrides_and_validate(scene, overrides);
  return scene;
}

}  // namespace relief
