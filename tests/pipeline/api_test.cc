// The library interface (include/relief/relief.h): scenes resolved as the command line resolves
// them, errors as values with the command line's messages, renders with exactly the outputs
// asked for.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "relief/relief.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace {

namespace api = relief::api;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using relief::test::CliResult;
using relief::test::concat;

// An Error's message for the report of a failed check; "" for a value.
template <class T>
std::string message_of(const api::Result<T>& result) {
  return result ? std::string() : result.error().message;
}

// A frame small enough for the sanitizer build.
const std::vector<std::string> kSmallApiFrame = {"viewport.width=64", "viewport.height=48",
                                                 "grid.width=32", "grid.height=32"};

api::Scene small_scene() {
  const api::Result<api::Scene> scene = api::Scene::load("", kSmallApiFrame);
  INFO(message_of(scene));
  REQUIRE(scene);
  return *scene;
}

// What `relief ARGS` prints on its error stream for the error `error`.
std::string cli_error_line(const api::Error& error) {
  return concat({"relief: error: ", error.message, "\n"});
}

TEST_CASE("apiLoadsTheDefaultSceneWhenGivenNoName", "[api]") {
  const api::Result<api::Scene> scene = api::Scene::load();
  INFO(message_of(scene));
  REQUIRE(scene);
  CHECK(scene->width() == 1280);
  CHECK(scene->height() == 1024);
  const CliResult cli = relief::test::run({"scene"});
  REQUIRE(cli.code == 0);
  CHECK(scene->to_json() == cli.out);
  const api::Result<api::Scene> named = api::Scene::load("default");
  INFO(message_of(named));
  REQUIRE(named);
  CHECK(named->to_json() == scene->to_json());
}

TEST_CASE("apiLoadsEveryPresetAsTheSceneCommandPrintsIt", "[api]") {
  const std::vector<std::string> presets = api::presets();
  CHECK(std::find(presets.begin(), presets.end(), "default") != presets.end());
  CHECK(std::find(presets.begin(), presets.end(), "lava") != presets.end());
  CHECK(std::is_sorted(presets.begin(), presets.end()));
  for (const std::string& name : presets) {
    INFO(name);
    const api::Result<api::Scene> scene = api::Scene::load(name);
    INFO(message_of(scene));
    REQUIRE(scene);
    const CliResult cli = relief::test::run({"scene", name});
    REQUIRE(cli.code == 0);
    CHECK(scene->to_json() == cli.out);
  }
}

TEST_CASE("apiLoadsASceneFileAndAppliesOverridesInOrder", "[api]") {
  relief::test::TempDir dir("api-file");
  const std::string file = relief::test::write_file(
      dir.path() / "scene.json", R"({"viewport": {"width": 320, "height": 200}})");
  const api::Result<api::Scene> scene =
      api::Scene::load(file, {"viewport.height=100", "viewport.height=240", "terrain.H=0.5"});
  INFO(message_of(scene));
  REQUIRE(scene);
  CHECK(scene->width() == 320);
  CHECK(scene->height() == 240);
  const CliResult cli = relief::test::run({"scene", file, "--set", "viewport.height=100", "--set",
                                           "viewport.height=240", "--set", "terrain.H=0.5"});
  REQUIRE(cli.code == 0);
  CHECK(scene->to_json() == cli.out);
  CHECK_THAT(scene->to_json(), Contains("\"H\": 0.5"));
}

TEST_CASE("apiRefusesBadScenesWithExitCodeTwoAndTheCommandLinesMessage", "[api]") {
  relief::test::TempDir dir("api-bad");
  const std::string not_json = relief::test::write_file(dir.path() / "a.json", R"({"terrain": )");
  const std::string bad_field =
      relief::test::write_file(dir.path() / "b.json", R"({"terrain": {"r": 1}})");
  struct Case {
    std::string scene;
    std::vector<std::string> overrides;
    std::string names;  // a part of the message
  };
  const std::vector<Case> cases = {
      {"", {"grid.width=1"}, "grid.width"},
      {"", {"terrain.H=nan"}, "terrain.H"},
      {"", {"terrain.bogus=1"}, "terrain.bogus"},
      {"", {"no equals sign"}, "no equals sign"},
      {"no-such-preset", {}, "no-such-preset"},
      {not_json, {}, "a.json"},
      {bad_field, {}, "terrain.r"},
      {dir.path().string(), {}, "regular file"},
  };
  for (const Case& c : cases) {
    const api::Result<api::Scene> scene = api::Scene::load(c.scene, c.overrides);
    REQUIRE_FALSE(scene);
    const api::Error& error = scene.error();
    INFO(error.message);
    CHECK(error.exit_code == api::kExitBadInput);
    CHECK_THAT(error.message, Contains(c.names));
    CHECK(error.message.find('\n') == std::string::npos);
    std::vector<std::string> args = {"scene"};
    if (!c.scene.empty()) {  // the command line's SCENE left out, not empty
      args.push_back(c.scene);
    }
    for (const std::string& assignment : c.overrides) {
      args.insert(args.end(), {"--set", assignment});
    }
    const CliResult cli = relief::test::run(args);
    CHECK(cli.code == error.exit_code);
    CHECK(cli.err == cli_error_line(error));
  }
}

TEST_CASE("renderReturnsOnlyTheSrgbImageWhenNoOutputIsAskedFor", "[api]") {
  const api::Result<api::Rendering> frame = api::render(small_scene());
  INFO(message_of(frame));
  REQUIRE(frame);
  const api::Image& image = frame->image;
  CHECK(image.width == 64);
  CHECK(image.height == 48);
  CHECK(image.srgb.size() == 64u * 48u * 3u);
  CHECK(image.linear.empty());
  CHECK(image.depth.empty());
  CHECK(image.primitive.empty());
  CHECK(image.normal.empty());
  CHECK(image.world_height.empty());
  CHECK(image.octaves.empty());
  CHECK(std::any_of(image.srgb.begin(), image.srgb.end(),
                    [&](std::uint8_t v) { return v != image.srgb[0]; }));
  const api::Statistics& stats = frame->statistics;
  REQUIRE_FALSE(stats.stages.empty());
  // The work counters reach the caller: every pixel is shaded once, as terrain or background.
  std::uint64_t shaded = 0;
  for (const api::StageReport& stage : stats.stages) {
    for (const auto& [name, value] : stage.counters) {
      if (name == "pixels shaded as terrain" || name == "pixels shaded as background") {
        shaded += value;
      }
    }
  }
  CHECK(shaded == 64u * 48u);
  CHECK(stats.total_ms > 0);
  CHECK(stats.triangles_submitted == 2u * 31u * 31u);
  CHECK(stats.triangles_set_up > 0);
}

TEST_CASE("renderReturnsEachRequestedOutputAtTheImageSizeAndNoOther", "[api]") {
  const api::Scene scene = small_scene();
  const std::size_t pixels = 64 * 48;
  struct Case {
    const char* name;
    bool api::RenderOptions::*flag;
    std::size_t values;  // per pixel
  };
  const Case cases[] = {{"linear", &api::RenderOptions::linear, 3},
                        {"depth", &api::RenderOptions::depth, 1},
                        {"primitive", &api::RenderOptions::primitive, 1},
                        {"normal", &api::RenderOptions::normal, 3},
                        {"world_height", &api::RenderOptions::world_height, 1},
                        {"octaves", &api::RenderOptions::octaves, 1}};
  for (const Case& c : cases) {
    INFO(c.name);
    api::RenderOptions options;
    options.*c.flag = true;
    const api::Result<api::Rendering> frame = api::render(scene, options);
    INFO(message_of(frame));
    REQUIRE(frame);
    const api::Image& image = frame->image;
    CHECK(image.srgb.size() == 3 * pixels);
    const std::size_t sizes[] = {image.linear.size(),       image.depth.size(),
                                 image.primitive.size(),    image.normal.size(),
                                 image.world_height.size(), image.octaves.size()};
    for (std::size_t k = 0; k < std::size(cases); ++k) {
      INFO(cases[k].name);
      CHECK(sizes[k] == (cases[k].flag == c.flag ? c.values * pixels : 0));
    }
  }
}

TEST_CASE("renderGivesIdenticalBytesOnOneAndTwoThreads", "[api]") {
  const api::Scene scene = small_scene();
  api::RenderOptions options;
  options.linear = true;
  options.threads = 1;
  const api::Result<api::Rendering> one = api::render(scene, options);
  options.threads = 2;
  const api::Result<api::Rendering> two = api::render(scene, options);
  INFO(message_of(one));
  REQUIRE(one);
  INFO(message_of(two));
  REQUIRE(two);
  CHECK(one->image.srgb == two->image.srgb);
  CHECK(one->image.linear == two->image.linear);  // bitwise: no NaN leaves a stage
}

TEST_CASE("renderRunsFromSeveralThreadsAtOnceOnOneScene", "[api]") {
  const api::Scene scene = small_scene();
  const api::Result<api::Rendering> reference = api::render(scene);
  INFO(message_of(reference));
  REQUIRE(reference);
  std::vector<std::vector<std::uint8_t>> images(3);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < images.size(); ++k) {
    threads.emplace_back([&, k] {
      api::RenderOptions options;
      options.threads = int(k);  // 0: the default arena; 1 and 2: arenas of their own
      if (const api::Result<api::Rendering> frame = api::render(scene, options)) {
        images[k] = frame->image.srgb;
      }
    });
  }
  for (std::thread& thread : threads) {
    thread.join();
  }
  for (const std::vector<std::uint8_t>& image : images) {
    CHECK(image == reference->image.srgb);
  }
}

TEST_CASE("renderRefusesAnUnknownBackendNamingTheAllowedOnes", "[api]") {
  const std::vector<std::string> backends = api::backends();
  REQUIRE_FALSE(backends.empty());
  CHECK(backends.front() == "reference");
  api::RenderOptions options;
  options.backend = "vulkan";
  const api::Result<api::Rendering> frame = api::render(small_scene(), options);
  REQUIRE_FALSE(frame);
  CHECK(frame.error().exit_code == api::kExitBadInput);
  CHECK_THAT(frame.error().message, Contains("vulkan"));
  for (const std::string& name : backends) {
    CHECK_THAT(frame.error().message, Contains(name));
  }
}

TEST_CASE("renderRefusesAThreadCountOutOfRange", "[api]") {
  for (const int threads : {-1, 1025}) {
    api::RenderOptions options;
    options.threads = threads;
    const api::Result<api::Rendering> frame = api::render(small_scene(), options);
    REQUIRE_FALSE(frame);
    CHECK(frame.error().exit_code == api::kExitBadInput);
    CHECK_THAT(frame.error().message, Contains("RenderOptions::threads"));
  }
}

TEST_CASE("renderRefusesAFrameLargerThanItsMemoryBudgetWithExitCodeTwo", "[api]") {
  api::RenderOptions options;
  options.max_memory_bytes = 1 << 20;
  const api::Result<api::Rendering> frame = api::render(small_scene(), options);
  REQUIRE_FALSE(frame);
  INFO(frame.error().message);
  CHECK(frame.error().exit_code == api::kExitBadInput);
  CHECK_THAT(frame.error().message, StartsWith("this render needs about "));
  CHECK_THAT(frame.error().message, Contains("RenderOptions::max_memory_bytes is 1.0 MiB"));
  CHECK_THAT(frame.error().message, Contains("raise RenderOptions::max_memory_bytes"));
}

TEST_CASE("renderRefusesAMissingTextureFileWithTheCommandLinesMessage", "[api]") {
  std::vector<std::string> overrides = kSmallApiFrame;
  overrides.emplace_back("shading.layers={\"0\": {\"texture\": \"/nonexistent/bed.png\"}}");
  const api::Result<api::Scene> scene = api::Scene::load("", overrides);
  INFO(message_of(scene));
  REQUIRE(scene);  // texture files are read by render only
  const api::Result<api::Rendering> frame = api::render(*scene);
  REQUIRE_FALSE(frame);
  CHECK(frame.error().exit_code == api::kExitBadInput);
  CHECK_THAT(frame.error().message, Contains("/nonexistent/bed.png"));
  relief::test::TempDir dir("api-texture");
  std::vector<std::string> args = {"render", "-o", (dir.path() / "out.png").string()};
  for (const std::string& assignment : overrides) {
    args.insert(args.end(), {"--set", assignment});
  }
  const CliResult cli = relief::test::run(args);
  CHECK(cli.code == frame.error().exit_code);
  CHECK(cli.err == cli_error_line(frame.error()));
}

TEST_CASE("encodePngGivesTheFileTheRenderCommandWrites", "[api]") {
  const api::Scene scene = small_scene();
  const api::Result<api::Rendering> frame = api::render(scene);
  INFO(message_of(frame));
  REQUIRE(frame);
  // With the scene: the file itself, metadata included (image/image_metadata.h).
  const api::Result<std::vector<unsigned char>> png = api::encode_png(frame->image, scene);
  INFO(message_of(png));
  REQUIRE(png);
  // Without it the scene's text chunk is left out: shorter by at least the scene's text.
  const api::Result<std::vector<unsigned char>> bare = api::encode_png(frame->image);
  REQUIRE(bare);
  CHECK(bare->size() + scene.to_json().size() < png->size());
  relief::test::TempDir dir("api-png");
  const std::filesystem::path file = dir.path() / "cli.png";
  std::vector<std::string> args = {"render", "-o", file.string()};
  for (const std::string& assignment : kSmallApiFrame) {
    args.insert(args.end(), {"--set", assignment});
  }
  REQUIRE(relief::test::run(args).code == 0);
  CHECK(*png == relief::test::read_bytes(file));
}

TEST_CASE("encodersRefuseBuffersThatDoNotMatchTheirSize", "[api]") {
  api::Image image;
  image.width = 4;
  image.height = 2;
  image.srgb.assign(4 * 2 * 3 - 1, 0);
  const api::Result<std::vector<unsigned char>> png = api::encode_png(image);
  REQUIRE_FALSE(png);
  CHECK(png.error().exit_code == api::kExitBadInput);
  CHECK_THAT(png.error().message, Contains("expected 24"));
  image.width = 0;
  CHECK_THAT(api::encode_png(image).error().message, Contains("0x2"));

  const std::vector<float> values(4 * 2 * 3, 0.5f);
  const api::Result<std::vector<unsigned char>> pfm = api::encode_pfm(4, 2, 3, values);
  INFO(message_of(pfm));
  REQUIRE(pfm);
  const std::string header = "PF\n4 2\n-1.0\n";
  REQUIRE(pfm->size() == header.size() + values.size() * sizeof(float));
  CHECK(std::equal(header.begin(), header.end(), pfm->begin()));
  CHECK_FALSE(api::encode_pfm(4, 2, 1, values));
  CHECK_FALSE(api::encode_pfm(4, 2, 2, values));
  CHECK_FALSE(api::encode_pfm(-4, 2, 3, values));
}

TEST_CASE("versionIsTheProjectsVersion", "[api]") {
  CHECK(api::version() == RELIEF_PROJECT_VERSION);
}

}  // namespace
