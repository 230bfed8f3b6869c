// Flicker as a measured error (eval/flicker.h, relief flicker): the moves are the camera's
// horizontal forward direction and its yaw; a camera that does not move changes nothing in
// real time or in the truth (both are deterministic); a moving one changes both; the change is
// measured in sRGB codes of the display values; and the command's refusals.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "core/srgb.h"
#include "eval/flicker.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

TEST_CASE("flickerMovesAreTheCamerasForwardDirectionAndYaw", "[ground-truth]") {
  const Scene scene = resolve_scene("default", {"camera.yaw_deg=90", "camera.pitch_deg=-30"});
  const Scene forward = moved_scene(scene, CameraMove::kForward, 5.0, 3);
  // Yaw 90 looks along +x (core/scene/scene.h): 15 units along x, none along y or z.
  CHECK(forward.camera.position[0] == Approx(scene.camera.position[0] + 15.0));
  CHECK(forward.camera.position[1] == scene.camera.position[1]);
  CHECK(forward.camera.position[2] == Approx(scene.camera.position[2]).margin(1e-9));
  CHECK(forward.camera.pitch_deg == scene.camera.pitch_deg);
  const Scene turned = moved_scene(scene, CameraMove::kTurn, 2.5, 4);
  CHECK(turned.camera.yaw_deg == 100.0);
  CHECK(turned.camera.position == scene.camera.position);
  CHECK(moved_scene(scene, CameraMove::kForward, 5.0, 0).camera.position == scene.camera.position);
}

TEST_CASE("bandedChangeIsTheMeanDisplayChangeInSrgbCodes", "[ground-truth]") {
  GroundTruthImage banded;
  banded.width = 4;
  banded.height = 1;
  banded.distance = {0.0f, 10.0f, 20.0f, 30.0f};  // sky, near, middle, far
  const std::vector<float> before(12, 0.25f);
  std::vector<float> after = before;
  CHECK(banded_change(before, after, banded) == std::vector<double>(kDistanceBands + 1, 0.0));
  for (int c = 0; c < 3; ++c) {
    after[3 * 3 + std::size_t(c)] = 0.5f;  // the far pixel brightens
  }
  const std::vector<double> change = banded_change(before, after, banded);
  const double codes = 255.0 * (srgb_encode(0.5) - srgb_encode(0.25));
  CHECK(change[0] == 0.0);
  CHECK(change[3] == Approx(codes));
  CHECK(change[kDistanceBands] == Approx(codes / 4));
}

TEST_CASE("flickerOfAStillCameraIsZeroAndOfAMovingOnePositive", "[ground-truth]") {
  test::TempDir dir("flicker");
  const auto flicker = [&](const std::string& step, const std::string& move,
                           const std::string& pitch = "-8") {
    const std::string json = (dir.path() / ("f" + step + move + pitch + ".json")).string();
    const test::CliResult r = test::run({"flicker",       "badlands",
                                         "--set",         "viewport.width=64",
                                         "--set",         "viewport.height=48",
                                         "--set",         "grid.width=32",
                                         "--set",         "grid.height=32",
                                         "--supersample", "1",
                                         "--grid-scale",  "1",
                                         "--frames",      "3",
                                         "--step",        step,
                                         "--move",        move,
                                         "--set",         "camera.pitch_deg=" + pitch,
                                         "--json",        json});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const std::vector<unsigned char> bytes = test::read_bytes(json);
    return nlohmann::json::parse(bytes.begin(), bytes.end());
  };
  const nlohmann::json still = flicker("0", "forward");
  CHECK(still["realtime_change"]["all"] == 0.0);
  CHECK(still["truth_change"]["all"] == 0.0);
  CHECK(still["per_frame"].size() == 3);
  CHECK(still["mean_flip"]["all"].get<double>() > 0.0);  // real time is not its truth
  const nlohmann::json moving = flicker("20", "forward");
  CHECK(moving["realtime_change"]["all"].get<double>() > 0.0);
  CHECK(moving["truth_change"]["all"].get<double>() > 0.0);
  const nlohmann::json turning = flicker("2", "turn");
  CHECK(turning["realtime_change"]["all"].get<double>() > 0.0);
  // Looking up at the sky alone: the terrain's bands have no pixels and no figures (null, not
  // a perfect 0).
  const nlohmann::json sky = flicker("2", "turn", "60");
  CHECK(sky["mean_flip"]["far third"].is_null());
  CHECK(sky["realtime_change"]["near third"].is_null());
  CHECK(sky["realtime_change"]["sky"].is_number());
}

TEST_CASE("flickerRefusesBadOptions", "[ground-truth]") {
  test::TempDir dir("flicker-refused");
  const std::string json = (dir.path() / "f.json").string();
  const auto refused = [&](std::vector<std::string> extra, const std::string& message) {
    std::vector<std::string> a = {"flicker", "--json", json};
    a.insert(a.end(), extra.begin(), extra.end());
    test::require_refused(test::run(a), message, json);
  };
  refused({"--move", "jump"}, "--move jump is not a move");
  refused({"--step", "nan"}, "--step");
  refused({"--step", "20000"}, "--step 20000 is out of range");
  refused({"--move", "turn", "--step", "90"}, "--step 90 is out of range");
  refused({"--frames", "1"}, "--frames");
  refused({"--frames", "65"}, "--frames");
  refused({"--supersample", "17"}, "--supersample 17 is out of range");
  refused({"--step", ""}, "--step");
  test::require_refused(test::run({"flicker", "--json", ""}), "--json is empty", json);
  test::require_refused(
      test::run({"flicker", "--json", (dir.path() / "missing" / "f.json").string()}),
      "does not exist", json);
}

}  // namespace
}  // namespace relief
