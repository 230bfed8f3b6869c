// Refusals a hostile pass found wrong or unclear: each names what is wrong and what is allowed,
// exits 2 and writes nothing; and the memory estimates that refused jobs that fit or advised the
// wrong remedy. Each case failed before (a raw CLI11 message, an option blamed that was not
// given, a second --set swallowing the scene, a sketch that was a basis image, a stress run
// that checked nothing, a 4096^2 grid refused at 2G).
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/job_memory.h"
#include "pipeline/memory_budget.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using Catch::Contains;
using test::CliResult;
using test::run;

const std::vector<std::string> kSmallRefusalFrame = {
    "--set", "viewport.width=64", "--set", "viewport.height=48",
    "--set", "grid.width=48",     "--set", "grid.height=48"};

std::vector<std::string> with_small(std::vector<std::string> args) {
  args.insert(args.end(), kSmallRefusalFrame.begin(), kSmallRefusalFrame.end());
  return args;
}

}  // namespace

TEST_CASE("aSetTakesOneValueAndLeavesTheSceneToScene", "[cli]") {
  // "--set a=b lava" once read lava as a second assignment ("expected KEY=VALUE").
  const CliResult lava = run({"scene", "--set", "viewport.width=64", "lava"});
  INFO(lava.err);
  REQUIRE(lava.code == 0);
  const Scene printed = resolve_scene_text(lava.out, "printed", ".", {});
  const Scene expected = resolve_scene("lava", {"viewport.width=64"});
  CHECK(scene_json_text(printed) == scene_json_text(expected));
  CHECK(scene_json_text(expected) != scene_json_text(resolve_scene("default", {})));
}

TEST_CASE("optionValuesOutOfTheirSetNameTheAllowedValues", "[cli]") {
  test::TempDir dir("float-format");
  const CliResult r = run({"stages", "--float-format", "2", "--out", (dir.path() / "s").string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--float-format: '2' is not a float format; allowed: pfm, exr"));
  CHECK_FALSE(std::filesystem::exists(dir.path() / "s"));
  // The names still work, in any case.
  CHECK(run(with_small({"stages", "--float-format", "EXR", "--out", (dir.path() / "e").string()}))
            .code == 0);
}

TEST_CASE("aSetValueThatLooksLikeJsonButDoesNotParseSaysSo", "[cli]") {
  for (const char* bad : {"terrain={bad", "terrain=[1,", "terrain.interpolant=\"quintic"}) {
    const CliResult r = run({"scene", "--set", bad});
    INFO(bad << ": " << r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("not valid JSON"));
    CHECK(r.err.find("must be a JSON object, got") == std::string::npos);
  }
  // A bare word stays a bare word.
  CHECK(run({"scene", "--set", "terrain.interpolant=quintic"}).code == 0);
}

TEST_CASE("sweepNamesItsOwnReferenceOptions", "[cli]") {
  test::TempDir dir("sweep-options");
  const CliResult r =
      run({"sweep", "--reference-supersample", "0", "--out", (dir.path() / "out").string()});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--reference-supersample 0 is out of range"));
  CHECK(r.err.find("--supersample") == std::string::npos);
}

TEST_CASE("aSketchNamesOnlyTheBuiltInSketches", "[cli]") {
  for (const char* name : {"builtin:nosuch", "builtin:basis/craters"}) {
    const CliResult r =
        run({"scene", "--set", std::string("terrain.sketch.image=\"") + name + "\""});
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("names no built-in sketch; allowed: builtin:island, or a PNG file"));
    CHECK(r.out.empty());
  }
  CHECK(run({"scene", "--set", "terrain.sketch.image=\"builtin:island\""}).code == 0);
}

TEST_CASE("stressRefusesABudgetBelowItsBaseSceneUpFront", "[cli]") {
  // Every case was once refused one by one, 18 failed rows and exit 1.
  const CliResult r = run({"stress", "--max-memory", "1M", "--backend", "simd"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("the stress suite's base scene on the simd backend needs about"));
  CHECK(r.out.empty());
}

TEST_CASE("aFineGridAtASmallViewportFitsWhereItsSetUpTrianglesDo", "[cli]") {
  // The estimate counted every triangle of the grid as set up; at 128 x 96 a 2048^2 grid sets
  // up a small share of them. The set-up triangles are counted when set up, against the budget.
  const Scene scene = resolve_scene("default", {"viewport.width=128", "viewport.height=96",
                                                "grid.width=2048", "grid.height=2048"});
  const MemoryEstimate estimate = estimate_render_memory(scene, Backend::kSimd, {});
  const std::uintmax_t vertices = std::uintmax_t{2048} * 2048;
  CHECK(estimate.total() < vertices * 100);  // 57 bytes a vertex, plus the resources
  test::TempDir dir("fine-grid");
  const std::filesystem::path out = dir.path() / "fine.png";
  const CliResult r =
      run({"render", "--set", "viewport.width=128", "--set", "viewport.height=96", "--set",
           "grid.width=2048", "--set", "grid.height=2048", "--max-memory", "512M", "-o",
           out.string(), "--stats-json", (dir.path() / "s.json").string()});
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(std::filesystem::is_regular_file(out));
  // Too little for the set-up triangles: refused once they are counted, nothing written.
  const std::filesystem::path tight = dir.path() / "tight.png";
  const CliResult refused =
      run({"render", "--set", "viewport.width=128", "--set", "viewport.height=96", "--set",
           "grid.width=2048", "--set", "grid.height=2048", "--max-memory",
           std::to_string(estimate.total() / 1048576 + 1) + "M", "-o", tight.string()});
  CHECK(refused.code == 2);
  CHECK_THAT(refused.err, Contains("set-up triangles and bins"));
  CHECK_FALSE(std::filesystem::exists(tight));
}

TEST_CASE("aRefusalDominatedByBasisImagesAdvisesOnTheImages", "[cli]") {
  const Scene scene =
      resolve_scene("craters", {"viewport.width=64", "viewport.height=48", "grid.width=48",
                                "grid.height=48", "terrain.basis.upsample=8"});
  const MemoryEstimate estimate = estimate_render_memory(scene, Backend::kSimd, {});
  const std::string budget = std::to_string(estimate.total() / 2 / 1048576 + 1) + "M";
  const CliResult r =
      run({"render", "craters", "--set", "viewport.width=64", "--set", "viewport.height=48",
           "--set", "grid.width=48", "--set", "grid.height=48", "--set", "terrain.basis.upsample=8",
           "--max-memory", budget, "-o", "/nonexistent/never.png"});
  INFO(r.err);
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("The basis images dominate: use smaller images or a lower "
                             "terrain.basis.upsample, or raise --max-memory."));
  CHECK(r.err.find("Lower viewport") == std::string::npos);
}

TEST_CASE("memorySizesReachOneExbibyte", "[cli]") {
  CHECK(parse_memory_size("1P") == std::uintmax_t{1} << 50);
  CHECK(parse_memory_size("1E") == std::uintmax_t{1} << 60);
  CHECK(parse_memory_size("1EiB") == std::uintmax_t{1} << 60);
  CHECK_FALSE(parse_memory_size("1.5E"));
  CHECK_FALSE(parse_memory_size("1Z"));
}

}  // namespace relief

namespace relief {

TEST_CASE("outputsNamedAfterAnInputOfRasterOrCrosscheckAreRefused", "[cli]") {
  test::TempDir dir("alias-inputs");
  // relief raster s.json --out s would write s.json over the soup.
  const std::string soup = test::write_file(dir.path() / "s.json", "4 4\n");
  const CliResult raster = run({"raster", soup, "--out", (dir.path() / "s").string()});
  CHECK(raster.code == 2);
  CHECK_THAT(raster.err, Contains("name the same file"));
  CHECK(test::read_bytes(soup).size() == 4);
  // A scene file inside crosscheck's --out under one of its output names.
  const CliResult printed = run({"scene", "--set", "viewport.width=64"});
  REQUIRE(printed.code == 0);
  const std::string scene = test::write_file(dir.path() / "crosscheck.json", printed.out);
  const CliResult crosscheck = run({"crosscheck", scene, "--out", dir.path().string()});
  CHECK(crosscheck.code == 4);
  CHECK_THAT(crosscheck.err, Contains("SCENE") && Contains("name the same file"));
  CHECK(test::read_bytes(scene).size() == printed.out.size());
}

}  // namespace relief

namespace relief {

TEST_CASE("noOutputOfACommandReplacesItsSceneOrTheFilesItReads", "[cli]") {
  // stages once wrote stages.json over a scene file of that name in its --out, and a picture
  // over a sketch image there; every command's outputs now refuse the scene's inputs.
  test::TempDir dir("protected-inputs");
  const CliResult printed = run(with_small({"scene"}));
  REQUIRE(printed.code == 0);
  const std::string scene = test::write_file(dir.path() / "stages.json", printed.out);
  const CliResult stages = run({"stages", scene, "--out", dir.path().string()});
  CHECK(stages.code == 2);
  CHECK_THAT(stages.err, Contains("names the same file as the input SCENE"));
  CHECK(test::read_bytes(scene).size() == printed.out.size());
  CHECK_FALSE(std::filesystem::exists(dir.path() / "height.png"));
  // The same through the scene's own default, output.stages_dir.
  const CliResult here =
      run({"stages", scene, "--set", "output.stages_dir=\"" + dir.path().string() + "\""});
  CHECK(here.code == 2);
  CHECK(test::read_bytes(scene).size() == printed.out.size());
}

TEST_CASE("stressRefusesErrorBoundsItCannotCheck", "[cli]") {
  // The distance axis's bounds compare with reference-double; without it the table said every
  // check holds.
  const CliResult r = run({"stress", "--axis", "distance", "--backend", "simd", "--viewport", "32",
                           "24", "--grid", "16"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("checks its error bounds against reference-double"));
  CHECK(r.out.empty());
}

TEST_CASE("sweepIntoARegularFileIsAnOutputThatCannotBeWritten", "[cli]") {
  test::TempDir dir("sweep-file");
  const std::string file = test::write_file(dir.path() / "f.txt", "x");
  const CliResult r = run({"sweep", "--out", file, "--quick"});
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("cannot write into") && Contains("it exists and is not a directory"));
  CHECK(test::read_bytes(file).size() == 1);
}

TEST_CASE("optionValuesOfTheWrongFormAreNamedWithTheirRange", "[cli]") {
  const auto refused = [](std::vector<std::string> args, const std::string& message) {
    const CliResult r = run(std::move(args));
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains(message));
  };
  refused({"render", "--repeat", "1e3"}, "--repeat: '1e3' is not a whole number from 1 to 1000");
  refused({"render", "--threads", "1.5"}, "--threads: '1.5' is not a whole number from 1 to 1024");
  refused({"reference", "--supersample", "2.5"}, "--supersample: '2.5' is not a whole number");
  refused({"render", "--backend", "vulkan"}, "--backend: 'vulkan' is not a backend; allowed: ");
  refused({"render", "--max-memory", "7Q"}, "--max-memory: '7Q' is not a size from 1M to 1E");
  refused({"stress", "--max-memory", "7Q"}, "--max-memory: '7Q' is not a size from 1M to 1E");
  refused({"render", "--simd", ""}, "--simd: empty; give a target");
}

TEST_CASE("jsonParseErrorsSpeakPlainlyAndEscapeBytesThatAreNotUtf8", "[cli]") {
  test::TempDir dir("json-errors");
  const std::string bad = test::write_file(dir.path() / "bad.json", "{\"a\": \"\xff\"}");
  const CliResult r = run({"scene", bad});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("not valid JSON: parse error") && Contains("\\xff"));
  CHECK(r.err.find("[json.exception") == std::string::npos);
  CHECK(r.err.find('\xff') == std::string::npos);
  CHECK(r.err.find("NaN and Infinity") == std::string::npos);
  // The hint stays where the text holds something like NaN.
  const std::string nan = test::write_file(dir.path() / "nan.json", "{\"terrain\": {\"H\": NaN}}");
  CHECK_THAT(run({"scene", nan}).err, Contains("NaN and Infinity are not JSON"));
}

}  // namespace relief
