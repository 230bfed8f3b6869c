// terrain.basis from outside (§3 Eq. 2): the scene field's strict checks and every way an image
// file can be refused, through the command line (exit 2, the field named, nothing written),
// and the notes an image that does not tile gets.
#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <vector>

#include <stb_image_write.h>
#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::concat;
using test::require_refused;
using test::run;

std::string write_grey(const std::filesystem::path& path, int width, int height,
                       const std::vector<unsigned char>& grey, int channels = 1) {
  std::vector<unsigned char> pixels;
  for (const unsigned char g : grey) {
    pixels.insert(pixels.end(), std::size_t(channels), g);
  }
  REQUIRE(stbi_write_png(path.string().c_str(), width, height, channels, pixels.data(),
                         width * channels) != 0);
  return path.string();
}

// A side x side ramp along x (8-bit grey): it does not tile.
std::string write_ramp(const std::filesystem::path& path, int side) {
  std::vector<unsigned char> grey;
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      grey.push_back(static_cast<unsigned char>(x * 255 / (side - 1)));
    }
  }
  return write_grey(path, side, side, grey);
}

std::string quoted(const std::string& s) {
  return concat({"\"", s, "\""});
}

// `--set terrain.basis=...` with one image (and its weight) on the small craters preset.
std::vector<std::string> one_image(const std::string& image, const std::string& weight = "1",
                                   const std::string& more = "") {
  return {concat({"terrain.basis={\"images\": [{\"image\": ", quoted(image),
                  ", \"weight\": ", weight, more, "}]}"})};
}

// A 32 x 32 render of a 16 x 16 grid: the refusals and notes do not need more.
const std::vector<std::string> kSmallBasisFrame = {
    "--set", "viewport.width=32", "--set", "viewport.height=32",
    "--set", "grid.width=16",     "--set", "grid.height=16"};

struct Refusals {
  std::filesystem::path out;
  void operator()(const std::vector<std::string>& sets, const std::string& message) const {
    INFO(message);
    require_refused(test::render_preset("craters", sets, out, kSmallBasisFrame), message, out);
  }
};

TEST_CASE("basisFieldsAreCheckedNamingTheFieldAndTheRange", "[basis]") {
  test::TempDir dir("basis-fields");
  const Refusals refused{dir.path() / "out.png"};
  refused({"terrain.basis.tile_size=0"}, "terrain.basis.tile_size = 0 is out of range; allowed");
  refused({"terrain.basis.tile_size=1e10"}, "terrain.basis.tile_size = 1e+10 is out of range");
  refused({"terrain.basis.tile_size=1", "camera.far=1e6"},
          "terrain.basis.tile_size = 1 puts the farthest footprint beyond");
  refused({"terrain.basis.wrap=\"clamp\""},
          "terrain.basis.wrap = \"clamp\" is not allowed; "
          "allowed: repeat, mirror");
  refused({"terrain.basis.images=[]"}, "terrain.basis.images = [] must be an array of 1 to 4");
  refused({"terrain.basis.images=[{\"image\":\"a\"},{\"image\":\"a\"},{\"image\":\"a\"},"
           "{\"image\":\"a\"},{\"image\":\"a\"}]"},
          "terrain.basis.images");
  refused({"terrain.basis.images=[{\"weight\": 1}]"},
          "terrain.basis.images[0] = {\"weight\":1} must be an object with at least an \"image\"");
  // One rule and one message whichever side is crossed, naming the least non-zero weight.
  const std::string allowed =
      " is out of range; allowed 0, or 1e-06 <= terrain.basis.images[0].weight <= 1e+06, or a "
      "grey PNG's path";
  refused(one_image("builtin:basis/craters", "-0.5"),
          "terrain.basis.images[0].weight = -0.5" + allowed);
  refused(one_image("builtin:basis/craters", "2e6"),
          "terrain.basis.images[0].weight = 2e+06" + allowed);
  refused(one_image("builtin:basis/craters", "true"), "terrain.basis.images[0].weight");
  // A subnormal weight once made Eq. 2's products round to garbage.
  refused(one_image("builtin:basis/craters", "5e-324"),
          "terrain.basis.images[0].weight = 5e-324" + allowed);
  refused(one_image("builtin:basis/craters", "1e-7"),
          "terrain.basis.images[0].weight = 1e-07" + allowed);
  refused({"terrain.basis.upsample=3"},
          "terrain.basis.upsample = 3 is not a power of two; allowed 1, 2, 4 or 8");
  refused({"terrain.basis.upsample=16"}, "terrain.basis.upsample = 16 is out of range");
  refused(one_image("builtin:basis/craters", "0"),
          "every terrain.basis.images[k].weight is 0, so the weights sum to 0 everywhere; "
          "allowed: each weight 0, or 1e-06 to 1e+06");
  refused(one_image("builtin:basis/craters", "1", ", \"low_pass\": -1"),
          "terrain.basis.images[0].low_pass = -1 is out of range");
  refused(one_image("builtin:basis/craters", "1", ", \"high_pass\": 200"),
          "terrain.basis.images[0].high_pass = 200 texels is more than half the grid's side 256");
  refused(one_image("builtin:basis/craters", "1", ", \"normalize\": 1"),
          "terrain.basis.images[0].normalize = 1 is not a boolean");
  refused(one_image("builtin:basis/craters", "1", ", \"blur\": 1"),
          "unknown key 'terrain.basis.images[0].blur'");
  refused(one_image("builtin:basis/nothing"),
          "terrain.basis.images[0].image = "
          "\"builtin:basis/nothing\" names no built-in");
  refused(one_image("builtin:island"), "names no built-in basis image");
  // A new basis must list its images; null removes it.
  refused({"terrain.basis=null", "terrain.basis={\"tile_size\": 5}"},
          "terrain.basis must be null or an object with at least \"images\"");
  CHECK_FALSE(resolve_scene("craters", {"terrain.basis=null"}).terrain.basis);
}

TEST_CASE("badBasisImagesAreRefusedNamingTheFieldWithNothingWritten", "[basis]") {
  test::TempDir dir("basis-files");
  const Refusals refused{dir.path() / "out.png"};
  const std::string good = write_ramp(dir.path() / "good.png", 16);
  const auto image = [&](const std::string& file) { return one_image(file); };
  const auto weight = [&](const std::string& file) { return one_image(good, quoted(file)); };
  refused(image((dir.path() / "missing.png").string()), "terrain.basis.images[0].image");
  refused(weight((dir.path() / "missing.png").string()), "terrain.basis.images[0].weight");
  refused(image(dir.path().string()), "is a directory");
  const std::string fifo = (dir.path() / "fifo").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  refused(weight(fifo), "terrain.basis.images[0].weight");
  refused(image("/dev/zero"), "is a character device, not a regular file");
  const std::string large = write_ramp(dir.path() / "large.png", 1024);
  refused(
      {concat({"terrain.basis={\"upsample\": 8, \"images\": [{\"image\": ", quoted(large), "}]}"})},
      "terrain.basis.upsample = 8 refines the 1024-texel grid to 8192 texels a side, more "
      "than 4096; allowed terrain.basis.upsample <= 4 for this grid");
  refused(image(test::write_file(dir.path() / "text.png", "not a png at all, but long enough!")),
          "terrain.basis.images[0].image = ");
  refused(image(test::write_file(dir.path() / "text.png", "not a png at all, but long enough!")),
          "is not a PNG image");
  const std::vector<unsigned char> grey(16 * 16, 90);
  refused(image(write_grey(dir.path() / "rgb.png", 16, 16, grey, 3)),
          "has colour type 2 (RGB); allowed: a grey PNG with one channel");
  refused(weight(write_grey(dir.path() / "ga.png", 16, 16, grey, 2)),
          "terrain.basis.images[0].weight = ");
  refused(weight(write_grey(dir.path() / "ga.png", 16, 16, grey, 2)),
          "has colour type 4 (grey + alpha)");
  refused(image(write_grey(dir.path() / "wide.png", 16, 8, std::vector<unsigned char>(128, 1))),
          "is 16x8 texels; allowed: square, a power of two from 4 to 4096");
  refused(image(write_grey(dir.path() / "odd.png", 12, 12, std::vector<unsigned char>(144, 1))),
          "is 12x12 texels");
  refused(image(write_grey(dir.path() / "tiny.png", 2, 2, {1, 2, 3, 4})), "is 2x2 texels");
  // A header alone: 4-bit grey, and a 4096 side under mirror (8192 once mirrored).
  std::string header("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\0\x10\0\0\0\x10\x04\0\0\0\0\0\0\0\0", 33);
  refused(image(test::write_file(dir.path() / "four.png", header)),
          "has 4 bits per channel; allowed: 8 or 16");
  header[18] = header[22] = 0x10, header[19] = header[23] = 0, header[24] = 8;  // 4096 x 4096
  std::vector<std::string> mirrored = image(test::write_file(dir.path() / "big.png", header));
  mirrored.push_back("terrain.basis.wrap=\"mirror\"");
  refused(mirrored, "is 4096x4096 texels; allowed: square, a power of two from 4 to 2048");
  // Sizes that differ, between two images and between an image and its weight.
  const std::string small = write_ramp(dir.path() / "small.png", 8);
  refused(weight(small), "terrain.basis.images[0].weight = ");
  refused(weight(small), "is 8x8 texels, but terrain.basis.images[0].image is 16x16");
  refused({concat({"terrain.basis={\"images\": [{\"image\": ", quoted(good),
                   "}, {\"image\": ", quoted(small), "}]}"})},
          "terrain.basis.images[1].image = ");
  // Weights summing to zero at one texel: the weight image is black there.
  std::vector<unsigned char> holes(16 * 16, 255);
  holes[7 * 16 + 9] = 0;
  refused(weight(write_grey(dir.path() / "holes.png", 16, 16, holes)),
          "terrain.basis.images: the weights sum to 0 at texel (9, 7)");
  // A constant image cannot be normalized.
  refused(
      one_image(write_grey(dir.path() / "flat.png", 16, 16, grey), "1", ", \"normalize\": true"),
      "terrain.basis.images[0].image cannot be normalized: its variance is 0");
}

TEST_CASE("anImageThatDoesNotTileIsNotedWithItsSeamMeasureAndMirrorSilencesIt", "[basis]") {
  test::TempDir dir("basis-seam");
  const std::string ramp = write_ramp(dir.path() / "ramp.png", 16);
  const std::filesystem::path out = dir.path() / "out.png";
  const auto render = [&](const std::vector<std::string>& sets) {
    return test::render_preset("craters", sets, out, kSmallBasisFrame);
  };
  const test::CliResult repeat = render(one_image(ramp));
  CHECK(repeat.code == 0);
  CHECK_THAT(repeat.err, Catch::Contains("relief: note: terrain.basis.images[0].image = "));
  CHECK_THAT(repeat.err, Catch::Contains("does not tile: its seam measure is 15"));
  CHECK_THAT(repeat.err, Catch::Contains("terrain.basis.wrap = \"mirror\""));
  std::vector<std::string> mirror = one_image(ramp);
  mirror.push_back("terrain.basis.wrap=\"mirror\"");
  const test::CliResult mirrored = render(mirror);
  CHECK(mirrored.code == 0);
  CHECK(mirrored.err.find("does not tile") == std::string::npos);
  // The shipped presets tile and say nothing; horizontal_scale, unused, is noted when set.
  CHECK(render({}).err.empty());
  const test::CliResult scaled = render({"terrain.horizontal_scale=500"});
  CHECK(scaled.code == 0);
  // craters: 256-texel images refined 4 times, so P = 1024 and the cell 8000 / 1024.
  CHECK_THAT(scaled.err, Catch::Contains("terrain.horizontal_scale = 500 is not used with "
                                         "terrain.basis: the octave-0 cell is "
                                         "terrain.basis.tile_size / P = 8000 / 1024 = 7.8125 "
                                         "world units, P the composed grid's side (256-texel "
                                         "images, refined 4 times)"));
  // A 16-texel image mirrored, with the preset's refinement: P = 16 x 2 x 4.
  std::vector<std::string> mirrored_scaled = one_image(ramp);
  mirrored_scaled.push_back("terrain.basis.wrap=\"mirror\"");
  mirrored_scaled.push_back("terrain.horizontal_scale=500");
  const test::CliResult small = render(mirrored_scaled);
  CHECK(small.code == 0);
  CHECK_THAT(small.err, Catch::Contains("the octave-0 cell is terrain.basis.tile_size / P = "));
  CHECK_THAT(small.err, Catch::Contains(" = 8000 / 128 = 62.5 world units"));
  CHECK_THAT(small.err, Catch::Contains("(16-texel images, mirrored, refined 4 times)"));
}

// The stress suite on a basis preset: its cases that set the octave-0 cell through
// horizontal_scale expect basis mode's own rule instead (stress_cases.cc).
TEST_CASE("theStressSuiteRunsOnABasisPreset", "[basis][stress]") {
  const test::CliResult r = test::run({"stress", "craters", "--axis", "octaves", "--backend",
                                       "simd", "--viewport", "32", "24", "--grid", "16"});
  INFO(r.out << r.err);
  CHECK(r.code == 0);
}

}  // namespace
}  // namespace relief
