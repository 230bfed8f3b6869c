// The cloud layer in whole frames (core/clouds.h): the same bytes from the simd backend on
// every target and thread count as from the reference, seen from below, inside and above the
// layer and over water; a layer holding no cloud changes no bit; an opaque overcast leaves
// the ground lit as if the sun were off; its work counted; its fields refused out of range.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/limits.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "raster/raster_types.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/cli_support.h"
#include "tests/support/frame_counters.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

std::vector<std::string> small_cloud_frame(std::vector<std::string> more) {
  more.insert(more.end(),
              {"viewport.width=96", "viewport.height=72", "grid.width=64", "grid.height=64"});
  return more;
}

Frame render_clouds(const Scene& scene, Backend backend, int cloud_steps = 1) {
  FrameRequest request;
  request.backend = backend;
  request.outputs.linear = true;
  request.outputs.primitive = true;
  request.cloud_steps = cloud_steps;
  return render_frame(scene, load_scene_resources(scene), request);
}

TEST_CASE("cloudFramesAreBitIdenticalOnTheSimdBackendOnEveryTargetAndThreadCount",
          "[clouds][simd]") {
  const EachTarget targets;
  // Below the layer (default); over water and open water (lake); with the atmosphere, cast
  // shadows and sky light (sunset); the camera (at 700) inside the layer; the layer below the
  // camera, the mountains through it; a low sun behind a warped, finely detailed layer.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"default", "sky.clouds={}"},
      {"lake", "sky.clouds={\"coverage\": 0.6}"},
      {"sunset", "sky.clouds={\"altitude\": 1500}"},
      {"default", "sky.clouds={\"altitude\": 600, \"thickness\": 200, \"density\": 0.01}"},
      {"default", "sky.clouds={\"altitude\": 150, \"thickness\": 250, \"coverage\": 0.5}"},
      {"default", "sky.clouds={\"octaves\": 8, \"warp\": 4, \"scale\": 400}"},
  };
  for (const auto& [preset, clouds] : cases) {
    const Scene scene = resolve_scene(preset, small_cloud_frame({clouds}));
    const Frame reference = render_clouds(scene, Backend::kReference);
    REQUIRE(test::frame_counter(reference, "cloud lattice samples") > 0);
    targets.each_with_threads({1, 2}, [&](const std::string& target, int threads) {
      const Frame got = render_clouds(scene, Backend::kSimd);
      INFO(preset << " " << clouds << ", " << target << ", " << threads << " threads");
      REQUIRE(got.image.srgb == reference.image.srgb);
      REQUIRE(test::same_bits(got.image.linear, reference.image.linear));
      for (const char* counter : {"view rays through the cloud layer",
                                  "sun rays through the cloud layer", "cloud lattice samples"}) {
        INFO(counter);
        CHECK(test::frame_counter(got, counter) == test::frame_counter(reference, counter));
      }
    });
  }
}

TEST_CASE("aLayerHoldingNoCloudChangesNoBit", "[clouds]") {
  // Coverage 0: every density is exactly 0, so every path lets all light through
  // (exp2_det(0) = 1): radiance x 1 + cloud x 0 is the radiance, the sun's share x 1 the share.
  for (const char* preset : {"default", "lake", "sunset"}) {
    const Scene none = resolve_scene(preset, small_cloud_frame({}));
    const Scene empty = resolve_scene(preset, small_cloud_frame({"sky.clouds={\"coverage\": 0}"}));
    for (const Backend backend : {Backend::kReference, Backend::kSimd}) {
      INFO(preset << ", " << backend_name(backend));
      const Frame a = render_clouds(none, backend);
      const Frame b = render_clouds(empty, backend);
      CHECK(test::same_bits(a.image.linear, b.image.linear));
      CHECK(test::frame_counter(b, "view rays through the cloud layer") > 0);
    }
  }
}

TEST_CASE("anOpaqueOvercastLightsTheGroundAsIfTheSunWereOff", "[clouds]") {
  // No water, no fog (its colour warms toward the sun), the layer above every mountain: the
  // ground's light is then the sky's and the ambient's alone.
  const std::vector<std::string> common = {"terrain.water_level=null", "sky.fog_density=0"};
  auto overcast = common;
  overcast.push_back(
      "sky.clouds={\"altitude\": 20000, \"coverage\": 1, \"density\": 100, \"thickness\": 500}");
  auto sun_off = common;
  sun_off.push_back("lighting.sun_intensity=0");
  const Frame a =
      render_clouds(resolve_scene("default", small_cloud_frame(overcast)), Backend::kReference);
  const Frame b =
      render_clouds(resolve_scene("default", small_cloud_frame(sun_off)), Backend::kReference);
  REQUIRE(a.image.primitive == b.image.primitive);
  std::size_t ground = 0, sky = 0;
  for (std::size_t k = 0; k < a.image.primitive.size(); ++k) {
    if (a.image.primitive[k] == raster::kNoPrimitive) {
      // The sky is the layer's own light alone: no sun disc, no blue behind it.
      ++sky;
      CHECK(a.image.linear[3 * k] > 0.0f);
      continue;
    }
    ++ground;
    for (int c = 0; c < 3; ++c) {
      const float x = a.image.linear[3 * k + c], y = b.image.linear[3 * k + c];
      REQUIRE(std::abs(x - y) <= 1e-6f * std::max(1.0f, y));
    }
  }
  CHECK(ground > 1000);
  CHECK(sky > 100);
  CHECK(test::frame_counter(a, "sun rays through the cloud layer") == ground);
}

TEST_CASE("theWaterReflectsTheLayer", "[clouds]") {
  // lake with the sun off: the camera, under the layer, looks down at the water below the
  // horizon, so its view rays there never reach the layer, and the ground's sun (the layer's
  // shadow scales it) is 0: what changes there is the reflected sky, seen through the clouds.
  const std::vector<std::string> dark = {"lighting.sun_intensity=0"};
  auto cloudy = dark;
  cloudy.push_back("sky.clouds={\"coverage\": 0.7}");
  const Scene with = resolve_scene("lake", small_cloud_frame(cloudy));
  const Scene without = resolve_scene("lake", small_cloud_frame(dark));
  const Frame a = render_clouds(with, Backend::kReference);
  const Frame b = render_clouds(without, Backend::kReference);
  REQUIRE(a.image.primitive == b.image.primitive);
  const int width = with.viewport.width, height = with.viewport.height;
  std::size_t changed = 0;
  for (int py = 0; py < height / 3; ++py) {  // the bottom third: water below the horizon
    for (int px = 0; px < width; ++px) {
      const std::size_t k = std::size_t(py) * width + px;
      changed += a.image.linear[3 * k] != b.image.linear[3 * k];
    }
  }
  CHECK(changed > std::size_t(width) * (height / 3) / 4);
  CHECK(test::frame_counter(a, "sun rays through the cloud layer") > 0);
}

TEST_CASE("aLayerBelowEveryTerrainChangesNoBitAndASetSunReadsNoPath", "[clouds]") {
  // Below the horizon without water the background stands for terrain past the far distance:
  // its path ends by the frame's lowest terrain height, above a layer 100 km down.
  const std::vector<std::string> dry = {"terrain.water_level=null"};
  auto buried = dry;
  buried.push_back("sky.clouds={\"altitude\": -1e5, \"coverage\": 1, \"density\": 1}");
  for (const Backend backend : {Backend::kReference, Backend::kSimd}) {
    const Frame a = render_clouds(resolve_scene("default", small_cloud_frame(buried)), backend);
    const Frame b = render_clouds(resolve_scene("default", small_cloud_frame(dry)), backend);
    CHECK(test::same_bits(a.image.linear, b.image.linear));
    CHECK(test::frame_counter(a, "view rays through the cloud layer") == 0);
  }
  const Frame night = render_clouds(
      resolve_scene("default",
                    small_cloud_frame({"sky.clouds={}", "lighting.sun_elevation_deg=-30"})),
      Backend::kSimd);
  CHECK(test::frame_counter(night, "sun rays through the cloud layer") == 0);
  CHECK(test::frame_counter(night, "view rays through the cloud layer") > 0);
}

TEST_CASE("theTruthReadsTheLayerAlongEachPath", "[clouds]") {
  // An overcast of constant density: every point of a path reads the same, so the truth's
  // midpoint rule is the one point; a broken layer's paths read differently.
  const Scene constant = resolve_scene(
      "default", small_cloud_frame({"sky.clouds={\"altitude\": 900, \"coverage\": 1}"}));
  const Frame one = render_clouds(constant, Backend::kReferenceDouble, 1);
  const Frame many = render_clouds(constant, Backend::kReferenceDouble, 16);
  for (std::size_t k = 0; k < one.image.linear.size(); ++k) {
    REQUIRE(std::abs(one.image.linear[k] - many.image.linear[k]) <=
            1e-5f * std::max(1.0f, one.image.linear[k]));
  }
  CHECK(test::frame_counter(many, "cloud lattice samples") >
        8 * test::frame_counter(one, "cloud lattice samples"));
  for (const int steps : {0, -1, limits::kMaxCloudSteps + 1}) {
    CHECK_THROWS_AS(render_clouds(constant, Backend::kReference, steps), std::invalid_argument);
  }
  const Scene broken = resolve_scene("default", small_cloud_frame({"sky.clouds={}"}));
  CHECK_FALSE(test::same_bits(render_clouds(broken, Backend::kReferenceDouble, 1).image.linear,
                              render_clouds(broken, Backend::kReferenceDouble, 16).image.linear));
}

TEST_CASE("cloudFieldsOutOfRangeAreRefusedNamingTheField", "[clouds][cli]") {
  const test::TempDir dir("clouds-refuse");
  const std::filesystem::path out = dir.path() / "out.png";
  const auto refused = [&](const std::string& clouds, const std::string& message) {
    test::require_refused(test::render_preset("default", small_cloud_frame({clouds}), out), message,
                          out);
  };
  refused("sky.clouds={\"density\": -1}", "sky.clouds.density");
  refused("sky.clouds={\"density\": 1e300}", "sky.clouds.density");
  refused("sky.clouds={\"coverage\": 1.5}", "sky.clouds.coverage");
  refused("sky.clouds={\"thickness\": 0}", "sky.clouds.thickness");
  refused("sky.clouds={\"altitude\": 1e300}", "sky.clouds.altitude");
  refused("sky.clouds={\"scale\": 0.5}", "sky.clouds.scale");
  refused("sky.clouds={\"octaves\": 0}", "sky.clouds.octaves");
  refused("sky.clouds={\"octaves\": 9}", "sky.clouds.octaves");
  refused("sky.clouds={\"octaves\": 2.5}", "sky.clouds.octaves");
  refused("sky.clouds={\"warp\": 17}", "sky.clouds.warp");
  refused("sky.clouds={\"color\": [2, 0, 0]}", "sky.clouds.color");
  refused("sky.clouds={\"colour\": [1, 1, 1]}", "colour");
  refused("sky.clouds=3", "sky.clouds");
  refused("sky.clouds.coverage=NaN", "sky.clouds");
  // A planet's clouds would follow its sphere: refused, the field named.
  test::require_refused(test::render_preset("planet", small_cloud_frame({"sky.clouds={}"}), out),
                        "sky.clouds", out);
}

TEST_CASE("aCameraInsideTheLayerAndALayerInsideTheTerrainRenderFinite", "[clouds]") {
  for (const std::string& clouds :
       {std::string("sky.clouds={\"altitude\": 650, \"thickness\": 100, \"density\": 100, "
                    "\"coverage\": 1}"),
        std::string("sky.clouds={\"altitude\": -500, \"thickness\": 3000, \"coverage\": 0.7}"),
        std::string("sky.clouds={\"altitude\": 800}"), std::string("sky.clouds={}")}) {
    for (const char* sun : {"lighting.sun_elevation_deg=90", "lighting.sun_elevation_deg=-30",
                            "lighting.sun_elevation_deg=0"}) {
      const Frame f =
          render_clouds(resolve_scene("default", small_cloud_frame({clouds, sun})), Backend::kSimd);
      INFO(clouds << ", " << sun);
      for (const float v : f.image.linear) {
        REQUIRE(std::isfinite(v));
        REQUIRE(v >= 0.0f);
      }
    }
  }
}

}  // namespace
}  // namespace relief
