// terrain.heightfield's files from the command line (pipeline/heightfield_files.h): hostile
// files refused naming the field, and EXR and TIFF read through the image module as a PFM is.
#include <sys/stat.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/height_sketch.h"
#include "pipeline/heightfield_files.h"
#include "tests/support/cli_support.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/test_support.h"
#include "tools/float_image_file.h"
#include "tools/image_library.h"

namespace relief {
namespace {

using test::concat;
using test::require_refused;
using test::run;

HeightFieldSettings settings_for(const std::string& file) {
  HeightFieldSettings s;
  s.image = file;
  s.extent = {-1000.0, -1000.0, 1000.0, 1000.0};
  s.height = {-200.0, 800.0};
  return s;
}

TEST_CASE("hostileHeightfieldFilesAreRefusedNamingTheField", "[heightfield]") {
  test::TempDir dir("heightfield-hostile");
  const std::filesystem::path out = dir.path() / "out.png";
  const auto scene_with = [&](const std::string& file, const std::string& more = "") {
    return test::write_file(
        dir.path() / "scene.json",
        concat({R"({"grid": {"width": 48, "height": 48}, "viewport": {"width": 48, "height": 32},
                   "terrain": {"heightfield": {"file": ")",
                file, R"(", "extent": [-1000, -1000, 1000, 1000])", more, "}}}"}));
  };
  const auto refused = [&](const std::string& file, const std::string& message,
                           const std::string& more = "") {
    INFO(file << ": " << message);
    require_refused(run({"render", scene_with(file, more), "-o", out.string()}), message, out);
  };
  const std::vector<float> ramp = {0.0f, 0.25f, 0.5f, 0.75f, 0.125f, 0.375f};
  const auto pfm = [&](const std::string& name, const std::string& bytes) {
    return test::write_file(dir.path() / name, bytes);
  };
  const std::string good = pfm("good.pfm", test::pfm_bytes(3, 2, ramp));
  refused(test::write_file(dir.path() / "f.jpg", "x"), "terrain.heightfield.file = \"" +
                                                           (dir.path() / "f.jpg").string() +
                                                           "\" has no height format's extension");
  refused((dir.path() / "missing.pfm").string(), "terrain.heightfield.file");
  refused("builtin:island", "names a built-in image; allowed: a file");
  std::filesystem::create_directories(dir.path() / "folder.png");
  refused((dir.path() / "folder.png").string(), "not a regular file");
  refused(pfm("rgb.pfm", test::pfm_bytes(3, 2, ramp, true, "PF")), "is a three-channel PFM (PF)");
  refused(pfm("junk.pfm", "Pf\n3 x\n-1\n"), "has a malformed PFM header");
  refused(pfm("zero.pfm", "Pf\n3 2\n0\n"), "has a malformed PFM header");
  refused(pfm("noend.pfm", "Pf\n3 2\n-1"), "has a malformed PFM header \"Pf 3 2 -1\"");
  refused(pfm("padded.pfm", "Pf\n3 2" + std::string(200, ' ') + "\n-1\n"),
          "all within the first 128 bytes");
  const std::string crlf_samples =
      test::pfm_bytes(3, 2, ramp).substr(12);  // after "Pf\n3 2\n-1.0\n"
  refused(pfm("crlf.pfm", "Pf\r\n3 2\r\n-1.0\r\n" + crlf_samples),
          "ends its PFM header with CR LF");
  // A header that promises more than the file holds is refused from the file's size, before
  // any sample is allocated: not as a memory problem.
  require_refused(
      run({"render",
           scene_with(pfm("short.pfm", "Pf\n16385 16385\n-1.0\n" + std::string(16, '\0'))),
           "--max-memory", "1G", "-o", out.string()}),
      "its header (16385x16385) asks for exactly", out);
  const std::string whole = test::pfm_bytes(3, 2, ramp);
  refused(pfm("cut.pfm", whole.substr(0, whole.size() - 3)), "its header (3x2) asks for exactly");
  refused(pfm("long.pfm", whole + "extra"), "its header (3x2) asks for exactly");
  refused(pfm("thin.pfm", test::pfm_bytes(1, 3, {0, 0, 0})),
          "is 1x3 samples; allowed 2 to 16385 on each side");
  refused(pfm("huge.pfm", "Pf\n20000 20000\n-1\n"), "is 20000x20000 samples");
  std::vector<float> holes = ramp;
  holes[4] = std::numeric_limits<float>::quiet_NaN();
  refused(pfm("nan.pfm", test::pfm_bytes(3, 2, holes)), "has sample nan at column 1, row 1");
  holes[4] = std::numeric_limits<float>::infinity();
  refused(pfm("inf.pfm", test::pfm_bytes(3, 2, holes)), "has sample inf at column 1, row 1");
  holes[4] = 2e7f;
  refused(pfm("tall.pfm", test::pfm_bytes(3, 2, holes)), "world height 2e+07",
          R"(, "height": [0, 1])");
  refused(test::write_file(dir.path() / "odd.r16", std::string(9, '\1')),
          "is 9 bytes, not a whole number of 16-bit samples");
  refused(test::write_file(dir.path() / "six.raw", std::string(12, '\1')),
          "holds 6 samples, not a square number; give terrain.heightfield.raw_width");
  refused(test::write_file(dir.path() / "rows.raw", std::string(12, '\1')),
          "terrain.heightfield.raw_width = 4 does not divide the 6 samples", R"(, "raw_width": 4)");
  refused(good, "terrain.heightfield.raw_width = 3 is for RAW16 files", R"(, "raw_width": 3)");
  refused(test::write_file(dir.path() / "one.raw", std::string(2, '\1')),
          "is 1x1 samples; allowed 2 to 16385");
  std::string header("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\x40\x02\0\0\0\x10\x10\0\0\0\0\0\0\0\0",
                     33);  // 16386 x 16, 16-bit grey: refused from the header alone
  refused(test::write_file(dir.path() / "wide.png", header), "is 16386x16 samples");
  header[25] = 2;  // RGB
  header[19] = 0x10, header[18] = 0;
  refused(test::write_file(dir.path() / "rgb.png", header), "has colour type 2");
  refused(good, "terrain.heightfield.height = [5,5] is empty", R"(, "height": [5, 5])");
  // One of sketch and heightfield; a new heightfield names its file.
  require_refused(run({"render", scene_with(good), "--set",
                       "terrain.sketch={\"image\":\"builtin:island\"}", "-o", out.string()}),
                  "terrain.heightfield and terrain.sketch are both given", out);
  require_refused(
      run({"render", "--set", "terrain.heightfield={\"extent\":[0,0,1,1]}", "-o", out.string()}),
      "terrain.heightfield must be null or an object with at least a \"file\"", out);
  // A field too large for the memory given is refused before it is read, naming the remedy.
  header[25] = 0;
  header[16] = 0, header[17] = 0, header[18] = 0x40, header[19] = 0x01;  // 16385 wide
  header[20] = 0, header[21] = 0, header[22] = 0x40, header[23] = 0x01;  // 16385 high
  const std::string giant = test::write_file(dir.path() / "giant.png", header);
  require_refused(run({"render", scene_with(giant), "--max-memory", "1G", "-o", out.string()}),
                  "The height field dominates: use a smaller terrain.heightfield.file", out);
  // Interpolating coefficients of an alternating field overshoot it (core/field_prefilter.h):
  // beyond +-1e7 they are refused; within, the field renders.
  std::vector<float> checker(64);
  for (std::size_t k = 0; k < checker.size(); ++k) {
    checker[k] = float(((k % 8) + (k / 8)) % 2);
  }
  const std::string board = pfm("board.pfm", test::pfm_bytes(8, 8, checker));
  refused(board, "needs coefficients up to", R"(, "height": [-5e6, 5e6], "interpolating": true)");
  CHECK(run({"render", scene_with(board, R"(, "height": [-5e5, 5e5], "interpolating": true)"), "-o",
             out.string()})
            .code == 0);
  std::filesystem::remove(out);
  // The good file renders.
  CHECK(run({"render", scene_with(good), "-o", out.string()}).code == 0);
}

TEST_CASE("exrAndTiffHeightfieldsGiveThePfmsHeights", "[heightfield]") {
  install_height_field_image_reader();  // as run_cli does: the library alone reads neither
  test::TempDir dir("heightfield-images");
  constexpr int kW = 7, kH = 5;
  std::vector<float> top_first(kW * kH), bottom_first(kW * kH);
  test::TestRandom rng(3);
  for (float& v : top_first) {
    v = float(rng.uniform(-0.5, 1.5));
  }
  for (int j = 0; j < kH; ++j) {
    for (int i = 0; i < kW; ++i) {
      bottom_first[std::size_t((kH - 1 - j) * kW + i)] = top_first[std::size_t(j * kW + i)];
    }
  }
  const std::string pfm =
      test::write_file(dir.path() / "f.pfm", test::pfm_bytes(kW, kH, top_first));
  const std::vector<unsigned char> exr_bytes =
      encode_float_image(FloatFormat::kExr, kW, kH, 1, bottom_first, kW, {});
  const std::string exr =
      test::write_file(dir.path() / "f.exr", std::string(exr_bytes.begin(), exr_bytes.end()));
  // A float TIFF by OpenImageIO's own tool (openimageio-tools, a dependency of the build).
  const std::string tif = (dir.path() / "f.tif").string();
  REQUIRE(std::system(concat({"oiiotool '", pfm, "' -d float -o '", tif, "'"}).c_str()) == 0);
  const HeightSketch expected = load_height_field(settings_for(pfm));
  for (const std::string& file : {exr, tif}) {
    INFO(file);
    const HeightSketch field = load_height_field(settings_for(file));
    REQUIRE(field.width == kW);
    REQUIRE(field.height == kH);
    CHECK(field.heights == expected.heights);
  }
  // Hostile images: three channels, not an image, a FIFO (refused before the module opens it).
  const std::filesystem::path out = dir.path() / "out.png";
  const auto scene_with = [&](const std::string& file) {
    return test::write_file(
        dir.path() / "scene.json",
        concat({R"({"grid": {"width": 48, "height": 48}, "viewport": {"width": 48, "height": 32},
                   "terrain": {"heightfield": {"file": ")",
                file, R"(", "extent": [-1000, -1000, 1000, 1000]}}})"}));
  };
  std::vector<float> rgb(std::size_t(kW * kH * 3), 0.5f);
  const std::vector<unsigned char> rgb_bytes =
      encode_float_image(FloatFormat::kExr, kW, kH, 3, rgb, std::size_t(kW) * 3, {});
  const std::string rgb_exr =
      test::write_file(dir.path() / "rgb.exr", std::string(rgb_bytes.begin(), rgb_bytes.end()));
  require_refused(run({"render", scene_with(rgb_exr), "-o", out.string()}),
                  "has 3 channels; allowed: one", out);
  require_refused(
      run({"render", scene_with(test::write_file(dir.path() / "junk.tif", "not a tiff")), "-o",
           out.string()}),
      "could not be read as an image", out);
  const std::string fifo = (dir.path() / "pipe.exr").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  require_refused(run({"render", scene_with(fifo), "-o", out.string()}), "not a regular file", out);
  // The extension names the format; a TIFF cut short is refused, not read as zeros.
  require_refused(run({"render",
                       scene_with(test::write_file(dir.path() / "png.exr",
                                                   "P5\n2 2\n255\n" + std::string(4, '\1'))),
                       "-o", out.string()}),
                  "could not be read as an image", out);
  const std::vector<unsigned char> tif_bytes = test::read_bytes(tif);
  const std::string cut = test::write_file(
      dir.path() / "cut.tif",
      std::string(tif_bytes.begin(), tif_bytes.begin() + std::ptrdiff_t(tif_bytes.size() - 40)));
  require_refused(run({"render", scene_with(cut), "-o", out.string()}),
                  "could not be read as an image", out);
  // Levels of detail are for a field without the fractal.
  require_refused(run({"render", scene_with(exr), "--set", "terrain.heightfield.fractal=true",
                       "--set", "terrain.heightfield.level_of_detail=true", "-o", out.string()}),
                  "terrain.heightfield.level_of_detail = true with terrain.heightfield.fractal",
                  out);
  CHECK(run({"render", scene_with(exr), "-o", out.string()}).code == 0);
}

}  // namespace
}  // namespace relief
