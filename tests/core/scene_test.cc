#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"

namespace relief {
namespace {

using nlohmann::json;

// Applies one layer to the defaults and validates; returns the error message or "".
std::string error_of(const std::string& layer_text) {
  try {
    Scene scene;
    apply_scene_layer(scene, json::parse(layer_text), "scene file s.json");
    validate_scene(scene);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

std::string error_of_override(const std::string& assignment) {
  try {
    resolve_scene("default", {assignment});
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

using Catch::Matchers::Contains;

TEST_CASE("sceneRejectsUnknownKeysNamingTheAllowedOnes", "[scene]") {
  const std::string e = error_of(R"({"terrain": {"hurst": 0.8}})");
  CHECK_THAT(e, Contains("scene file s.json"));
  CHECK_THAT(e, Contains("unknown key 'terrain.hurst'"));
  CHECK_THAT(e, Contains("H"));
  CHECK_THAT(error_of(R"({"camra": {}})"), Contains("unknown key 'camra'"));
}

TEST_CASE("sceneRejectsWrongTypes", "[scene]") {
  CHECK_THAT(error_of(R"({"terrain": {"r": "two"}})"),
             Contains("terrain.r = \"two\" is not a number"));
  CHECK_THAT(error_of(R"({"grid": {"width": 512.5}})"),
             Contains("grid.width = 512.5 is not an integer"));
  CHECK_THAT(error_of(R"({"terrain": {"warp": {"enabled": 1}}})"),
             Contains("terrain.warp.enabled = 1 is not a boolean"));
  CHECK_THAT(error_of(R"({"camera": {"position": [1, 2]}})"),
             Contains("camera.position = [1,2] must be an array of 3 numbers"));
  CHECK_THAT(error_of(R"({"terrain": {"interpolant": "spline"}})"),
             Contains("allowed: linear, cubic, quintic"));
  CHECK_THAT(error_of(R"({"terrain": {"seed": -1}})"),
             Contains("terrain.seed = -1 is not an unsigned"));
  CHECK_THAT(error_of(R"([1, 2])"), Contains("must be a JSON object"));
}

TEST_CASE("sceneRejectsValuesOutOfRangeQuotingTheRange", "[scene]") {
  CHECK_THAT(error_of(R"({"terrain": {"r": 1}})"),
             Contains("terrain.r = 1 is out of range; allowed 1.001 <= terrain.r <= 16"));
  CHECK_THAT(error_of(R"({"terrain": {"r": 0.5}})"), Contains("1.001 <= terrain.r"));
  CHECK_THAT(error_of(R"({"grid": {"width": 1}})"),
             Contains("grid.width = 1 is out of range; allowed 2 <= grid.width <= 8192"));
  CHECK_THAT(error_of(R"({"viewport": {"height": 16385}})"),
             Contains("allowed 1 <= viewport.height <= 16384"));
  CHECK_THAT(error_of(R"({"terrain": {"H": 0}})"), Contains("allowed 0.00025 <= terrain.H <= 1"));
  CHECK_THAT(error_of(R"({"camera": {"pitch_deg": 91}})"),
             Contains("-90 <= camera.pitch_deg <= 90"));
  CHECK_THAT(error_of(R"({"terrain": {"lattice_size": 300}})"),
             Contains("terrain.lattice_size = 300 is not a power of two"));
  CHECK_THAT(error_of(R"({"camera": {"near": 0}})"), Contains("1e-17 <= camera.near"));
}

TEST_CASE("sceneRejectsNonFiniteNumbers", "[scene]") {
  CHECK_THAT(error_of_override("terrain.H=nan"),
             Contains("terrain.H = nan is not a finite number"));
  CHECK_THAT(error_of_override("terrain.r=-Infinity"), Contains("is not a finite number"));
  CHECK_THAT(error_of_override("camera.far=1e400"),
             Contains("camera.far = 1e400 is not a finite number"));
}

TEST_CASE("sceneChecksRulesBetweenFields", "[scene]") {
  CHECK_THAT(error_of(R"({"terrain": {"first_octave": 5, "last_octave": 3}})"),
             Contains("terrain.last_octave = 3 is below terrain.first_octave = 5"));
  CHECK_THAT(error_of(R"({"terrain": {"first_octave": 0, "last_octave": 30}})"),
             Contains("allowed at most 24"));
  CHECK_THAT(error_of(R"({"grid": {"width": 5, "margin": 2}})"),
             Contains(">= 2 * grid.margin + 2 = 6"));
  CHECK_THAT(error_of(R"({"camera": {"near": 10, "far": 5}})"),
             Contains("allowed camera.near < camera.far"));
  CHECK_THAT(
      error_of(R"({"camera": {"fov_y_deg": 120}, "viewport": {"width": 4000, "height": 100}})"),
      Contains("horizontal field of view"));
  CHECK_THAT(error_of(R"({"terrain": {"warp": {"r0": [0, 0]}}})"), Contains("terrain.warp.r0"));
  CHECK_THAT(error_of(R"({"terrain": {"r": 16, "last_octave": 20}})"),
             Contains("octave frequencies up to 2^80"));
  CHECK_THAT(error_of(R"({"camera": {"look_at": [0, 0, -10], "yaw_deg": 5}})"),
             Contains("both set the view direction"));
}

TEST_CASE("sceneAcceptsEveryPresetAndRoundTripsThroughJson", "[scene]") {
  for (const std::string& name : preset_names()) {
    INFO(name);
    const Scene scene = resolve_scene(name, {});
    Scene reloaded;
    apply_scene_layer(reloaded, scene_to_json(scene), "round trip");
    validate_scene(reloaded);
    CHECK(scene_to_json(reloaded) == scene_to_json(scene));
  }
  CHECK(resolve_scene("lava", {}).terrain.warp.enabled);
  CHECK_FALSE(resolve_scene("plain", {}).terrain.warp.enabled);
}

TEST_CASE("everyPresetIsADistinctScene", "[scene]") {
  // alpine is the default spelled out; every other preset must differ from it and from each
  // other (plain once equalled the default exactly).
  const std::vector<std::string> names = preset_names();
  for (std::size_t a = 0; a < names.size(); ++a) {
    for (std::size_t b = a + 1; b < names.size(); ++b) {
      const bool defaults = (names[a] == "alpine" || names[a] == "default") &&
                            (names[b] == "alpine" || names[b] == "default");
      INFO(names[a] << " and " << names[b]);
      CHECK((scene_to_json(resolve_scene(names[a], {})) ==
             scene_to_json(resolve_scene(names[b], {}))) == defaults);
    }
  }
  const Scene plain = resolve_scene("plain", {});
  CHECK_FALSE(plain.terrain.warp.enabled);
  CHECK_FALSE(plain.terrain.water_level.has_value());
  CHECK(plain.shading.layers.size() == 1);
}

TEST_CASE("overridesApplyInOrderAndParseJsonValues", "[scene]") {
  const Scene scene = resolve_scene(
      "lava", {"terrain.H=0.85", "terrain.interpolant=cubic", "camera.position=[1, 2, 3]",
               "terrain.water_level=null", "terrain.H=0.9"});
  CHECK(scene.terrain.H == 0.9);
  CHECK(scene.terrain.interpolant == Interpolant::kCubic);
  CHECK(scene.camera.position == Vec3d{1, 2, 3});
  CHECK_FALSE(scene.terrain.water_level.has_value());
  CHECK(scene.terrain.warp.enabled);
  CHECK_THAT(error_of_override("terrain"), Contains("expected KEY=VALUE"));
  CHECK_THAT(error_of_override("terrain..H=1"), Contains("empty segment"));
  CHECK_THAT(error_of_override("terrain.H=abc"), Contains("terrain.H = \"abc\" is not a number"));
}

TEST_CASE("lookAtSetsYawAndPitch", "[scene]") {
  Scene scene;
  apply_scene_layer(
      scene, json::parse(R"({"camera": {"position": [0, 10, 0], "look_at": [10, 0, 0]}})"), "test");
  CHECK(scene.camera.yaw_deg == Approx(90.0));
  CHECK(scene.camera.pitch_deg == Approx(-45.0));
  CHECK_THAT(error_of(R"({"camera": {"position": [1, 1, 1], "look_at": [1, 1, 1]}})"),
             Contains("must differ from camera.position"));
}

TEST_CASE("unknownSceneNamesListThePresets", "[scene]") {
  try {
    resolve_scene("no-such-scene", {});
    FAIL("expected a SceneError");
  } catch (const SceneError& e) {
    CHECK_THAT(std::string(e.what()), Contains("neither a readable file nor a preset"));
    CHECK_THAT(std::string(e.what()), Contains("lava"));
  }
}

TEST_CASE("alpinePresetIsTheBuiltInDefault", "[scene]") {
  // scenes/alpine.json spells out every field: it must stay equal to the built-in defaults.
  CHECK(scene_to_json(resolve_scene("alpine", {})) == scene_to_json(Scene{}));
  CHECK(scene_to_json(resolve_scene("default", {})) == scene_to_json(Scene{}));
}

TEST_CASE("sceneValidatesMaterialLayers", "[scene]") {
  CHECK_THAT(error_of(R"({"shading": {"layers": [{"texture": "builtin:marble"}]}})"),
             Contains("names no built-in texture"));
  CHECK_THAT(error_of(R"({"shading": {"layers": []}})"), Contains("allowed 1 to 8"));
  CHECK_THAT(error_of(R"({"shading": {"layers": [{"name": "a"}]}})"),
             Contains("must be an object with at least a \"texture\""));
  CHECK_THAT(error_of(R"({"shading": {"layers": {"9": {"tile_size": 2}}}})"),
             Contains("no layer '9'"));
  CHECK_THAT(error_of(R"({"shading": {"layers": {"1": {"slope_deg": [40, 20]}}}})"),
             Contains("is empty; allowed [low, high] with low < high"));
  CHECK_THAT(error_of(R"({"shading": {"layers": {"1": {"tile_size": 0}}}})"),
             Contains("1e-04 <= shading.layers[1].tile_size"));
  CHECK_THAT(error_of(R"({"shading": {"layers": [{"name": "x", "texture": "builtin:sand"},
                                                 {"name": "x", "texture": "builtin:rock"}]}})"),
             Contains("are both named 'x'"));
  CHECK_THAT(error_of(R"({"water": {"deep_color": [0, 2, 0]}})"),
             Contains("allowed 0 <= water.deep_color[1] <= 1"));
  CHECK_THAT(error_of(R"({"lighting": {"exposure": 0}})"), Contains("1e-11 <= lighting.exposure"));
  // A patch by index, as --set shading.layers.2.slope_deg=[0,20] writes it.
  const Scene patched = resolve_scene("alpine", {"shading.layers.2.slope_deg=[0,20]"});
  CHECK(patched.shading.layers[2].slope_deg == Vec2d{0, 20});
  CHECK(patched.shading.layers[2].texture == "builtin:grass");
}

}  // namespace
}  // namespace relief
