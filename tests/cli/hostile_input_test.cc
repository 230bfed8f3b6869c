// Input a hostile tester would try: deep nesting, duplicate keys, NUL bytes, special files
// behind innocent names, huge values, empty names, impossible memory. Every case ends with a
// message that names the problem and exit code 2, and writes nothing.
#include <sys/stat.h>

#include <cstring>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "pipeline/memory_budget.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tools/cli.h"

namespace relief {
namespace {

using Catch::Matchers::Contains;

using test::concat;
using test::require_refused;
using test::run;
using test::write_file;
using CliResult = test::CliResult;

TEST_CASE("deeplyNestedValuesAreRefusedWithoutRecursion", "[hostile]") {
  test::TempDir dir("nesting");
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::filesystem::path out = dir.path() / "out.png";
  const std::string file =
      write_file(dir.path() / "deep.json", concat({R"({"camera": {"position": )", deep, "}}"}));
  require_refused(run({"render", file, "-o", out.string()}), "nested deeper than 16 levels", out);
  // Unterminated nesting is refused the same way, before the syntax error is reached.
  write_file(dir.path() / "open.json", std::string(100000, '['));
  require_refused(run({"render", (dir.path() / "open.json").string(), "-o", out.string()}),
                  "nested deeper than 16 levels", out);
  require_refused(run({"render", "--set", concat({"camera.position=", deep}), "-o", out.string()}),
                  "nested deeper than 16 levels", out);
  // A key path of many segments builds the same nesting.
  std::string key = "a";
  for (int k = 0; k < 50000; ++k) {
    key += ".a";
  }
  require_refused(run({"render", "--set", concat({key, "=1"}), "-o", out.string()}), "segments",
                  out);
}

TEST_CASE("sceneFilesRejectDuplicateKeysAndNulBytes", "[hostile]") {
  test::TempDir dir("duplicates");
  const std::filesystem::path out = dir.path() / "out.png";
  const std::string duplicate =
      write_file(dir.path() / "dup.json", R"({"terrain": {"H": 0.5, "r": 2, "H": 0.9}})");
  require_refused(run({"render", duplicate, "-o", out.string()}), "key 'terrain.H' appears twice",
                  out);
  const std::string nested = write_file(
      dir.path() / "dup2.json",
      R"({"shading": {"layers": [{"texture": "builtin:sand", "name": "a", "name": "b"}]}})");
  require_refused(run({"render", nested, "-o", out.string()}),
                  "key 'shading.layers[0].name' appears twice", out);
  const std::string nul =
      write_file(dir.path() / "nul.json", std::string("{\"time\": 1}\0{\"time\": 2}", 23));
  require_refused(run({"render", nul, "-o", out.string()}), "contains a NUL byte at offset 11",
                  out);
  // A NUL inside a string would cut a path short for the operating system.
  require_refused(
      run({"render", "--set", R"(shading.layers.0.texture="a.png\u0000.txt")", "-o", out.string()}),
      "contains a NUL character", out);
  require_refused(run({"render", "--set", R"(output.image="x.png\u0000")", "-o", out.string()}),
                  "contains a NUL character", out);
}

TEST_CASE("specialFilesAreRefusedBeforeAnythingIsRead", "[hostile]") {
  test::TempDir dir("special");
  const std::filesystem::path out = dir.path() / "out.png";
  const std::string fifo = (dir.path() / "pipe.png").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::filesystem::create_directory(dir.path() / "folder.png");
  const std::string folder = (dir.path() / "folder.png").string();
  const std::vector<std::pair<std::string, std::string>> files = {
      {folder, "is a directory, not a regular file"},
      {"/dev/zero", "is a character device, not a regular file"},
      {fifo, "is a FIFO (named pipe), not a regular file"}};
  for (const auto& [path, reason] : files) {
    INFO(path);
    // As a texture, as a scene file and as a triangle soup: refused at once, never waited on.
    require_refused(
        run({"render", "--set", concat({"shading.layers.1.texture=", path}), "-o", out.string()}),
        "shading.layers[1].texture", out);
    require_refused(
        run({"render", "--set", concat({"shading.layers.1.texture=", path}), "-o", out.string()}),
        reason, out);
    if (path != folder) {  // a directory named like a scene is read as a scene file
      require_refused(run({"render", path, "-o", out.string()}), reason, out);
    }
    require_refused(run({"raster", path, "--out", (dir.path() / "soup").string()}), reason,
                    dir.path() / "soup.json");
  }
  require_refused(run({"render", folder, "-o", out.string()}), "is a directory", out);
}

TEST_CASE("texturesAreCheckedByTheirPngHeaderBeforeTheRestIsRead", "[hostile]") {
  test::TempDir dir("png-header");
  const std::filesystem::path out = dir.path() / "out.png";
  // A PNG signature and IHDR of 100000 x 100000 pixels, and nothing after it: refused by its
  // size, not called "not a PNG".
  auto header = [](std::uint32_t width, std::uint32_t height, int depth) {
    std::string h("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16);
    for (std::uint32_t v : {width, height}) {
      for (int shift = 24; shift >= 0; shift -= 8) {
        h += static_cast<char>((v >> shift) & 0xff);
      }
    }
    h += static_cast<char>(depth);
    h += std::string("\x02\0\0\0\0\0\0\0", 8);  // RGB, deflate, no interlace, a (wrong) CRC
    return h;
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {header(100000, 100000, 8), "is 100000x100000 pixels; allowed: square, a power of two"},
      {header(256, 256, 16), "has 16 bits per channel; allowed: 8-bit PNG"},
      {header(256, 256, 8) + "garbage", "could not be decoded"},
      {std::string("\x89PNG\r\n\x1a\n", 8), "is not a PNG image"},
      {"", "is not a PNG image"}};
  int k = 0;
  for (const auto& [bytes, message] : cases) {
    const std::string texture =
        write_file(dir.path() / concat({"t", std::to_string(k++), ".png"}), bytes);
    require_refused(run({"render", "--set", concat({"shading.layers.2.texture=", texture}), "-o",
                         out.string()}),
                    message, out);
  }
  // A file larger than any acceptable texture is refused by its size alone (a sparse file).
  const std::filesystem::path huge = dir.path() / "huge.png";
  write_file(huge, header(4096, 4096, 8));
  std::filesystem::resize_file(huge, std::uintmax_t{200} << 20);
  require_refused(run({"render", "--set", concat({"shading.layers.2.texture=", huge.string()}),
                       "-o", out.string()}),
                  "is 200.0 MiB; allowed at most 65.0 MiB", out);
}

TEST_CASE("messagesNameTheProblemAndCutHugeValues", "[hostile]") {
  test::TempDir dir("messages");
  const std::filesystem::path out = dir.path() / "out.png";
  require_refused(run({"render", "--set", "grid.width=1e9", "-o", out.string()}),
                  "grid.width = 1e+09 is out of range; allowed 2 <= grid.width <= 8192", out);
  require_refused(run({"render", "--set", "grid.width=2.5", "-o", out.string()}),
                  "grid.width = 2.5 is not an integer", out);
  CHECK(resolve_scene("default", {"grid.width=256.0", "terrain.seed=1e3"}).grid.width == 256);
  const CliResult unknown = run({"nonsense"});
  CHECK(unknown.code == kExitBadInput);
  CHECK_THAT(unknown.err, Contains("unknown command 'nonsense'; commands: scene, stages"));
  // A value of a million characters is quoted in a line, not echoed whole.
  const std::string huge(1000000, 'x');
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", "--set", concat({"terrain.r=\"", huge, "\""}), "-o",
                                 out.string()},
        std::vector<std::string>{"render", "--set", concat({"terrain.", huge, "=1"}), "-o",
                                 out.string()},
        std::vector<std::string>{"render", "--set", concat({"shading.layers.", huge, ".name=a"})},
        std::vector<std::string>{"render", huge},
        std::vector<std::string>{"render", "--threads", huge}}) {
    const CliResult r = run(args);
    CHECK(r.code == kExitBadInput);
    CHECK(r.err.size() < 1000);
    CHECK_THAT(r.err, Contains("relief: error:"));
  }
}

TEST_CASE("emptyNamesAreErrorsNotDefaults", "[hostile]") {
  test::TempDir dir("empty-names");
  const std::string soup = write_file(dir.path() / "soup.txt", "4 4\n0 0 0.5 4 0 0.5 0 4 0.5\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", "-o", ""},
        std::vector<std::string>{"render", "--float", ""},
        std::vector<std::string>{"stages", "--out", ""},
        std::vector<std::string>{"raster", soup, "--out", ""},
        std::vector<std::string>{"raster", "", "--out", (dir.path() / "p").string()},
        std::vector<std::string>{"render", "--set", "output.image=\"\""}}) {
    const CliResult r = run(args);
    INFO(r.err);
    CHECK(r.code == kExitBadInput);
    CHECK_THAT(r.err, Contains("empty"));
  }
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator()) == 1);
}

TEST_CASE("outputNamesFromTheSceneMustNameTheFormatTheyAreWrittenIn", "[hostile]") {
  test::TempDir dir("output-names");
  const std::filesystem::path jpg = dir.path() / "x.jpg";
  require_refused(run({"render", "--set", concat({"output.image=", jpg.string()})}),
                  "output.image = \"" + jpg.string() + "\": the image is written as PNG", jpg);
  require_refused(
      run({"render", "--set", concat({"output.float_image=", (dir.path() / "x.tif").string()}),
           "-o", (dir.path() / "x.png").string()}),
      "give a name ending in .pfm or .exr", dir.path() / "x.png");
  require_refused(run({"render", "-o", (dir.path() / "x.PnG.jpg").string()}),
                  "give a file name ending in .png", dir.path() / "x.PnG.jpg");
  CHECK(resolve_scene("default", {"output.image=A.PNG"}).output.image == "A.PNG");
}

TEST_CASE("viewportOfTheRasterCommandMustBeFinite", "[hostile]") {
  test::TempDir dir("viewport");
  const std::string soup = write_file(dir.path() / "soup.txt", "4 4\n0 0 0.5 4 0 0.5 0 4 0.5\n");
  for (const char* bad : {"nan", "inf", "-inf", "1e7", "0x1p3"}) {
    const CliResult r = run(
        {"raster", soup, "--out", (dir.path() / "p").string(), "--viewport", bad, "0", "64", "64"});
    INFO(bad << ": " << r.err);
    CHECK(r.code == kExitBadInput);
    CHECK_THAT(r.err, Contains("--viewport"));
  }
}

TEST_CASE("overridesGiveTheViewDirectionInOneFormOnly", "[hostile]") {
  CHECK_THROWS_WITH(resolve_scene("default", {"camera.look_at=[10, 0, 0]", "camera.yaw_deg=5"}),
                    Contains("both set the view direction"));
  CHECK_THROWS_WITH(resolve_scene("default", {"camera.pitch_deg=-5", "camera.look_at=[10, 0, 0]"}),
                    Contains("both set the view direction"));
  // Within the overrides, look_at is resolved against the final position, whatever the order.
  const Scene a =
      resolve_scene("default", {"camera.look_at=[10, 0, 0]", "camera.position=[0, 10, 0]"});
  const Scene b =
      resolve_scene("default", {"camera.position=[0, 10, 0]", "camera.look_at=[10, 0, 0]"});
  CHECK(a.camera.yaw_deg == Approx(90.0));
  CHECK(a.camera.pitch_deg == Approx(-45.0));
  CHECK(a.camera.yaw_deg == b.camera.yaw_deg);
  CHECK(a.camera.pitch_deg == b.camera.pitch_deg);
  // A later source may still adjust the angles that an earlier one gave.
  test::TempDir dir("look-at");
  const std::string file = write_file(
      dir.path() / "s.json", R"({"camera": {"position": [0, 10, 0], "look_at": [10, 0, 0]}})");
  const Scene adjusted = resolve_scene(file, {"camera.pitch_deg=-10"});
  CHECK(adjusted.camera.yaw_deg == Approx(90.0));
  CHECK(adjusted.camera.pitch_deg == -10.0);
}

TEST_CASE("jobsThatCannotFitTheirMemoryAreRefusedWithTheEstimate", "[hostile]") {
  test::TempDir dir("memory");
  const std::filesystem::path out = dir.path() / "out.png";
  require_refused(run({"render", "--max-memory", "32M", "-o", out.string()}),
                  "this render needs about", out);
  require_refused(run({"render", "--max-memory", "32M", "-o", out.string()}),
                  "--max-memory 32M is 32.0 MiB", out);
  // Past the up-front estimate, the set-up triangles and bins are counted and refused.
  require_refused(run({"render", "--max-memory", "48M", "-o", out.string()}),
                  "the rasteriser's set-up triangles and bins for this frame need", out);
  require_refused(run({"stages", "--set", "grid.width=8192", "--set", "grid.height=8192",
                       "--max-memory", "1G", "--out", (dir.path() / "stages").string()}),
                  "relief stages needs about", dir.path() / "stages");
  for (const char* bad : {"12x", "0", "-1G", "nan", "1e30T", "100K"}) {
    const CliResult r = run({"render", "--max-memory", bad, "-o", out.string()});
    INFO(bad << ": " << r.err);
    CHECK(r.code == kExitBadInput);
    CHECK_THAT(r.err, Contains("--max-memory"));
  }
  CHECK(parse_memory_size("1.5G") == std::uintmax_t{3} << 29);
  CHECK(parse_memory_size("512MiB") == std::uintmax_t{512} << 20);
  CHECK(parse_memory_size("2097152") == std::uintmax_t{2} << 20);
  // A soup whose framebuffer cannot fit, and one whose bins cannot: 20,000 triangles covering
  // every tile of a 4096 x 4096 framebuffer, 4096 bin entries each (320 MiB of bins), which
  // are counted before they are allocated.
  const std::string small = "16384 16384\n0 0 0.5 16384 0 0.5 0 16384 0.5\n";
  require_refused(run({"raster", write_file(dir.path() / "big.txt", small), "--out",
                       (dir.path() / "big").string(), "--max-memory", "1G"}),
                  "rasterising this soup needs about", dir.path() / "big.json");
  std::string many = "4096 4096\n";
  for (int k = 0; k < 20000; ++k) {
    many += "-10 -10 0.5 9000 -10 0.5 -10 9000 0.5\n";
  }
  const std::string soup = write_file(dir.path() / "many.txt", many);
  const CliResult bins =
      run({"raster", soup, "--out", (dir.path() / "many").string(), "--max-memory", "1G"});
  require_refused(bins, "rasteriser bins: 31", dir.path() / "many.json");
}

}  // namespace
}  // namespace relief
