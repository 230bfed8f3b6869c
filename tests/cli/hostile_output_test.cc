// The second round of hostile input (a tester with fresh eyes): corrupt images, invalid UTF-8,
// names that are empty, long or end in a directory, outputs that cannot all be written, and
// messages that must stay readable. Each case was reproduced on the code before its fix.
#include <sys/stat.h>

#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using Catch::Matchers::Contains;
using test::concat;
using test::require_refused;
using test::run;
using test::write_file;

// A PNG chunk: length, type, data, CRC-32 (ISO/IEC 15948 §5.3; CRC of type and data).
std::string png_chunk(const std::string& type, const std::string& data) {
  std::uint32_t crc = 0xffffffffu;
  for (const char c : type + data) {
    crc ^= static_cast<unsigned char>(c);
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
  }
  crc ^= 0xffffffffu;
  auto big_endian = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  return big_endian(static_cast<std::uint32_t>(data.size())) + type + data + big_endian(crc);
}

TEST_CASE("aCorruptDeflateStreamInATextureIsAnErrorNotACrash", "[hostile]") {
  // A valid signature and IHDR (16 x 16 RGB), then a zlib header followed by deflate block
  // type 3, which does not exist: stb fails without a reason, and relief once crashed on it.
  test::TempDir dir("corrupt-png");
  const std::string ihdr = std::string("\0\0\0\x10\0\0\0\x10\x08\x02\0\0\0", 13);
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) +
                          png_chunk("IDAT", "\x78\x9c\x07") + png_chunk("IEND", "");
  const std::string texture = write_file(dir.path() / "bad.png", png);
  const std::filesystem::path out = dir.path() / "out.png";
  require_refused(
      run({"render", "--set", concat({"shading.layers.1.texture=", texture}), "-o", out.string()}),
      "could not be decoded: corrupt image data", out);
}

TEST_CASE("invalidUtf8IsRefusedInScenesAndHarmlessInFileNames", "[hostile]") {
  test::TempDir dir("utf8");
  const std::string bad = "\xff\xfe";
  require_refused(run({"scene", "--set", concat({"output.image=", bad, ".png"})}),
                  "is not valid UTF-8", dir.path() / "nothing");
  require_refused(run({"render", "--set", concat({"shading.layers.0.name=", bad})}),
                  "is not valid UTF-8", dir.path() / "nothing");
  CHECK_FALSE(is_valid_utf8("\xc0\x80"));      // an overlong NUL
  CHECK_FALSE(is_valid_utf8("\xed\xa0\x80"));  // a surrogate
  CHECK(is_valid_utf8("h\xc3\xb6he \xe2\x86\x92 \xf0\x9f\x8f\x94"));
  // A file name is bytes on Linux: a soup's outputs are all written, the manifest's text with
  // the replacement character.
  const std::string soup = write_file(dir.path() / "s.txt", "4 4\n0 0 0.5 4 0 0.5 0 4 0.5\n");
  const std::string prefix = concat({(dir.path() / "p").string(), bad});
  const test::CliResult r = run({"raster", soup, "--out", prefix});
  INFO(r.err);
  CHECK(r.code == 0);
  for (const char* suffix :
       {".primitive.bin", ".depth.pfm", ".barycentric.pfm", ".coverage.png", ".json"}) {
    CHECK(std::filesystem::exists(prefix + suffix));
  }
}

TEST_CASE("aLookAtOverrideIsCheckedAgainstTheFinalPosition", "[hostile]") {
  // The look_at equals the default position, but a later override moves the camera away.
  const Scene scene =
      resolve_scene("default", {"camera.look_at=[0, 700, 0]", "camera.position=[0, 0, 0]"});
  CHECK(scene.camera.pitch_deg == Approx(90.0));
  CHECK_THROWS_WITH(
      resolve_scene("default", {"camera.position=[5, 5, 5]", "camera.look_at=[5, 5, 5]"}),
      Contains("the target must differ from camera.position"));
}

TEST_CASE("thePrintedSceneLoadsBackFromAnotherDirectory", "[hostile]") {
  // Texture paths are relative to the scene file; the printed scene holds them absolute.
  test::TempDir dir("round-trip");
  std::filesystem::create_directories(dir.path() / "a");
  std::filesystem::create_directories(dir.path() / "b");
  const std::vector<std::uint8_t> pixels(4 * 4 * 3, 100);
  const std::vector<unsigned char> png = encode_png_rgb(4, 4, pixels);
  write_file(dir.path() / "a" / "t.png", std::string(png.begin(), png.end()));
  const std::string scene =
      write_file(dir.path() / "a" / "s.json", R"({"shading": {"layers": [{"texture": "t.png"}]}})");
  const test::CliResult printed = run({"scene", scene});
  REQUIRE(printed.code == 0);
  const std::string saved = write_file(dir.path() / "b" / "saved.json", printed.out);
  const test::CliResult reloaded = run({"scene", saved});
  INFO(reloaded.err);
  REQUIRE(reloaded.code == 0);
  CHECK(reloaded.out == printed.out);
  const auto layers = nlohmann::json::parse(printed.out)["shading"]["layers"];
  CHECK(std::filesystem::path(layers[0]["texture"].get<std::string>()).is_absolute());
  const test::CliResult render =
      run({"render", saved, "--set", "viewport.width=32", "--set", "viewport.height=24", "--set",
           "grid.width=16", "--set", "grid.height=16", "-o", (dir.path() / "x.png").string()});
  INFO(render.err);
  CHECK(render.code == 0);
}

TEST_CASE("emptyOrNamelessTargetsAndMisappliedOptionsAreRefused", "[hostile]") {
  test::TempDir dir("names");
  const std::string soup = write_file(dir.path() / "s.txt", "8 8\n0 0 0.5 8 0 0.5 0 8 0.5\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", "", "-o", (dir.path() / "e.png").string()},
        std::vector<std::string>{"stages", "", "--out", (dir.path() / "st").string()},
        std::vector<std::string>{"scene", ""}}) {
    require_refused(run(args), "SCENE is empty", dir.path() / "e.png");
  }
  for (const std::string& prefix :
       {(dir.path() / "out").string() + "/", std::string("."), (dir.path() / "..").string()}) {
    require_refused(run({"raster", soup, "--out", prefix}), "has no file name part",
                    dir.path() / "out" / ".json");
  }
  require_refused(
      run({"raster", soup, "--out", (dir.path() / "p").string(), "--viewport", "0", "0", "4", "4"}),
      "--viewport applies to clip-coordinate soups", dir.path() / "p.json");
  // A layer index has one spelling: "01" would patch layer 1 a second time.
  CHECK_THROWS_WITH(
      resolve_scene("default",
                    {R"(shading.layers={"1": {"specular": 1}, "01": {"specular": 0.5}})"}),
      Contains("no layer '01'"));
  CHECK_THROWS_WITH(resolve_scene("default", {".time=1"}), Contains("has an empty segment"));
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator()) == 1);
}

TEST_CASE("longOutputNamesWorkAndHugeOnesGiveShortMessages", "[hostile]") {
  test::TempDir dir("long-names");
  // 250 bytes, legal on Linux (255): the temporary name must not grow past the limit.
  const std::string name = (dir.path() / (std::string(246, 'n') + ".png")).string();
  const test::CliResult ok =
      run({"render", "--set", "viewport.width=16", "--set", "viewport.height=16", "--set",
           "grid.width=8", "--set", "grid.height=8", "-o", name});
  INFO(ok.err);
  CHECK(ok.code == 0);
  CHECK(std::filesystem::exists(name));
  const std::string huge = (dir.path() / (std::string(120000, 'x') + ".png")).string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", "-o", huge.substr(0, huge.size() - 4) + ".jpg"},
        std::vector<std::string>{"render", "--set", "viewport.width=16", "--set",
                                 "viewport.height=16", "--set", "grid.width=8", "--set",
                                 "grid.height=8", "-o", huge}}) {
    const test::CliResult r = run(args);
    CHECK(r.code != 0);
    CHECK(r.err.size() < 1000);
  }
}

TEST_CASE("aCommandsOutputsAppearTogetherOrNotAtAll", "[hostile]") {
  test::TempDir dir("output-sets");
  const std::vector<std::string> tiny = {
      "--set", "viewport.width=16", "--set", "viewport.height=16",
      "--set", "grid.width=8",      "--set", "grid.height=8"};
  // The float image cannot be written: neither is the PNG.
  std::vector<std::string> render = {"render", "-o", (dir.path() / "a.png").string(), "--float",
                                     (dir.path() / "missing" / "a.pfm").string()};
  render.insert(render.end(), tiny.begin(), tiny.end());
  const test::CliResult r = run(render);
  CHECK(r.code == kExitOutputError);
  CHECK_FALSE(std::filesystem::exists(dir.path() / "a.png"));
  // stages.json is a directory: none of the fields' files appear either.
  std::filesystem::create_directories(dir.path() / "st" / "stages.json");
  std::vector<std::string> stages = {"stages", "--out", (dir.path() / "st").string()};
  stages.insert(stages.end(), tiny.begin(), tiny.end());
  const test::CliResult s = run(stages);
  INFO(s.err);
  CHECK(s.code == kExitOutputError);
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path() / "st"),
                      std::filesystem::directory_iterator()) == 1);
}

TEST_CASE("anOutputNamingASpecialFileIsRefusedAndTheFileKept", "[hostile]") {
  // Outputs are renamed into place; as root, a rename over /dev/null or a FIFO replaces the
  // special file. A FIFO in a temporary directory stands for them.
  test::TempDir dir("special-outputs");
  const std::filesystem::path image = dir.path() / "a.png";
  const std::filesystem::path fifo_json = dir.path() / "pipe.json";
  const std::filesystem::path fifo_png = dir.path() / "pipe.png";
  const std::filesystem::path fifo_pfm = dir.path() / "pipe.pfm";
  for (const std::filesystem::path& fifo : {fifo_json, fifo_png, fifo_pfm}) {
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  }
  const std::vector<std::vector<std::string>> outputs = {
      {"-o", image.string(), "--stats-json", fifo_json.string()},
      {"-o", fifo_png.string()},
      {"-o", image.string(), "--depth", fifo_pfm.string()}};
  for (const std::vector<std::string>& output : outputs) {
    std::vector<std::string> args = {
        "render",       "--set", "viewport.width=16", "--set", "viewport.height=16", "--set",
        "grid.width=8", "--set", "grid.height=8"};
    args.insert(args.end(), output.begin(), output.end());
    const test::CliResult r = run(args);
    INFO(output.back() << ": " << r.err);
    CHECK(r.code == kExitOutputError);
    CHECK_THAT(r.err, Contains("not a regular file"));
    for (const std::filesystem::path& fifo : {fifo_json, fifo_png, fifo_pfm}) {
      CHECK(std::filesystem::is_fifo(fifo));
    }
    CHECK_FALSE(std::filesystem::exists(image));
  }
}

TEST_CASE("soupsAcceptByteOrderMarksAndCrlfAndNameOutOfRangeNumbers", "[hostile]") {
  test::TempDir dir("soup-text");
  const std::string line = "0 0 0.5 8 0 0.5 0 8 0.5";
  const std::string padded = line + std::string(4096 - line.size(), ' ');  // exactly the limit
  const std::string soup =
      write_file(dir.path() / "s.txt", concat({"\xef\xbb\xbf", "8 8\r\n", padded, "\r\n"}));
  const test::CliResult ok = run({"raster", soup, "--out", (dir.path() / "p").string()});
  INFO(ok.err);
  CHECK(ok.code == 0);
  const std::string tiny = write_file(dir.path() / "t.txt", "8 8\n0 0 1e-400 8 0 0.5 0 8 0.5\n");
  require_refused(run({"raster", tiny, "--out", (dir.path() / "q").string()}),
                  "'1e-400' is out of the range of a double", dir.path() / "q.json");
  // Control characters in a message are escaped, never echoed raw.
  const test::CliResult escaped = run({"scene", "--set", concat({"ti\x1b[2Jme", "=1"})});
  CHECK(escaped.code == kExitBadInput);
  CHECK(escaped.err.find('\x1b') == std::string::npos);
  CHECK_THAT(escaped.err, Contains("ti\\x1b[2Jme"));
}

}  // namespace
}  // namespace relief
