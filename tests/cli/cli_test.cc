#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <stb_image.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "image/image_io.h"
#include "pipeline/build_info.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tools/cli.h"

namespace relief {
namespace {

using Catch::Matchers::Contains;

using test::CliResult;
using test::read_bytes;
using test::run;
using test::write_file;

TEST_CASE("helpExplainsTheCommandsAndOptions", "[cli]") {
  const CliResult top = run({"--help"});
  CHECK(top.code == 0);
  CHECK_THAT(top.out, Contains("stages"));
  CHECK_THAT(top.out, Contains("scene"));
  const CliResult stages = run({"stages", "--help"});
  CHECK(stages.code == 0);
  CHECK_THAT(stages.out, Contains("--set"));
  CHECK_THAT(stages.out, Contains("--out"));
  CHECK_THAT(stages.out, Contains("lava"));
}

TEST_CASE("sceneCommandPrintsTheEffectiveSceneAsJson", "[cli]") {
  const CliResult r = run({"scene", "lava", "--set", "terrain.H=0.85"});
  REQUIRE(r.code == 0);
  const nlohmann::json printed = nlohmann::json::parse(r.out);
  CHECK(printed["terrain"]["H"] == 0.85);
  CHECK(printed["terrain"]["warp"]["enabled"] == true);
}

TEST_CASE("badInputExitsWithCodeTwoAndWritesNoFile", "[cli]") {
  test::TempDir dir("bad-input");
  const std::filesystem::path out = dir.path() / "out";
  const std::vector<std::vector<std::string>> cases = {
      {"stages", write_file(dir.path() / "a.json", R"({"terrain": {"r": 1}})"), "--out",
       out.string()},
      {"stages", write_file(dir.path() / "b.json", R"({"terrain": {"q": 1}})"), "--out",
       out.string()},
      {"stages", write_file(dir.path() / "c.json", R"({"grid": {"width": 1}})"), "--out",
       out.string()},
      {"stages", write_file(dir.path() / "d.json", R"({"terrain": {"r": 1e400}})"), "--out",
       out.string()},
      {"stages", write_file(dir.path() / "e.json", R"({"terrain": )"), "--out", out.string()},
      {"stages", "--set", "terrain.H=nan", "--out", out.string()},
      {"stages", "--set", "viewport.width=16385", "--out", out.string()},
      {"stages", "no-such-preset", "--out", out.string()},
      {"stages", "--threads", "0", "--out", out.string()},
      {"stages", "--bogus", "--out", out.string()},
  };
  for (const auto& args : cases) {
    const CliResult r = run(args);
    INFO(r.err);
    CHECK(r.code == kExitBadInput);
    CHECK_THAT(r.err, Contains("relief: error:"));
    CHECK_FALSE(std::filesystem::exists(out));
  }
  // Only the scene files the test wrote are in the directory: no partial outputs.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) {
    ++entries;
  }
  CHECK(entries == 5);
}

TEST_CASE("stagesCommandWritesEveryBufferAsPngAndPfm", "[cli]") {
  test::TempDir dir("stages");
  const CliResult r = run({"stages", "--set", "grid.width=40", "--set", "grid.height=30", "--out",
                           dir.path().string()});
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("fractal"));
  const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir.path() / "stages.json"));
  for (const char* name : {"domain", "sigma", "nu", "height", "normal", "slope", "water_depth"}) {
    INFO(name);
    REQUIRE(manifest["files"].contains(name));
    const std::vector<unsigned char> png = read_bytes(dir.path() / (std::string(name) + ".png"));
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels =
        stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3);
    REQUIRE(pixels != nullptr);
    stbi_image_free(pixels);
    CHECK(w == 40);
    CHECK(h == 30);
  }
  // The raw height file holds exactly the stage-3 buffer (rows bottom-to-top).
  const Scene scene = resolve_scene("default", {"grid.width=40", "grid.height=30"});
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  GridBuffers<float> b(plan.layout);
  run_terrain_stages(plan, b);
  const std::vector<unsigned char> pfm = read_bytes(dir.path() / "height.pfm");
  const std::string header = "Pf\n40 30\n-1.0\n";
  REQUIRE(pfm.size() == header.size() + 40 * 30 * 4);
  CHECK(std::string(pfm.begin(), pfm.begin() + header.size()) == header);
  for (int j = 0; j < 30; ++j) {
    for (int i = 0; i < 40; ++i) {
      float v;
      std::memcpy(&v, pfm.data() + header.size() + (j * 40 + i) * 4, 4);
      REQUIRE(v == b.height[b.layout.index(i, j)]);
    }
  }
  const std::vector<unsigned char> domain = read_bytes(dir.path() / "domain.pfm");
  CHECK(std::string(domain.begin(), domain.begin() + 3) == "PF\n");
}

TEST_CASE("renderCommandWritesAnSrgbPngOfTheViewportSize", "[cli]") {
  test::TempDir dir("render");
  const std::string path = (dir.path() / "terrain.png").string();
  const CliResult r = run({"render", "--set", "viewport.width=160", "--set", "viewport.height=120",
                           "--set", "grid.width=64", "--set", "grid.height=64", "-o", path});
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("tiles: raster, resolve, shade, encode"));
  CHECK_THAT(r.out, Contains("backend simd ("));
  const std::vector<unsigned char> png = read_bytes(path);
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3);
  REQUIRE(pixels != nullptr);
  // The top row is sky (blue dominates), the bottom row terrain (it does not).
  const unsigned char* bottom = pixels + (static_cast<std::size_t>(h) - 1) * w * 3;
  const int top_red = pixels[0], top_blue = pixels[2];
  const int bottom_red = bottom[0], bottom_blue = bottom[2];
  CHECK(top_blue > top_red);
  CHECK(bottom_blue <= bottom_red);
  stbi_image_free(pixels);
  CHECK(w == 160);
  CHECK(h == 120);
}

TEST_CASE("renderRejectsBadInputWithoutWritingAFile", "[cli]") {
  test::TempDir dir("render-bad");
  const std::string png = (dir.path() / "x.png").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"render", "-o", (dir.path() / "x.jpg").string()},
           {"render", "--set", "camera.fov_y_deg=0", "-o", png},
           {"render", "--set", "grid.margin=99", "-o", png},
           {"render", "--repeat", "0", "-o", png},
           {"render", "--backend", "vulkan", "-o", png},
           {"render", "--simd", "avx9", "-o", png},
           {"render", "--simd", "sse4", "--backend", "reference", "-o", png},
           {"stages", "--backend", "", "--out", png},
           {"render", "--depth", png, "-o", png},
           {"render", "--primitive", png, "-o", png},
           {"render", "--normal", "", "-o", png}}) {
    const CliResult r = run(args);
    INFO(r.err);
    CHECK(r.code == kExitBadInput);
    CHECK_THAT(r.err, Contains("relief: error:"));
  }
  CHECK(dir.empty());
}

TEST_CASE("renderWritesEveryRequestedOutputOfEitherBackend", "[cli]") {
  test::TempDir dir("render-outputs");
  for (const char* backend : {"reference", "reference-double"}) {
    const auto file = [&](const char* name) {
      return (dir.path() / (std::string(backend) + name)).string();
    };
    const CliResult r = run({"render",
                             "--set",
                             "viewport.width=40",
                             "--set",
                             "viewport.height=30",
                             "--set",
                             "grid.width=24",
                             "--set",
                             "grid.height=24",
                             "--backend",
                             backend,
                             "-o",
                             file(".png"),
                             "--float",
                             file(".pfm"),
                             "--depth",
                             file("-depth.pfm"),
                             "--primitive",
                             file("-id.bin"),
                             "--normal",
                             file("-normal.pfm"),
                             "--height",
                             file("-height.pfm"),
                             "--octaves",
                             file("-nu.pfm")});
    INFO(r.err);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.out, Contains(std::string("backend ") + backend));
    CHECK(read_bytes(file("-id.bin")).size() == 40u * 30u * 4u);
    for (const auto& [name, header] :
         std::vector<std::pair<const char*, std::string>>{{".pfm", "PF\n40 30\n-1.0\n"},
                                                          {"-depth.pfm", "Pf\n40 30\n-1.0\n"},
                                                          {"-normal.pfm", "PF\n40 30\n-1.0\n"},
                                                          {"-height.pfm", "Pf\n40 30\n-1.0\n"},
                                                          {"-nu.pfm", "Pf\n40 30\n-1.0\n"}}) {
      const std::vector<unsigned char> pfm = read_bytes(file(name));
      const std::size_t channels = header[1] == 'F' ? 3 : 1;
      INFO(name);
      REQUIRE(pfm.size() == header.size() + 40 * 30 * 4 * channels);
      CHECK(std::string(pfm.begin(), pfm.begin() + header.size()) == header);
    }
  }
}

TEST_CASE("renderRejectsUnusableTextureFilesNamingTheLayer", "[cli]") {
  test::TempDir dir("textures");
  // A 6 x 4 PNG (not square), written with stb, and a file that is not a PNG at all.
  const std::vector<std::uint8_t> pixels(6 * 4 * 3, 128);
  const std::vector<unsigned char> png = encode_png_rgb(6, 4, pixels);
  std::ofstream(dir.path() / "wide.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  write_file(dir.path() / "text.png", "not an image");
  const std::string out = (dir.path() / "x.png").string();
  for (const auto& [file, message] : std::vector<std::pair<std::string, std::string>>{
           {"wide.png", "is 6x4 pixels; allowed: square"},
           {"text.png", "is not a PNG image"},
           {"missing.png", "cannot be opened"}}) {
    const std::string texture = (dir.path() / file).string();
    const CliResult r = run({"render", "--set", "shading.layers.3.texture=" + texture, "--set",
                             "viewport.width=32", "--set", "viewport.height=32", "-o", out});
    INFO(r.err);
    CHECK(r.code == kExitBadInput);
    CHECK_THAT(r.err, Contains("shading.layers[3].texture"));
    CHECK_THAT(r.err, Contains(message));
    CHECK_FALSE(std::filesystem::exists(out));
  }
  // A valid texture file is accepted, relative to the scene file's directory.
  const std::vector<std::uint8_t> square(8 * 8 * 3, 90);
  const std::vector<unsigned char> good = encode_png_rgb(8, 8, square);
  std::ofstream(dir.path() / "good.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(good.data()), std::streamsize(good.size()));
  const std::string scene = write_file(
      dir.path() / "scene.json",
      R"({"shading": {"layers": {"3": {"texture": "good.png"}}}, "viewport": {"width": 32, "height": 32}, "grid": {"width": 24, "height": 24}})");
  const CliResult ok = run({"render", scene, "-o", out});
  INFO(ok.err);
  CHECK(ok.code == 0);
  CHECK(std::filesystem::exists(out));
}

TEST_CASE("rasterCommandWritesTheDocumentedBuffers", "[cli]") {
  test::TempDir dir("raster");
  const std::string soup = write_file(dir.path() / "soup.txt",
                                      "# two triangles\n"
                                      "8 6\n"
                                      "0 0 0.5   8 0 0.5   0 6 0.5\n"
                                      "8 0 0.75  8 6 0.75  0 6 0.75   # nearer, reverse-Z\n");
  const std::string prefix = (dir.path() / "out" / "soup").string();
  const CliResult r = run({"raster", soup, "--out", prefix});
  REQUIRE(r.code == 0);
  const std::vector<unsigned char> ids = read_bytes(prefix + ".primitive.bin");
  REQUIRE(ids.size() == 8 * 6 * 4);
  std::uint32_t first = 0, last = 0;
  std::memcpy(&first, ids.data(), 4);                   // pixel (0, 0): only triangle 0
  std::memcpy(&last, ids.data() + (8 * 6 - 1) * 4, 4);  // pixel (7, 5): only triangle 1
  CHECK(first == 0);
  CHECK(last == 1);
  const std::vector<unsigned char> depth = read_bytes(prefix + ".depth.pfm");
  CHECK(std::string(depth.begin(), depth.begin() + 12) == "Pf\n8 6\n-1.0\n");
  const std::vector<unsigned char> bary = read_bytes(prefix + ".barycentric.pfm");
  CHECK(std::string(bary.begin(), bary.begin() + 12) == "PF\n8 6\n-1.0\n");
  CHECK(std::filesystem::exists(prefix + ".coverage.png"));
  CHECK(std::filesystem::exists(prefix + ".json"));
}

TEST_CASE("sampleSoupsOfTheDocsRasterise", "[cli]") {
  test::TempDir dir("sample-soups");
  for (const char* name : {"window", "clip"}) {
    const std::string soup = std::string(RELIEF_SOURCE_DIR) + "/docs/soups/" + name + ".txt";
    const std::string prefix = (dir.path() / name).string();
    const CliResult r = run({"raster", soup, "--out", prefix});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(prefix + ".json"));
    CHECK(manifest["triangles"].get<int>() >= 3);
    CHECK(manifest["covered_pixels"].get<int>() > 1000);
  }
}

TEST_CASE("rasterGivesTheSameBuffersWithEveryBackendAndSimdTarget", "[cli]") {
  test::TempDir dir("raster-backends");
  const std::string soup = std::string(RELIEF_SOURCE_DIR) + "/docs/soups/clip.txt";
  const std::string reference = (dir.path() / "reference").string();
  REQUIRE(run({"raster", soup, "--out", reference, "--backend", "reference"}).code == 0);
  std::vector<std::vector<std::string>> variants = {{}, {"--backend", "simd"}};
  for (const SimdTargetInfo& target : build_info().simd_targets) {
    if (target.supported) {
      variants.push_back({"--simd", target.name});
    }
  }
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const std::vector<std::string>& extra = variants[v];
    const std::string prefix = (dir.path() / std::to_string(v)).string();
    std::vector<std::string> args = {"raster", soup, "--out", prefix};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = run(args);
    INFO(args.back() << ": " << r.err);
    REQUIRE(r.code == 0);
    for (const char* file : {".primitive.bin", ".depth.pfm", ".barycentric.pfm"}) {
      CHECK(read_bytes(prefix + file) == read_bytes(reference + file));
    }
  }
  const CliResult wrong =
      run({"raster", soup, "--out", reference, "--backend", "reference-double"});
  CHECK(wrong.code == 2);
  CHECK_THAT(wrong.err, Contains("does not apply to relief raster"));
}

TEST_CASE("rasterRejectsMalformedSoupsNamingTheLine", "[cli]") {
  test::TempDir dir("raster-bad");
  const std::string prefix = (dir.path() / "out").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "empty"},
      {"8\n", ":1: the header must be 'W H'"},
      {"0 6\n", ":1: the header must be 'W H'"},
      {"8 6\n1 2 3 4 5 6 7 8 9 10\n", ":2: a triangle is 9 numbers"},
      {"8 6\n0 0 0.5 8 0 0.5 0 nan 0.5\n", ":2: 'nan' is not a finite number"},
      {"8 6\n0 0 0.5 8 0 0.5 0 6 1.5\n", ":2: vertex 2 has depth z = 1.5"},
      {"8 6\n0 0 0.5 8 0 0.5 0 3e6 0.5\n", ":2: vertex 2 lies outside the guard band"},
      {"8 6\n0 0 0.5 8 0 0.5 0 6 0.5\n0 0 0 1 1 0 0 1 0 1 0 1\n", ":3: clip coordinates, but"},
      {"8 6\n0 0 0.5 8 0 0.5 0 6 0.5 x\n", "'x' is not a finite number"},
  };
  int k = 0;
  for (const auto& [text, message] : cases) {
    const std::string soup = write_file(dir.path() / ("soup" + std::to_string(k++)), text);
    const CliResult r = run({"raster", soup, "--out", prefix});
    INFO(r.err);
    CHECK(r.code == kExitBadInput);
    CHECK_THAT(r.err, Contains(message));
  }
  const CliResult missing = run({"raster", (dir.path() / "none.txt").string(), "--out", prefix});
  CHECK(missing.code == kExitBadInput);
  const CliResult viewport = run({"raster", (dir.path() / "soup3").string(), "--out", prefix,
                                  "--viewport", "0", "0", "0", "5"});
  CHECK(viewport.code == kExitBadInput);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    CHECK(entry.path().filename().string().rfind("soup", 0) == 0);  // only the inputs
  }
}

TEST_CASE("infoListsTheBuildAndTheSimdTargets", "[cli]") {
  const CliResult r = run({"info"});
  CHECK(r.code == kExitOk);
  CHECK_THAT(r.out, Contains("relief "));
  CHECK_THAT(r.out, Contains("flags: -ffp-contract=off"));
  CHECK_THAT(r.out, Contains("Highway 1."));
  CHECK_THAT(r.out, Contains("SCALAR"));
  CHECK_THAT(r.out, Contains("simd backend target: "));
}

TEST_CASE("renderOnAForcedSimdTargetWritesTheReferencesBytes", "[cli]") {
  test::TempDir dir("render-simd");
  const std::vector<std::string> small = {
      "--set", "viewport.width=96", "--set", "viewport.height=64",
      "--set", "grid.width=40",     "--set", "grid.height=40"};
  const auto render = [&](std::vector<std::string> args, const std::string& name) {
    args.insert(args.begin(), {"render", "lava", "-o", (dir.path() / name).string()});
    args.insert(args.end(), small.begin(), small.end());
    const CliResult r = run(args);
    INFO(r.err);
    REQUIRE(r.code == kExitOk);
    return test::read_bytes(dir.path() / name);
  };
  const auto reference = render({"--backend", "reference"}, "reference.png");
  CHECK(render({"--simd", "scalar"}, "scalar.png") == reference);
  CHECK(render({"--backend", "simd"}, "best.png") == reference);
  CHECK(render({"--simd", "best", "--backend", "simd"}, "best2.png") == reference);
}

}  // namespace
}  // namespace relief
