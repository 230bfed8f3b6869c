// The GL side as a user meets it on Mesa's llvmpipe: `relief crosscheck PRESET --out DIR`
// exactly as typed (the default size and thresholds; it failed out of the box on alpine and
// lava where llvmpipe took the other mip level of a bilinear texture), --stats-json that no
// longer reports the software rasteriser's counters as 0, a stress run that asks for a GL it
// cannot have, and an address-space limit that crashed llvmpipe's shader compiler.
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/gl_backend.h"
#include "tests/gl/gl_presets.h"
#include "tests/support/cli_support.h"
#include "tests/support/limited_run.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using Catch::Contains;
using test::CliResult;
using test::run;

}  // namespace

TEST_CASE("theUsersCrosscheckOfEveryPresetPassesOnLlvmpipe", "[gl]") {
  test::TempDir dir("crosscheck-user");
  for (const std::string& preset : test::gl_preset_names()) {
    const std::filesystem::path out = dir.path() / preset;
    const CliResult r = run({"crosscheck", preset, "--out", out.string()});
    INFO(preset << ": " << r.err << r.out);
    CHECK(r.code == 0);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "crosscheck.json"));
    CHECK(j["verdict"] == "PASS");
    // No pixel changed triangle away from a triangle boundary (crosscheck.h's rule).
    CHECK(j["pixels"]["unexplained_changes"] == 0);
    CHECK(j["pixels"]["boundary_pixels"].get<double>() > 0);
    // Where the triangle is the same, at most one sRGB code once a bilinear level switch is
    // explained; trilinear presets need no explaining.
    CHECK(j["srgb_judged"]["max_error"].get<double>() <= 1.0 / 255 + 1e-7);
    const Scene scene = resolve_scene(preset, {});
    if (scene.shading.texture_filter == TextureFilter::kTrilinear) {
      CHECK(j["pixels"]["level_switch_channels"] == 0);
    }
    // PSNR is a number or null (infinite), never the string "inf".
    for (const char* part : {"srgb", "srgb_judged", "linear"}) {
      CHECK((j[part]["psnr_db"].is_number() || j[part]["psnr_db"].is_null()));
      CHECK(j[part]["psnr_db"].is_null() == (j[part]["max_error"].get<double>() == 0.0));
    }
  }
}

TEST_CASE("glStatsJsonMarksTheSoftwareRasterisersCountersAsNotApplicable", "[gl]") {
  test::TempDir dir("gl-stats");
  const CliResult r =
      run({"render", "--backend", "gl", "--set", "viewport.width=64", "--set", "viewport.height=48",
           "--set", "grid.width=40", "--set", "grid.height=30", "-o",
           (dir.path() / "g.png").string(), "--stats-json", (dir.path() / "s.json").string()});
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir.path() / "s.json"));
  // The grid's two triangles a cell go to GL's rasteriser; it has no set-up pieces or bins.
  CHECK(j["raster"]["triangles"] == 2 * 39 * 29);
  for (const char* counter : {"set_up", "bin_entries", "bin_bytes"}) {
    CHECK(j["raster"][counter].is_null());
  }
  CHECK_THAT(r.out, Contains("triangles submitted 2262 (to GL's rasteriser)"));
}

TEST_CASE("aStressRunOfAGlItCannotHaveIsRefusedNotPassed", "[gl]") {
  const std::filesystem::path binary = test::relief_binary();
  if (binary.empty()) {
    WARN("skipped: no relief binary in this build");
    return;
  }
  test::TempDir dir("stress-no-gl");
  // glvnd finds no EGL vendor: no context, as in a build or a machine without GL. The run once
  // skipped every case and said "every check holds", exit 0.
  const test::Exit r =
      test::run_binary(binary, "export __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json",
                       "stress --backend gl --axis pitch", dir.path());
  INFO(r.err);
  CHECK_FALSE(r.signalled);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--backend gl cannot run here") && Contains("nothing ran"));
}

TEST_CASE("anAddressSpaceTooSmallForTheGlDriverIsRefusedNotCrashed", "[gl]") {
  const std::filesystem::path binary = test::relief_binary();
  if (binary.empty() || test::kSanitized) {
    WARN("skipped: " << (test::kSanitized ? "a sanitizer build" : "no relief binary"));
    return;
  }
  test::TempDir dir("gl-ulimit");
  const std::filesystem::path out = dir.path() / "u.png";
  // 700000 KiB: the frame's estimate fits, llvmpipe's compiler and threads do not (it died of
  // SIGSEGV in its shader compiler).
  const test::Exit r = test::run_limited(
      binary, 700000,
      "render --backend gl --set viewport.width=512 --set viewport.height=384 -o '" + out.string() +
          "'",
      dir.path());
  INFO(r.err);
  CHECK_FALSE(r.signalled);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("the address-space limit (ulimit -v) leaves"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("theGlBackendRefusesCastShadowsItCannotDraw", "[gl]") {
  // No GLSL twin of the shadow stages yet (pipeline/stage_table.h): refused, not drawn without
  // them, with the field named; the CPU backends draw the same scene.
  test::TempDir dir("gl-shadows");
  const std::string out = (dir.path() / "sunset.png").string();
  const CliResult r = run({"render", "sunset", "--backend", "gl", "-o", out});
  INFO(r.err << r.out);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("lighting.shadows"));
  CHECK_FALSE(std::filesystem::exists(out));
  CHECK(run({"render", "sunset", "--backend", "simd", "-o", out}).code == 0);
}

TEST_CASE("theGlBackendRefusesSkyLightItCannotDraw", "[gl]") {
  // Sky light alone reads the same cache: refused the same way, the field named.
  test::TempDir dir("gl-sky");
  const std::string out = (dir.path() / "sunset.png").string();
  const CliResult r =
      run({"render", "sunset", "--set", "lighting.shadows=false", "--backend", "gl", "-o", out});
  INFO(r.err << r.out);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("lighting.sky_occlusion"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("theGlBackendRefusesTerrainReflectionsItCannotDraw", "[gl]") {
  // The mirror preset without its shadows and sky light: the reflections alone, named.
  test::TempDir dir("gl-mirror");
  const std::string out = (dir.path() / "mirror.png").string();
  const CliResult r = run({"render", "mirror", "--set", "lighting.shadows=false", "--set",
                           "lighting.sky_occlusion=false", "--backend", "gl", "-o", out});
  INFO(r.err << r.out);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("water.reflect_terrain"));
  CHECK_FALSE(std::filesystem::exists(out));
}

}  // namespace relief
