// relief crosscheck on llvmpipe: every preset, the CPU and GL backends compared stage by stage
// within the bounds docs/gl-backend.md and docs/gl-shading.md derive (stages 1-4 bit-identical
// on llvmpipe; a pixel may change triangle only near an edge; sRGB one code at most), and the
// command's refusals.
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/frame_plan.h"
#include "core/scene/scene_json.h"
#include "core/stage_params.h"
#include "gpu/gl_checks.h"
#include "gpu/gl_terrain.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "tests/gl/gl_presets.h"
#include "tests/gl/gl_test_context.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::CliResult;
using test::run;

TEST_CASE("crosscheckOfEveryPresetOnLlvmpipeIsWithinTheDocumentedBounds", "[gl]") {
  test::TempDir dir("crosscheck");
  for (const std::string& preset : test::gl_preset_names()) {
    const std::filesystem::path out = dir.path() / preset;
    const CliResult r =
        run({"crosscheck", preset, "--out", out.string(), "--set", "viewport.width=240", "--set",
             "viewport.height=160", "--set", "grid.width=160", "--set", "grid.height=160"});
    INFO(preset << ": " << r.err << r.out);
    REQUIRE(r.code == 0);  // PASS: no pixel more than one sRGB code apart
    for (const char* file :
         {"cpu.png", "gl.png", "image_difference.png", "visibility_difference.png",
          "height_difference.png", "crosscheck.txt"}) {
      CHECK(std::filesystem::is_regular_file(out / file));
    }
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "crosscheck.json"));
    // Stages 1-4 are bit-identical on llvmpipe (docs/gl-backend.md).
    CHECK(j["grid"]["valid_mismatch"] == 0);
    CHECK(j["grid"]["max_height_error"] == 0.0);
    CHECK(j["grid"]["max_octave_error"] == 0.0);
    CHECK(j["grid"]["max_normal_angle_deg"] == 0.0);
    CHECK(j["grid"]["vertices"].get<double>() > 0);
    // Visibility: llvmpipe snaps as the CPU does; pixels change hands only on the framebuffer's
    // border and within 2/256 px of an edge (docs/gl-shading.md): a thousandth of the image is
    // far above what that allows on these frames.
    CHECK(j["pixels"]["primitive_mismatch"].get<double>() <=
          1e-3 * j["pixels"]["count"].get<double>());
    CHECK(j["srgb"]["max_error"].get<double>() <= 1.0 / 255 + 1e-7);
    CHECK(j["pixels"]["max_depth_error"].get<double>() < 1e-4);
    CHECK(j["pixels"]["max_normal_angle_deg"].get<double>() < 1.0);
    CHECK(j["frame_ms"]["gl"].get<double>() > 0);
  }
}

TEST_CASE("theGlBackendLeavesTheCallersContextCurrentAndRaisesNoGlError", "[gl]") {
  test::gl_context();
  void* const before = gpu::current_egl_context();
  REQUIRE(before != nullptr);
  test::TempDir dir("crosscheck-context");
  const CliResult r = run({"render", "--backend", "gl", "-o", (dir.path() / "a.png").string(),
                           "--set", "viewport.width=64", "--set", "viewport.height=48", "--set",
                           "grid.width=48", "--set", "grid.height=48"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(gpu::current_egl_context() == before);
  // The test context still works, and GL's debug output reported no error on it.
  test::gl_debug_errors().clear();
  const Scene scene = resolve_scene(
      "lava", {"viewport.width=64", "viewport.height=48", "grid.width=48", "grid.height=48"});
  const SceneResources resources = load_scene_resources(scene);
  const FramePlan plan = make_frame_plan(scene, resources.lattice);
  gpu::GlTerrain terrain(plan.layout, resources.lattice);
  terrain.run(make_terrain_params<float>(plan));
  GridBuffers<float> grid(plan.layout);
  terrain.read_all(grid);
  CHECK(test::gl_debug_errors().empty());
  // An invalid call is reported through the callback (the test of the test).
  glBindBuffer(GL_ARRAY_BUFFER, 0xdeadbeefu);
  CHECK_FALSE(test::gl_debug_errors().empty());
  gpu::clear_gl_errors();
  test::gl_debug_errors().clear();
}

TEST_CASE("aGlRenderTooLargeForTheMemoryIsRefusedNamingTheGlPart", "[gl]") {
  test::TempDir dir("gl-memory");
  const std::string png = (dir.path() / "big.png").string();
  // 16384^2 pixels: 4 GiB for the CPU's image, about 31 GiB more for the GL side's copies.
  const CliResult r = run({"render", "--backend", "gl", "-o", png, "--set", "viewport.width=16384",
                           "--set", "viewport.height=16384", "--max-memory", "8G"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("GL targets, read-back and buffers"));
  CHECK(!std::filesystem::exists(png));
  // The CPU backends' estimate of the same render has no GL part, and fits.
  const Scene scene = resolve_scene("default", {"viewport.width=16384", "viewport.height=16384"});
  const MemoryEstimate cpu = estimate_render_memory(scene, Backend::kSimd, {});
  const MemoryEstimate gl = estimate_render_memory(scene, Backend::kGl, {});
  CHECK(cpu.total() < (std::uintmax_t{8} << 30));
  CHECK(gl.total() - cpu.total() >= std::uintmax_t{16384} * 16384 * 123);
}

TEST_CASE("crosscheckRefusesBadInputAndWritesNothing", "[gl]") {
  test::TempDir dir("crosscheck-bad");
  const std::string out = (dir.path() / "out").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"crosscheck"},                                 // --out missing
           {"crosscheck", "--out", ""},                    // empty
           {"crosscheck", "--out", out, "--fail", "nan"},  // threshold not a number
           {"crosscheck", "--out", out, "--fail", "-1"},   // negative
           {"crosscheck", "--out", out, "--cpu-backend", "gl"},
           {"crosscheck", "--out", out, "--repeat", "0"},
           {"crosscheck", "no-such-preset", "--out", out},
           {"crosscheck", "--out", out, "--set", "viewport.width=0"}}) {
    const CliResult r = run(args);
    INFO(r.err);
    CHECK(r.code == 4);
    CHECK_THAT(r.err, Catch::Contains("relief: error:"));
  }
  CHECK(!std::filesystem::exists(out));
  // --out naming a regular file: nothing is written, exit 5 (output error).
  const std::string file = test::write_file(dir.path() / "file", "x");
  const CliResult r =
      run({"crosscheck", "--out", file, "--set", "viewport.width=64", "--set", "viewport.height=64",
           "--set", "grid.width=32", "--set", "grid.height=32"});
  CHECK(r.code == 5);
  CHECK(test::read_bytes(file).size() == 1);
}

}  // namespace
}  // namespace relief
