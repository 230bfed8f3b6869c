// Inputs the fuzzers (fuzz/) found to crash, hang or exhaust memory, each through the normal
// API with the clean exit-2 error it now gets. The inputs are files under fuzz/regressions/.
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "pipeline/scene_resources.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using Catch::Matchers::Contains;

const std::filesystem::path kRegressions =
    std::filesystem::path(RELIEF_SOURCE_DIR) / "fuzz" / "regressions";

// The SceneError that loading `file` as layer 2's texture throws, as `relief render` loads it.
std::string texture_error(const std::filesystem::path& file) {
  MaterialLayer layer;
  layer.texture = file.string();
  try {
    load_layer_texture(layer, 16, "shading.layers[2].texture");
  } catch (const SceneError& e) {
    CHECK(e.path() == "shading.layers[2].texture");
    return e.what();
  }
  FAIL("expected a SceneError for " << file);
  return "";
}

// Found by relief_fuzz_texture: a 73-byte PNG whose second IDAT chunk claims 1.3 GB. stb_image
// grew its buffer to 2 GiB for it before finding the data missing.
TEST_CASE("aTextureChunkLongerThanTheFileIsRefusedBeforeDecoding", "[fuzz][hostile]") {
  const std::filesystem::path file = kRegressions / "texture_chunk_length_past_end.png";
  REQUIRE(std::filesystem::file_size(file) == 73);
  const std::string message = texture_error(file);
  CHECK_THAT(message, Contains("shading.layers[2].texture = \""));
  CHECK_THAT(message, Contains("could not be decoded: chunk IDAT at byte 57 has 1314062348 data "
                               "bytes, but only 4 follow (the file is truncated)"));
}

// Found while fixing the above: stb_image inflates image data for as long as the deflate
// stream goes on (to 4 GiB), whatever the header says. Here 1 MiB from 1 KiB of file for a 4x4
// texture that needs 52 bytes.
TEST_CASE("aTextureWhoseDataInflatesPastItsHeaderIsRefused", "[fuzz][hostile]") {
  const std::string message = texture_error(kRegressions / "texture_inflates_past_header.png");
  CHECK_THAT(message, Contains("could not be decoded: its image data inflates to more than the 52 "
                               "bytes its 4x4 header gives"));
}

// Found by relief_fuzz_texture: a zero-length IDAT chunk before any image data makes stb_image
// call memcpy with a null destination (UBSan: "null pointer passed as argument 1").
TEST_CASE("anEmptyFirstImageDataChunkIsRefusedBeforeDecoding", "[fuzz][hostile]") {
  const std::string message = texture_error(kRegressions / "texture_empty_first_idat.png");
  CHECK_THAT(message, Contains("could not be decoded: chunk IDAT at byte 33 is empty and comes "
                               "before the image data"));
}

// The same through the command line: exit code 2, nothing written.
TEST_CASE("fuzzFoundTexturesEndWithExitCodeTwo", "[fuzz][hostile]") {
  test::TempDir dir("fuzz-regression");
  const std::filesystem::path out = dir.path() / "out.png";
  for (const char* name : {"texture_chunk_length_past_end.png", "texture_empty_first_idat.png",
                           "texture_inflates_past_header.png"}) {
    INFO(name);
    test::require_refused(
        test::run({"render", "--set", "shading.layers.0.texture=" + (kRegressions / name).string(),
                   "--set", "viewport.width=8", "--set", "viewport.height=8", "-o", out.string()}),
        "could not be decoded", out);
  }
}

}  // namespace
}  // namespace relief
