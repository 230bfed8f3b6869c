// terrain.planet from outside, where a hostile pass found holes: a water sphere or terrain at or
// past the planet's centre, the lattice rule with basis images, and `relief path` into a
// directory that already holds frames. Each refusal: exit 2, the field named, nothing written.
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

const std::vector<std::string> kSmallPlanetFrame = {
    "--set", "viewport.width=64", "--set", "viewport.height=48",
    "--set", "grid.width=32",     "--set", "grid.height=32"};

test::CliResult render(const std::string& preset, const std::vector<std::string>& sets,
                       const std::filesystem::path& out) {
  return test::render_preset(preset, sets, out, kSmallPlanetFrame);
}

TEST_CASE("nothingOfAPlanetMayReachItsCentre", "[planet][cli]") {
  test::TempDir dir("planet-centre");
  const std::filesystem::path out = dir.path() / "p.png";
  // The water sphere's radius R + w - base must be positive (it once drew a sphere of |R + w|).
  const test::CliResult water =
      render("planet",
             {"terrain.planet.radius=1000", "terrain.horizontal_scale=1000",
              "terrain.amplitude=100", "terrain.water_level=-5000"},
             out);
  INFO(water.err);
  CHECK(water.code == 2);
  CHECK(water.err.find("terrain.water_level = -5000 puts the water sphere at or past the "
                       "planet's centre") != std::string::npos);
  CHECK(water.err.find("allowed terrain.water_level > -900") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
  // Terrain whose bounds reach below -R would be bent through the centre.
  const test::CliResult deep =
      render("planet",
             {"terrain.planet.radius=1000", "terrain.horizontal_scale=1000",
              "terrain.amplitude=3000", "terrain.water_level=null"},
             out);
  INFO(deep.err);
  CHECK(deep.code == 2);
  CHECK(deep.err.find("terrain.planet.radius = 1000 is not above the depth the terrain can "
                      "reach below the datum, ") != std::string::npos);
  // The depth is printed once, and the advice stays within the field's range.
  const std::size_t depth_at = deep.err.find("datum, ") + 7;
  const std::string depth = deep.err.substr(depth_at, deep.err.find(' ', depth_at) - depth_at);
  CHECK(std::stod(depth) > 1000);
  CHECK(deep.err.find(depth, depth_at + 1) == std::string::npos);
  CHECK(deep.err.find("allowed: a radius above that depth (terrain.planet.radius is at most "
                      "1e+08)") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
  // relief scene validates as render does: the same refusal, nothing printed.
  const test::CliResult scene =
      test::run({"scene", "planet", "--set", "terrain.planet.radius=1000", "--set",
                 "terrain.horizontal_scale=1000", "--set", "terrain.amplitude=3000", "--set",
                 "terrain.water_level=null"});
  CHECK(scene.code == 2);
  CHECK(scene.out.empty());
  CHECK(scene.err.find("terrain.planet.radius = 1000 is not above the depth") != std::string::npos);
  // Terrain deeper than the largest radius: no radius is suggested.
  const test::CliResult deepest =
      test::run({"scene", "planet", "--set", "terrain.amplitude=1e7", "--set", "terrain.H=0.1"});
  CHECK(deepest.code == 2);
  CHECK(deepest.err.find("no radius up to terrain.planet.radius's maximum 1e+08 holds it") !=
        std::string::npos);
  // The same small planet with shallow terrain renders.
  const test::CliResult shallow =
      render("planet",
             {"terrain.planet.radius=1000", "terrain.horizontal_scale=1000", "terrain.amplitude=20",
              "terrain.water_level=null", "camera.position=[0,30000,0]", "camera.pitch_deg=-89"},
             out);
  INFO(shallow.err);
  CHECK(shallow.code == 0);
}

TEST_CASE("thePlanetsLatticeRuleUsesTheBasisImagesCell", "[planet][cli]") {
  // With basis images horizontal_scale is unused: the rule names tile_size, not it.
  const test::CliResult r = test::run({"scene", "craters", "--set", "terrain.planet.radius=1e8",
                                       "--set", "terrain.horizontal_scale=10"});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.find("for this terrain.basis.tile_size, terrain.r") != std::string::npos);
  CHECK(test::run({"scene", "craters", "--set", "terrain.planet.radius=1e5"}).code == 0);
}

TEST_CASE("aPathRefusesADirectoryThatAlreadyHoldsFrames", "[planet][cli]") {
  test::TempDir dir("path-stale");
  const std::filesystem::path out = dir.path() / "frames";
  std::filesystem::create_directories(out / "frame_0001.png");  // a directory in the way
  std::vector<std::string> args = {"path", "planet",          "--out", out.string(),    "--frames",
                                   "2",    "--from-altitude", "1e6",   "--to-altitude", "1e4"};
  args.insert(args.end(), kSmallPlanetFrame.begin(), kSmallPlanetFrame.end());
  const test::CliResult r = test::run(args);
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK(r.err.find("already holds frame_0001.png") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out / "frame_0000.png"));
  std::filesystem::remove_all(out / "frame_0001.png");
  CHECK(test::run(args).code == 0);
  CHECK(std::filesystem::is_regular_file(out / "frame_0001.png"));
  CHECK(test::run(args).code == 2);  // its own frames, a second time
}

// The stress suite on the presets that are not the default: its cases once assumed the
// default's camera.far, last_octave and flat datum, and once ran the island without its sketch
// (an internal error).
TEST_CASE("theStressSuiteRunsOnTheIslandAndThePlanet", "[planet][stress]") {
  for (const char* preset : {"island", "planet"}) {
    const test::CliResult r =
        test::run({"stress", preset, "--axis", "altitude", "--axis", "octaves", "--axis", "r",
                   "--backend", "simd", "--viewport", "32", "24", "--grid", "16"});
    INFO(preset << ": " << r.out << r.err);
    CHECK(r.code == 0);
  }
}

}  // namespace
}  // namespace relief
