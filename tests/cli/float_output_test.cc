// Float outputs as EXR (tools/float_image_file.h) beside PFM, and the metadata of Relief's
// images as OpenImageIO and idiff read them: the EXR holds the PFM's floats bit for bit, the
// scene in both file types parses back to the scene.
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <stb_image.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "image/image_metadata.h"
#include "pipeline/build_info.h"
#include "tests/support/cli_support.h"
#include "tests/support/idiff_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::CliResult;
using test::read_bytes;
using test::run;

const std::vector<std::string> kSmallFloatFrame = {"viewport.width=48", "viewport.height=36",
                                                   "grid.width=24", "grid.height=24"};

std::vector<std::string> with_scene(std::vector<std::string> args) {
  for (const std::string& o : kSmallFloatFrame) {
    args.insert(args.end(), {"--set", o});
  }
  return args;
}

// A PFM's floats, rows bottom first as written (image_io.h).
std::vector<float> pfm_floats(const std::filesystem::path& path, int& width, int& height,
                              int& channels) {
  std::ifstream in(path, std::ios::binary);
  std::string kind, scale;
  in >> kind >> width >> height >> scale;
  in.get();
  channels = kind == "PF" ? 3 : 1;
  std::vector<float> v(std::size_t(width) * std::size_t(height) * std::size_t(channels));
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(v.size() * 4));
  return v;
}

struct OiioImage {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // top row first
};

OiioImage read_with_oiio(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  REQUIRE(in);
  OiioImage image{in->spec(), {}};
  image.pixels.resize(image.spec.image_pixels() * std::size_t(image.spec.nchannels));
  REQUIRE(in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeFloat, image.pixels.data()));
  return image;
}

// The EXR holds the PFM's floats exactly, rows flipped (EXR top first, PFM bottom first).
void check_same_floats(const std::filesystem::path& exr, const std::filesystem::path& pfm) {
  INFO(exr.string());
  int w = 0, h = 0, c = 0;
  const std::vector<float> expected = pfm_floats(pfm, w, h, c);
  const OiioImage image = read_with_oiio(exr);
  REQUIRE((image.spec.width == w && image.spec.height == h && image.spec.nchannels == c));
  CHECK(image.spec.format == OIIO::TypeFloat);  // 32-bit channels, not half
  const std::size_t row = std::size_t(w) * std::size_t(c);
  for (int y = 0; y < h; ++y) {
    const float* exr_row = image.pixels.data() + std::size_t(y) * row;
    const float* pfm_row = expected.data() + std::size_t(h - 1 - y) * row;
    REQUIRE(std::memcmp(exr_row, pfm_row, row * 4) == 0);
  }
}

TEST_CASE("renderWritesFloatOutputsAsExrWithThePfmsFloats", "[float_output]") {
  test::TempDir dir("exr");
  const auto at = [&](const std::string& name) { return (dir.path() / name).string(); };
  const std::vector<std::string> names = {"linear", "depth", "normal", "height", "octaves"};
  for (const char* extension : {".pfm", ".exr"}) {
    const std::string e = extension;
    const CliResult r =
        run(with_scene({"render", "-o", at("r" + e + ".png"), "--float", at("linear" + e),
                        "--depth", at("depth" + e), "--normal", at("normal" + e), "--height",
                        at("height" + e), "--octaves", at("octaves" + e)}));
    INFO(r.err);
    REQUIRE(r.code == 0);
  }
  for (const std::string& name : names) {
    check_same_floats(at(name + ".exr"), at(name + ".pfm"));
  }
  // The EXR carries the software and the scene as string attributes, and no time stamp: the
  // same scene gives the same bytes.
  const Scene scene = resolve_scene("", kSmallFloatFrame);
  const OiioImage linear = read_with_oiio(at("linear.exr"));
  CHECK(linear.spec.get_string_attribute("Software") ==
        test::concat({"relief ", relief_version()}));
  const std::string text = linear.spec.get_string_attribute(std::string(kSceneKey));
  CHECK(text == scene_json_text(scene));
  CHECK(nlohmann::json::parse(text) == scene_to_json(scene));
  CHECK(linear.spec.find_attribute("DateTime") == nullptr);
  CHECK(linear.spec.get_string_attribute("compression") == "zip");
  const std::vector<unsigned char> first = read_bytes(at("linear.exr"));
  REQUIRE(run(with_scene({"render", "-o", at("again.png"), "--float", at("linear.exr")})).code ==
          0);
  CHECK(read_bytes(at("linear.exr")) == first);
  // The scene's own output.float_image may name an EXR; other extensions are refused.
  REQUIRE(run(with_scene({"render", "-o", at("s.png"), "--set",
                          test::concat({"output.float_image=", at("scene.exr")})}))
              .code == 0);
  check_same_floats(at("scene.exr"), at("linear.pfm"));
  test::require_refused(run(with_scene({"render", "-o", at("x.png"), "--float", at("x.tif")})),
                        "ending in .pfm or .exr", at("x.png"));
  test::require_refused(run(with_scene({"scene", "--set", "output.float_image=x.jpg"})),
                        ".pfm or .exr", at("x.jpg"));
}

TEST_CASE("stagesWriteExrBuffersOnRequest", "[float_output]") {
  test::TempDir dir("stages-exr");
  const std::string pfm = (dir.path() / "pfm").string(), exr = (dir.path() / "exr").string();
  REQUIRE(run(with_scene({"stages", "--out", pfm})).code == 0);
  const CliResult r = run(with_scene({"stages", "--out", exr, "--float-format", "exr"}));
  INFO(r.err);
  REQUIRE(r.code == 0);
  const nlohmann::json manifest =
      nlohmann::json::parse(std::ifstream(std::filesystem::path(exr) / "stages.json"));
  for (const char* name : {"domain", "sigma", "nu", "height", "normal", "slope", "water_depth"}) {
    CHECK(manifest["files"][name]["raw"] == std::string(name) + ".exr");
    CHECK_FALSE(std::filesystem::exists(std::filesystem::path(exr) / (std::string(name) + ".pfm")));
    check_same_floats(std::filesystem::path(exr) / (std::string(name) + ".exr"),
                      std::filesystem::path(pfm) / (std::string(name) + ".pfm"));
  }
  test::require_refused(
      run({"stages", "--out", (dir.path() / "x").string(), "--float-format", "tiff"}),
      "--float-format", dir.path() / "x");
}

// OpenImageIO reads the text chunks Relief inserts into stb's PNG as attributes, with the
// pixels unchanged, and idiff reads the file.
TEST_CASE("openImageIoReadsTheMetadataOfReliefsPng", "[float_output]") {
  test::TempDir dir("png-oiio");
  const std::filesystem::path png = dir.path() / "r.png";
  REQUIRE(run(with_scene({"render", "-o", png.string()})).code == 0);
  const OiioImage image = read_with_oiio(png);
  const Scene scene = resolve_scene("", kSmallFloatFrame);
  CHECK(image.spec.get_string_attribute("Software") == test::concat({"relief ", relief_version()}));
  const std::string text = image.spec.get_string_attribute(std::string(kSceneKey));
  CHECK(nlohmann::json::parse(text) == scene_to_json(scene));
  // The same pixels as stb decodes (the PNG encoder's own reader in the library's tests).
  const std::vector<unsigned char> bytes = read_bytes(png);
  int w = 0, h = 0, n = 0;
  unsigned char* pixels = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &n, 3);
  REQUIRE(pixels != nullptr);
  for (std::size_t k = 0; k < image.pixels.size(); ++k) {
    REQUIRE(std::lround(image.pixels[k] * 255.0f) == pixels[k]);
  }
  stbi_image_free(pixels);
  const test::ToolRun idiff = test::run_idiff(png, png, {});
  INFO(idiff.out);
  CHECK(idiff.code == 0);
  CHECK_THAT(idiff.out, Catch::Matchers::Contains("PASS"));
}

}  // namespace
}  // namespace relief
