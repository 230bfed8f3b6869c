// The metadata Relief's images carry (image/image_metadata.h): text chunks inserted into the
// PNG that stb_image_write made (image/png_text.h), with a CRC-32 of their own
// (image/crc32.h). Read back here by Relief's own chunk reader and by stb; OpenImageIO and
// idiff read them in tests/eval/compare_test.cc.
#include <cstring>
#include <string>
#include <vector>

#include <stb_image.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "image/crc32.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "image/png_text.h"
#include "pipeline/build_info.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::read_bytes;
using test::run;

std::span<const unsigned char> bytes_of(std::string_view text) {
  return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

// A small picture with every byte different from its neighbours.
std::vector<std::uint8_t> test_pixels(int width, int height) {
  std::vector<std::uint8_t> rgb(std::size_t(width) * std::size_t(height) * 3);
  for (std::size_t k = 0; k < rgb.size(); ++k) {
    rgb[k] = static_cast<std::uint8_t>((k * 37 + k / 7) & 0xff);
  }
  return rgb;
}

// The pixels stb decodes, as RGB bytes top row first.
std::vector<std::uint8_t> decode(const std::vector<unsigned char>& png) {
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3);
  REQUIRE(pixels != nullptr);
  std::vector<std::uint8_t> out(pixels, pixels + std::size_t(w) * std::size_t(h) * 3);
  stbi_image_free(pixels);
  return out;
}

// The chunk types of a PNG in file order.
std::vector<std::string> chunk_types(const std::vector<unsigned char>& png) {
  std::vector<std::string> types;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::size_t length = std::size_t(png[at]) << 24 | std::size_t(png[at + 1]) << 16 |
                               std::size_t(png[at + 2]) << 8 | std::size_t(png[at + 3]);
    types.emplace_back(png.begin() + std::ptrdiff_t(at) + 4, png.begin() + std::ptrdiff_t(at) + 8);
    at += length + 12;
  }
  return types;
}

TEST_CASE("crc32GivesTheStandardCheckValue", "[png_text]") {
  // The check value of CRC-32/ISO-HDLC, the CRC PNG uses (ISO/IEC 15948 Annex D).
  CHECK(crc32(bytes_of("123456789")) == 0xCBF43926u);
  CHECK(crc32(bytes_of("")) == 0u);
  // Fed in two parts, as a chunk's type and data are.
  CHECK(crc32(bytes_of("6789"), crc32(bytes_of("12345"))) == 0xCBF43926u);
  // IEND's CRC, which every PNG file ends with.
  CHECK(crc32(bytes_of("IEND")) == 0xAE426082u);
}

TEST_CASE("textChunksGoRightAfterIhdrAndLeaveThePixelsAlone", "[png_text]") {
  const std::vector<std::uint8_t> rgb = test_pixels(13, 7);
  const std::vector<unsigned char> bare = encode_png_rgb(13, 7, rgb);
  const std::vector<ImageText> text = {{"Software", "relief 0.1.0"},
                                       {"relief:scene", "{\"layer\": \"n\xc3\xa9v\xc3\xa9\"}"}};
  const std::vector<unsigned char> png = encode_png_rgb(13, 7, rgb, text);
  // ASCII text as tEXt, UTF-8 as iTXt, both before every chunk stb wrote.
  std::vector<std::string> expected = chunk_types(bare);
  expected.insert(expected.begin() + 1, {"tEXt", "iTXt"});
  CHECK(chunk_types(png) == expected);
  // Every other byte is stb's.
  const std::size_t after_ihdr = 8 + 25;
  CHECK(std::equal(bare.begin(), bare.begin() + after_ihdr, png.begin()));
  CHECK(std::equal(bare.begin() + after_ihdr, bare.end(),
                   png.end() - std::ptrdiff_t(bare.size() - after_ihdr)));
  CHECK(decode(png) == decode(bare));
  // Rows top first in the file, bottom first in Relief's buffers.
  const std::vector<std::uint8_t> pixels = decode(png);
  CHECK(std::equal(pixels.begin(), pixels.begin() + 13 * 3, rgb.end() - 13 * 3));

  const std::vector<ImageText> read = read_png_text(png);
  REQUIRE(read.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(read[k].keyword == text[k].keyword);
    CHECK(read[k].text == text[k].text);
  }
}

TEST_CASE("aChunkWithABadCrcIsNotRead", "[png_text]") {
  const std::vector<ImageText> text = {{"Comment", "hello"}};
  std::vector<unsigned char> png = encode_png_rgb(2, 2, test_pixels(2, 2), text);
  REQUIRE(read_png_text(png).size() == 1);
  png[8 + 25 + 8] ^= 1;  // the first byte of the tEXt chunk's data
  CHECK(read_png_text(png).empty());
}

TEST_CASE("keywordsAndTextsNoPngReaderAcceptsAreRefused", "[png_text]") {
  const std::vector<unsigned char> png = encode_png_rgb(2, 2, test_pixels(2, 2));
  for (const ImageText& bad : std::vector<ImageText>{{"", "x"},
                                                     {std::string(80, 'k'), "x"},
                                                     {" lead", "x"},
                                                     {"trail ", "x"},
                                                     {"two  spaces", "x"},
                                                     {"tab\there", "x"},
                                                     {"nul", std::string("a\0b", 3)}}) {
    INFO(bad.keyword);
    CHECK_THROWS_AS(insert_png_text(png, std::vector<ImageText>{bad}), PngTextError);
  }
  CHECK_THROWS_AS(insert_png_text(bytes_of("not a png at all, not at all, no"), {}), PngTextError);
}

// Every PNG relief writes names the software; those of a scene carry the scene, whose JSON
// loads back to the same scene, and their pixels are the PNG of the image without the text.
TEST_CASE("everyPngReliefWritesCarriesTheSoftwareAndItsScene", "[png_text]") {
  test::TempDir dir("png-text");
  const std::vector<std::string> overrides = {"viewport.width=40", "viewport.height=30",
                                              "grid.width=24", "grid.height=24",
                                              "shading.layers.0.name=b\xc3\xa9"
                                              "d"};
  std::vector<std::string> args = {"render", "-o", (dir.path() / "r.png").string()};
  std::vector<std::string> stage_args = {"stages", "--out", (dir.path() / "s").string()};
  for (const std::string& o : overrides) {
    args.insert(args.end(), {"--set", o});
    stage_args.insert(stage_args.end(), {"--set", o});
  }
  REQUIRE(run(args).code == 0);
  REQUIRE(run(stage_args).code == 0);
  const Scene scene = resolve_scene("", overrides);
  const std::string software = test::concat({"relief ", relief_version()});
  for (const std::string name : {"r.png", "s/height.png", "s/domain.png", "s/normal.png"}) {
    INFO(name);
    const std::vector<unsigned char> png = read_bytes(dir.path() / name);
    const std::vector<ImageText> text = read_png_text(png);
    REQUIRE(text.size() == 2);
    CHECK(text[0].keyword == kSoftwareKey);
    CHECK(text[0].text == software);
    CHECK(text[1].keyword == kSceneKey);
    CHECK(text[1].text == scene_json_text(scene));
    Scene reloaded;
    apply_scene_layer(reloaded, nlohmann::json::parse(text[1].text), "round trip");
    CHECK(scene_to_json(reloaded) == scene_to_json(scene));
    // A UTF-8 layer name makes the scene an iTXt chunk.
    CHECK(chunk_types(png)[2] == "iTXt");
  }
  // The render's pixels are those of the PNG without metadata.
  const std::vector<unsigned char> png = read_bytes(dir.path() / "r.png");
  std::vector<std::uint8_t> bottom_first = decode(png);
  for (int j = 0; j < 15; ++j) {
    std::swap_ranges(bottom_first.begin() + j * 120, bottom_first.begin() + (j + 1) * 120,
                     bottom_first.begin() + (29 - j) * 120);
  }
  CHECK(decode(encode_png_rgb(40, 30, bottom_first)) == decode(png));

  // A soup has no scene: its picture names the software alone.
  const std::string soup =
      test::write_file(dir.path() / "soup.txt", "4 4\n0 0 0.5 4 0 0.5 0 4 0.5\n");
  REQUIRE(run({"raster", soup, "--out", (dir.path() / "soup").string()}).code == 0);
  const std::vector<ImageText> coverage =
      read_png_text(read_bytes(dir.path() / "soup.coverage.png"));
  REQUIRE(coverage.size() == 1);
  CHECK(coverage[0].keyword == kSoftwareKey);
  CHECK(coverage[0].text == software);
}

}  // namespace
}  // namespace relief
