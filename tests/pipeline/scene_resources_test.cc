// Loading a scene's resources (pipeline/scene_resources.h): the layers' textures, built side by
// side, have the bits of one built alone at any thread count, and of all failing layers the
// first is the one reported, whatever order the threads finished in; of failing resources of
// several kinds, the first in loading order.
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/proto_texture.h"
#include "core/scene/scene_json.h"
#include "core/texture_synthesis.h"
#include "pipeline/scene_resources.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

TEST_CASE("layerTexturesHaveTheSameBitsAtEveryThreadCount", "[resources]") {
  for (const char* preset : {"default", "alpine", "lava"}) {
    const Scene scene = resolve_scene(preset, {});
    std::vector<ProtoTexture> alone;
    for (const MaterialLayer& layer : scene.shading.layers) {
      alone.push_back(build_proto_texture(
          load_layer_texture(layer, scene.shading.texture_size, "t"), scene.shading.mip_blend));
    }
    for (const int threads : {1, 2, 8}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      const SceneResources resources = load_scene_resources(scene);
      REQUIRE(resources.textures.size() == alone.size());
      for (std::size_t k = 0; k < alone.size(); ++k) {
        INFO(preset << ", layer " << k << ", " << threads << " threads");
        CHECK(resources.textures[k].texels == alone[k].texels);
        CHECK(resources.textures[k].levels.size() == alone[k].levels.size());
      }
    }
  }
}

TEST_CASE("ofSeveralFailingLayersTheFirstIsReported", "[resources]") {
  const test::TempDir dir("resources-first");
  const std::string bad = test::write_file(dir.path() / "bad.png", "not a png");
  Scene scene = resolve_scene("default", {});
  REQUIRE(scene.shading.layers.size() >= 3);
  for (std::size_t k = 1; k < scene.shading.layers.size(); ++k) {
    scene.shading.layers[k].texture = bad;
  }
  for (int run = 0; run < 20; ++run) {
    try {
      (void)load_scene_resources(scene);
      FAIL("loaded a layer that is no PNG");
    } catch (const SceneError& e) {
      CHECK(e.path() == "shading.layers[1].texture");
    }
  }
}

TEST_CASE("ofFailingResourcesOfEveryKindTheFirstInLoadingOrderIsReported", "[resources]") {
  const test::TempDir dir("resources-order");
  const std::string bad = test::write_file(dir.path() / "bad.png", "not a png");
  Scene scene = resolve_scene("default", {});
  scene.terrain.sketch = SketchSettings{bad};
  scene.sky.skybox = SkyboxSettings{{bad, bad, bad, bad, bad, bad}};
  const auto reported = [&] {
    try {
      (void)load_scene_resources(scene);
    } catch (const SceneError& e) {
      return e.path();
    }
    return std::string("nothing");
  };
  for (int run = 0; run < 10; ++run) {
    CHECK(reported() == "terrain.sketch.image");  // before the skybox, whichever ends first
  }
  REQUIRE(scene.shading.layers.size() >= 3);
  scene.shading.layers[2].texture = bad;
  for (int run = 0; run < 10; ++run) {
    CHECK(reported() == "shading.layers[2].texture");  // the layers before the sketch
  }
}

}  // namespace
}  // namespace relief
