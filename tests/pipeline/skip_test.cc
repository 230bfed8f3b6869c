// The work a frame skips (pipeline/frame_skips.h): each skip, turned off, must leave every
// output bit-identical while the counters that measure its work rise; and the counters must
// add up (docs/stages.md, "Skipped work").
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "core/stage_params.h"
#include "core/vertex_culling.h"
#include "core/vertex_transform.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/support/frame_counters.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// grid.width 90 leaves padding at the end of each row (the pitch is a multiple of 16).
const std::vector<std::string> kSkipTestFrame = {"viewport.width=200", "viewport.height=150",
                                                 "grid.width=90", "grid.height=90"};

std::vector<std::string> small(std::vector<std::string> extra) {
  std::vector<std::string> overrides = kSkipTestFrame;
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return overrides;
}

FrameRequest every_output_request(Backend backend, const FrameSkips& skips) {
  FrameRequest request;
  request.backend = backend;
  request.outputs = {true, true, true, true, true, true};
  request.skips = skips;
  return request;
}

void require_same_outputs(const FrameImage& a, const FrameImage& b) {
  REQUIRE(a.srgb == b.srgb);
  REQUIRE(a.linear == b.linear);
  REQUIRE(a.depth == b.depth);
  REQUIRE(a.primitive == b.primitive);
  REQUIRE(a.normal == b.normal);
  REQUIRE(a.world_height == b.world_height);
  REQUIRE(a.octaves == b.octaves);
}

// Each skip by name, for the messages.
struct SkipField {
  const char* name;
  bool FrameSkips::*field;
};
const SkipField kSkips[] = {{"invalid_vertices", &FrameSkips::invalid_vertices},
                            {"unseen_vertices", &FrameSkips::unseen_vertices},
                            {"unused_octaves", &FrameSkips::unused_octaves},
                            {"empty_tiles", &FrameSkips::empty_tiles},
                            {"water", &FrameSkips::water},
                            {"fog", &FrameSkips::fog},
                            {"dither", &FrameSkips::dither},
                            {"specular", &FrameSkips::specular},
                            {"zero_weights", &FrameSkips::zero_weights},
                            {"lit_shadows", &FrameSkips::lit_shadows},
                            {"unread_shadow_levels", &FrameSkips::unread_shadow_levels},
                            {"occluded_tiles", &FrameSkips::occluded_tiles}};

FrameSkips nothing_skipped() {
  FrameSkips none;
  for (const SkipField& skip : kSkips) {
    none.*skip.field = false;
  }
  return none;
}

TEST_CASE("noSkipChangesAnyOutputOfAnyPresetInEitherBackend", "[skip]") {
  for (const std::string& preset : preset_names()) {
    const Scene scene = resolve_scene(preset, kSkipTestFrame);
    const SceneResources resources = load_scene_resources(scene);
    for (Backend backend : {Backend::kReference, Backend::kReferenceDouble}) {
      const Frame all = render_frame(scene, resources, every_output_request(backend, FrameSkips{}));
      INFO(preset << ", " << backend_name(backend));
      for (const SkipField& skip : kSkips) {
        FrameSkips skips;
        skips.*skip.field = false;
        INFO("without skip " << skip.name);
        require_same_outputs(
            all.image, render_frame(scene, resources, every_output_request(backend, skips)).image);
      }
      INFO("without any skip");
      require_same_outputs(
          all.image,
          render_frame(scene, resources, every_output_request(backend, nothing_skipped())).image);
    }
  }
}

// A scene where skip `field` saves work, and the counters that must drop when it is on.
struct SkipCase {
  const char* skip;
  bool FrameSkips::*field;
  std::string preset;
  std::vector<std::string> overrides;
  std::vector<std::string> counters;
  FrameSkips base = {};  // the other skips
};

TEST_CASE("everySkipLowersTheCountersOfTheWorkItSaves", "[skip]") {
  FrameSkips without_unseen;
  without_unseen.unseen_vertices = false;
  const std::vector<SkipCase> cases = {
      // Without the culling of unseen vertices (which never flags an invalid one).
      {"invalid_vertices",
       &FrameSkips::invalid_vertices,
       "default",
       {},
       {"vertices evaluated", "point-octaves summed", "vertices transformed"},
       without_unseen},
      // Looking along the ground: the grid's rows reach past the screen's sides.
      {"unseen_vertices",
       &FrameSkips::unseen_vertices,
       "default",
       {"camera.fov_y_deg=30"},
       {"vertices evaluated", "point-octaves summed", "vertices transformed",
        "triangles submitted"}},
      // From high above and coarse detail no vertex needs the finest octaves.
      {"unused_octaves",
       &FrameSkips::unused_octaves,
       "default",
       {"terrain.lod.bias=-4"},
       {"octaves in the table"}},
      // The sky fills the top rows of tiles.
      {"empty_tiles", &FrameSkips::empty_tiles, "default", {}, {"tiles rasterised"}},
      // A water level below every height the terrain can take.
      {"water",
       &FrameSkips::water,
       "default",
       {"terrain.water_level=-2000"},
       {"water depths computed"}},
      {"fog", &FrameSkips::fog, "plain", {}, {"fogged pixels"}},
      {"dither", &FrameSkips::dither, "plain", {}, {"dither samples"}},
      {"specular", &FrameSkips::specular, "plain", {}, {"specular terms"}},
      {"zero_weights", &FrameSkips::zero_weights, "alpine", {}, {"texture fetches"}},
      {"lit_shadows",
       &FrameSkips::lit_shadows,
       "sunset",
       {},
       {"pixels with the sun disc's share evaluated"}},
      {"unread_shadow_levels",
       &FrameSkips::unread_shadow_levels,
       "sunset",
       {},
       {"cache samples evaluated", "samples swept"}},
      // Sky light alone reads the cache too, toward all four sides.
      {"unread_shadow_levels",
       &FrameSkips::unread_shadow_levels,
       "sunset",
       {"lighting.shadows=false"},
       {"cache samples evaluated", "samples swept"}},
  };
  for (const SkipCase& c : cases) {
    const Scene scene = resolve_scene(c.preset, small(c.overrides));
    const SceneResources resources = load_scene_resources(scene);
    FrameSkips without = c.base;
    without.*c.field = false;
    const Frame on =
        render_frame(scene, resources, every_output_request(Backend::kReference, c.base));
    const Frame off =
        render_frame(scene, resources, every_output_request(Backend::kReference, without));
    INFO("skip " << c.skip << " on " << c.preset);
    require_same_outputs(on.image, off.image);
    for (const std::string& name : c.counters) {
      INFO(name);
      CHECK(test::frame_counter(on, name) < test::frame_counter(off, name));
    }
  }
}

TEST_CASE("theCountersOfAFrameAddUp", "[skip]") {
  for (const std::string& preset : preset_names()) {
    const Scene scene = resolve_scene(preset, kSkipTestFrame);
    const SceneResources resources = load_scene_resources(scene);
    const Frame frame =
        render_frame(scene, resources, every_output_request(Backend::kReference, {}));
    INFO(preset);
    const std::uint64_t pixels = 200u * 150u;
    // Every pixel is shaded once, as terrain exactly where a triangle covers it.
    CHECK(test::frame_counter(frame, "pixels shaded as terrain") ==
          test::frame_counter(frame, "pixels covered"));
    CHECK(test::frame_counter(frame, "pixels shaded as terrain") +
              test::frame_counter(frame, "pixels shaded as background") ==
          pixels);
    // Vertices: drawn ones are evaluated, and transformed, and get normals.
    const std::uint64_t drawn = test::frame_counter(frame, "vertices to draw");
    CHECK(drawn <= test::frame_counter(frame, "vertices to evaluate"));
    CHECK(test::frame_counter(frame, "vertices evaluated") ==
          test::frame_counter(frame, "vertices to evaluate"));
    CHECK(test::frame_counter(frame, "vertices transformed") == drawn);
    CHECK(test::frame_counter(frame, "normals computed") == drawn);
    CHECK(test::frame_counter(frame, "vertices evaluated") <=
          test::frame_counter(frame, "grid vertices"));
    // A vertex sums at most the table's octaves.
    CHECK(test::frame_counter(frame, "point-octaves summed") <=
          test::frame_counter(frame, "vertices evaluated") *
              test::frame_counter(frame, "octaves in the table"));
    CHECK(test::frame_counter(frame, "octaves in the table") <=
          std::uint64_t(scene.terrain.last_octave - scene.terrain.first_octave + 1));
    // Triangles: submitted within the grid, set up within those (clipping can split one
    // triangle into a few pieces, but the frame culls far more than it splits).
    CHECK(test::frame_counter(frame, "triangles submitted") <=
          test::frame_counter(frame, "triangles in the grid"));
    CHECK(test::frame_counter(frame, "tiles rasterised") <= test::frame_counter(frame, "tiles"));
    // The stages that ran, by name, in the order of the table (a planet frame evaluates every
    // valid vertex: no outcodes of the height bounds, docs/planet.md; cast shadows' and sky
    // light's stages run where the scene has them).
    for (const StageTime& stage : frame.stats.stages) {
      INFO(stage.name);
      const bool shadow_stage = stage.name == "shadow heights" || stage.name == "sun horizons";
      if (shadow_stage) {
        CHECK(stage.ran == (scene.lighting.shadows || scene.lighting.sky_occlusion));
        continue;
      }
      if (stage.name == "sky horizons") {
        CHECK(stage.ran == scene.lighting.sky_occlusion);
        continue;
      }
      CHECK(
          (stage.ran || (scene.terrain.planet && stage.name == "vertex outcodes (height bounds)")));
    }
  }
}

TEST_CASE("aStageWithNothingToDoIsReportedSkipped", "[skip]") {
  const Scene scene = resolve_scene("default", kSkipTestFrame);
  const SceneResources resources = load_scene_resources(scene);
  FrameSkips skips;
  skips.unseen_vertices = false;  // no outcodes needed, before stage 3 or after it
  const Frame frame =
      render_frame(scene, resources, every_output_request(Backend::kReference, skips));
  int skipped = 0;
  for (const StageTime& stage : frame.stats.stages) {
    INFO(stage.name);
    // The default scene has no cast shadows and no sky light: their three stages have
    // nothing to do either.
    const bool idle = stage.name.rfind("vertex outcodes", 0) == 0 ||
                      stage.name == "shadow heights" || stage.name == "sun horizons" ||
                      stage.name == "sky horizons";
    CHECK(stage.ran != idle);
    skipped += idle;
  }
  CHECK(skipped == 5);
}

TEST_CASE("theCountersAreTheSameForEveryThreadCount", "[skip]") {
  const Scene scene = resolve_scene("lake", kSkipTestFrame);
  const SceneResources resources = load_scene_resources(scene);
  std::vector<std::vector<std::pair<std::string, std::uint64_t>>> runs;
  for (int threads : {1, 2, 3}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const Frame frame =
        render_frame(scene, resources, every_output_request(Backend::kReference, {}));
    std::vector<std::pair<std::string, std::uint64_t>> counters;
    for (const StageTime& stage : frame.stats.stages) {
      for (const WorkCounter& c : stage.counters) {
        counters.emplace_back(c.name, c.value);
      }
    }
    runs.push_back(std::move(counters));
  }
  CHECK(runs[0].size() > 20);
  CHECK(runs[1] == runs[0]);
  CHECK(runs[2] == runs[0]);
}

// The outcodes' promise (core/vertex_culling.h): a plane marked outside has every height the
// terrain can take there outside it (or the vertex's own height, after stage 3), in the clip
// coordinates stage 5 computes in float.
TEST_CASE("anOutcodeMarksAPlaneOnlyWhenEveryHeightThereIsOutsideIt", "[skip]") {
  test::TestRandom random(7);
  const NoiseLattice lattice = make_noise_lattice(1, 256);
  int marked_by_bounds = 0, marked_by_height = 0;
  for (const char* pitch : {"camera.pitch_deg=-8", "camera.pitch_deg=-90", "camera.pitch_deg=35",
                            "camera.pitch_deg=-45"}) {
    for (const char* fov : {"camera.fov_y_deg=60", "camera.fov_y_deg=5", "camera.fov_y_deg=150"}) {
      Scene scene = resolve_scene("default", small({pitch, fov}));
      const FramePlan plan = make_frame_plan(scene, lattice);
      const TransformParams<float> transform = make_terrain_params<float>(plan).transform;
      // One row of random points around the camera, near and far, each at the bounds'
      // lowest, highest and a random height.
      constexpr int kPoints = 4000;
      CullParams<float> cull = make_cull_params<float>(plan);
      cull.width = cull.pitch = kPoints;
      cull.height = 1;
      std::vector<float> dx(kPoints), dz(kPoints), h(kPoints);
      std::vector<std::uint8_t> valid(kPoints, 1), by_bounds(kPoints), by_height(kPoints);
      for (int k = 0; k < kPoints; ++k) {
        const double radius = std::pow(10.0, 6.0 * random.uniform(0.0, 1.0) - 1.0);
        const double angle = 2 * M_PI * random.uniform(0.0, 1.0);
        dx[k] = float(radius * std::cos(angle));
        dz[k] = float(radius * std::sin(angle));
      }
      vertex_outcodes<float>(cull, RowRange{0, 1}, dx, dz, {}, valid, by_bounds);
      for (int choice = 0; choice < 3; ++choice) {
        for (int k = 0; k < kPoints; ++k) {
          const double t = choice == 0 ? 0.0 : choice == 1 ? 1.0 : random.uniform(0.0, 1.0);
          h[k] = float(cull.height_lo + t * (double(cull.height_hi) - cull.height_lo));
        }
        vertex_outcodes<float>(cull, RowRange{0, 1}, dx, dz, h, valid, by_height);
        std::vector<float> x(kPoints), y(kPoints), z(kPoints), w(kPoints);
        transform_vertices<float>(transform, IndexRange{0, kPoints}, dx, dz, h, {},
                                  ClipSpans<float>{x, y, z, w});
        for (int k = 0; k < kPoints; ++k) {
          // GL's clip volume: -w <= x <= w, -w <= y <= w, z <= w (z is the near distance).
          const bool outside[5] = {x[k]<-w[k], x[k]> w[k], y[k]<-w[k], y[k]> w[k], w[k] < z[k]};
          for (int plane = 0; plane < 5; ++plane) {
            INFO(pitch << " " << fov << " point " << dx[k] << ", " << h[k] << ", " << dz[k]
                       << " plane " << plane);
            if (by_bounds[k] & (1u << plane)) {
              REQUIRE(outside[plane]);
              REQUIRE((by_height[k] & (1u << plane)) != 0);  // a point within the segment
              ++marked_by_bounds;
            }
            if (by_height[k] & (1u << plane)) {
              REQUIRE(outside[plane]);
              ++marked_by_height;
            }
          }
        }
      }
    }
  }
  // The test tests something; and the vertex's own height marks more than the bounds do.
  CHECK(marked_by_bounds > 10000);
  CHECK(marked_by_height > marked_by_bounds);
}

}  // namespace
}  // namespace relief
