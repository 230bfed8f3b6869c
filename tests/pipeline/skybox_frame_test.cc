// The skybox in whole frames (core/skybox.h): its files loaded and refused as the scene
// reference says, the same bytes from the simd backend on every target and thread count as
// from the reference, the water reflecting it, its memory estimated, and a scene without one
// left as it was.
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "core/srgb.h"
#include "pipeline/frame.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/cli_support.h"
#include "tests/support/simd_targets.h"
#include "tests/support/skybox_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

const std::vector<std::string> kSmallSkyboxFrame = {"viewport.width=96", "viewport.height=72",
                                                    "grid.width=64", "grid.height=64"};

Scene skybox_scene(const std::string& preset, const std::array<std::string, 6>& faces,
                   const std::string& extra = "") {
  std::vector<std::string> overrides = kSmallSkyboxFrame;
  overrides.push_back(test::skybox_override(faces, extra));
  return resolve_scene(preset, overrides);
}

// sRGB's decoding (IEC 61966-2-1), written out here.
double decoded(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST_CASE("skyboxFacesLoadAsLinearRadianceTimesTheIntensityTopRowFirst", "[skybox]") {
  const test::TempDir dir("skybox-load");
  const auto faces = test::write_checker_faces(dir.path(), 16, 4);
  const Scene scene = skybox_scene("default", faces, ", \"intensity\": 2.5");
  const std::optional<Skybox> box = load_skybox(scene);
  REQUIRE(box);
  REQUIRE(box->size == 16);
  for (int f = 0; f < 6; ++f) {
    const auto colour = test::face_colour(f);
    // The file's first row is the image's top: squares (0, 0) bright, (4, 0) dark.
    for (int c = 0; c < 3; ++c) {
      CHECK(box->texel(f, 0, 0)[c] == Approx(2.5 * decoded(colour[std::size_t(c)])).epsilon(1e-6));
      CHECK(box->texel(f, 0, 4)[c] ==
            Approx(2.5 * decoded(colour[std::size_t(c)] * 6 / 10)).epsilon(1e-6));
    }
  }
  Scene none = scene;
  none.sky.skybox.reset();
  CHECK_FALSE(load_skybox(none));
  CHECK_FALSE(same_resource_inputs(scene, none));
  Scene brighter = scene;
  brighter.sky.skybox->intensity = 3;
  CHECK_FALSE(same_resource_inputs(scene, brighter));
  Scene no_sun = scene;
  no_sun.sky.skybox->sun_disc = false;
  CHECK(same_resource_inputs(scene, no_sun));  // a frame parameter, not a texel
}

TEST_CASE("skyboxFilesThatCannotServeAreRefusedNamingTheFace", "[skybox][cli]") {
  const test::TempDir dir("skybox-refuse");
  auto faces = test::write_checker_faces(dir.path(), 16);
  const std::filesystem::path out = dir.path() / "out.png";
  const auto refused = [&](const std::array<std::string, 6>& f, const std::string& message,
                           const std::string& extra = "") {
    std::vector<std::string> sets = kSmallSkyboxFrame;
    sets.push_back(test::skybox_override(f, extra));
    test::require_refused(test::render_preset("default", sets, out), message, out);
  };
  {
    auto f = faces;
    f[3] = (dir.path() / "missing.png").string();
    refused(f, "sky.skybox.faces[3]");
  }
  {
    auto f = faces;
    const auto png = test::checker_face_png(4, 32, 8);
    f[4] = test::write_file(dir.path() / "big.png", std::string(png.begin(), png.end()));
    refused(f, "sky.skybox.faces[4] = \"" + f[4] + "\" is 32x32 pixels, sky.skybox.faces[0]");
  }
  {
    auto f = faces;
    f[1] = test::write_file(dir.path() / "text.png", "not a png at all");
    refused(f, "sky.skybox.faces[1]");
  }
  {
    auto f = faces;
    const auto png = test::checker_face_png(0, 12, 4);  // not a power of two
    f[0] = test::write_file(dir.path() / "twelve.png", std::string(png.begin(), png.end()));
    refused(f, "sky.skybox.faces[0] = \"" + f[0] +
                   "\" is 12x12 pixels; allowed: square, a power "
                   "of two from 4 to 2048");
  }
  {
    auto f = faces;
    const auto png = test::checker_face_png(0, 4096, 512);  // past kMaxSkyboxSize
    f[5] = test::write_file(dir.path() / "huge.png", std::string(png.begin(), png.end()));
    refused(f, "from 4 to 2048");
  }
  {
    auto f = faces;
    const std::string truncated = test::write_file(dir.path() / "cut.png", [&] {
      const auto png = test::checker_face_png(2, 16, 8);
      return std::string(png.begin(), png.begin() + std::ptrdiff_t(png.size() / 2));
    }());
    f[2] = truncated;
    refused(f, "sky.skybox.faces[2]");
  }
  refused(faces, "sky.skybox.intensity", ", \"intensity\": -1");
  refused(faces, "sky.skybox.intensity", ", \"intensity\": 1e300");
  refused(faces, "sky.skybox.sun_disc", ", \"sun_disc\": 3");
  std::vector<std::string> five = kSmallSkyboxFrame;
  five.push_back("sky.skybox={\"faces\": [\"a.png\", \"b.png\", \"c.png\", \"d.png\", \"e.png\"]}");
  test::require_refused(test::render_preset("default", five, out), "sky.skybox.faces", out);
  {
    // Special files: a directory, and a FIFO (which must not block the open).
    auto f = faces;
    f[3] = dir.path().string();
    refused(f, "sky.skybox.faces[3]");
    const std::filesystem::path fifo = dir.path() / "fifo.png";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    f[3] = fifo.string();
    refused(f, "sky.skybox.faces[3]");
  }
  {
    auto f = faces;
    f[2] = "";
    refused(f, "sky.skybox.faces[2] is empty");
    f[2] = "builtin:sky";
    refused(f, "sky.skybox.faces[2] = \"builtin:sky\" names no file");
  }
  std::vector<std::string> none = kSmallSkyboxFrame;
  none.push_back("sky.skybox={\"intensity\": 2}");
  test::require_refused(test::render_preset("default", none, out), "\"faces\"", out);
}

TEST_CASE("skyboxFramesAreBitIdenticalOnTheSimdBackendOnEveryTargetAndThreadCount",
          "[skybox][simd]") {
  const test::TempDir dir("skybox-simd");
  const auto faces = test::write_checker_faces(dir.path(), 32, 4);
  const EachTarget targets;
  // lake: open water and water over terrain both reflect the box; sunset: the sun over it.
  for (const char* preset : {"lake", "sunset", "default"}) {
    for (const std::string& extra : {std::string(), std::string(", \"sun_disc\": false")}) {
      const Scene scene = skybox_scene(preset, faces, extra);
      const SceneResources resources = load_scene_resources(scene);
      FrameRequest request;
      request.outputs.linear = true;
      request.backend = Backend::kReference;
      const Frame reference = render_frame(scene, resources, request);
      request.backend = Backend::kSimd;
      targets.each_with_threads({1, 2}, [&](const std::string& target, int threads) {
        const FrameImage got = render_frame(scene, resources, request).image;
        INFO(preset << extra << ", " << target << ", " << threads << " threads");
        REQUIRE(got.srgb == reference.image.srgb);
        REQUIRE(test::same_bits(got.linear, reference.image.linear));
      });
    }
  }
}

TEST_CASE("theSkyAndTheWaterShowTheBoxAndTheTerrainDoesNot", "[skybox]") {
  const test::TempDir dir("skybox-frame");
  const auto faces = test::write_checker_faces(dir.path(), 32, 4);
  const Scene with = skybox_scene("lake", faces);
  Scene without = with;
  without.sky.skybox.reset();
  FrameRequest request;
  request.outputs.primitive = true;
  request.outputs.linear = true;
  const Frame a = render_frame(with, load_scene_resources(with), request);
  const Frame b = render_frame(without, load_scene_resources(without), request);
  REQUIRE(a.image.primitive == b.image.primitive);
  std::size_t sky_changed = 0, sky = 0;
  for (std::size_t k = 0; k < a.image.primitive.size(); ++k) {
    const bool changed = a.image.linear[3 * k] != b.image.linear[3 * k] ||
                         a.image.linear[3 * k + 1] != b.image.linear[3 * k + 1] ||
                         a.image.linear[3 * k + 2] != b.image.linear[3 * k + 2];
    if (a.image.primitive[k] == raster::kNoPrimitive) {
      ++sky;
      sky_changed += changed;
    }
  }
  REQUIRE(sky > 100);
  CHECK(sky_changed == sky);  // every background pixel: the sky, or open water reflecting it
  // Terrain pixels change only where water covers them (its reflection); dry ground keeps its
  // bytes: the lake's shore pixels above the water level are most of the covered ones.
  std::size_t dry_same = 0, covered = 0;
  for (std::size_t k = 0; k < a.image.primitive.size(); ++k) {
    if (a.image.primitive[k] != raster::kNoPrimitive) {
      ++covered;
      dry_same += a.image.linear[3 * k] == b.image.linear[3 * k];
    }
  }
  CHECK(dry_same > 0);
  CHECK(dry_same < covered);
}

TEST_CASE("theMemoryEstimateCountsTheSkyboxFaces", "[skybox]") {
  const test::TempDir dir("skybox-memory");
  const auto faces = test::write_checker_faces(dir.path(), 256, 32);
  const Scene with = skybox_scene("default", faces);
  Scene without = with;
  without.sky.skybox.reset();
  const std::uintmax_t added = estimate_scene_resources_memory(with).total() -
                               estimate_scene_resources_memory(without).total();
  // At least the six faces' float texels the resources keep.
  CHECK(added >= 6u * 256u * 256u * 3u * sizeof(float));
  CHECK(added <= 6u * 256u * 256u * 32u + 6u * (1u << 20));
}

}  // namespace
}  // namespace relief
