// terrain.heightfield.geomipmap through whole frames (pipeline/cpu_backend_mesh.cc): over a sweep
// of cameras no pixel shows the background where its ray must meet the field (the seam test of
// tests/raster/geomipmap_seam_test.cc, now through every stage of a frame); every CPU backend
// draws it (simd the reference's bytes, reference-double close); occlusion culling is a skip
// (the same outputs, fewer tiles); the scene rules and the GL backend refuse what is not built.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/camera.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/gl_backend.h"
#include "pipeline/scene_resources.h"
#include "raster/raster_types.h"
#include "tests/support/cli_support.h"
#include "tests/support/frame_counters.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr int kSide = 257;  // 16 tiles of 16 cells: the lattice is the texel centres
constexpr double kHalfExtent = 2000.0;

// Ridges at several scales and a little noise (levels differ between neighbours everywhere),
// or a plateau at 400 over z > 1000 before a valley at 0 (the plateau hides the valley from
// a camera standing on it).
std::vector<float> field_samples(bool plateau) {
  std::vector<float> h(std::size_t(kSide) * kSide);
  for (int r = 0; r < kSide; ++r) {
    for (int c = 0; c < kSide; ++c) {
      std::uint64_t x = std::uint64_t(r) * 7919u + std::uint64_t(c);
      x = (x ^ (x >> 31)) * 0xbf58476d1ce4e5b9ull;
      x ^= x >> 29;
      const double noise = double(x % 4096) / 4096.0 - 0.5;
      const double ridges = 120.0 * std::sin(0.031 * c) * std::cos(0.027 * r) +
                            35.0 * std::sin(0.19 * c + 0.11 * r) + 4.0 * noise;
      const double z = -kHalfExtent + (r + 0.5) * 2 * kHalfExtent / kSide;  // row 0 at z0
      h[std::size_t(r) * kSide + c] = float(plateau ? (z > 1000.0 ? 400.0 : 0.2 * ridges) : ridges);
    }
  }
  return h;
}

struct FieldScene {
  test::TempDir dir{"geomipmap-frame"};
  std::vector<float> samples;
  Scene scene;
};

void build(FieldScene& f, bool plateau, double pixel_error) {
  f.samples = field_samples(plateau);
  const std::filesystem::path file = f.dir.path() / "field.pfm";
  std::ofstream(file, std::ios::binary) << test::pfm_bytes(kSide, kSide, f.samples);
  HeightFieldSettings field;
  field.image = file.string();
  field.extent = {-kHalfExtent, -kHalfExtent, kHalfExtent, kHalfExtent};
  field.height = {0.0, 1.0};  // the PFM's floats are world heights
  field.geomipmap = GeoMipMapSettings{16, pixel_error, true};
  f.scene.terrain.heightfield = field;
  f.scene.terrain.base_height = 0.0;
  f.scene.terrain.water_level.reset();
  f.scene.viewport.width = 320;
  f.scene.viewport.height = 240;
  f.scene.camera.near = 0.5;
  f.scene.camera.far = 60000.0;
}

// A view from near the field's edge over its ridges: most tiles in view, at several levels.
void look_over_the_ridges(Scene& scene) {
  scene.camera.position = {300.0, 400.0, 1800.0};
  scene.camera.pitch_deg = -14.0;
}

FrameRequest geometry_request(Backend backend, FrameSkips skips = {}) {
  FrameRequest request;
  request.backend = backend;
  request.skips = skips;
  request.outputs.primitive = true;
  request.outputs.depth = true;
  request.outputs.world_height = true;
  return request;
}

// Pixels whose ray, from a camera above every sample, reaches the plane of the lowest sample
// inside the texel centres' rectangle: it crosses the surface on the way (the mesh lies between
// the lowest and the highest sample, continuous over that rectangle), so a triangle must cover
// them. Returns (must cover, holes).
std::pair<std::uint64_t, std::uint64_t> seam_holes(const Scene& scene, const Frame& frame,
                                                   double lowest) {
  const CameraFrame cam = make_camera_frame(scene.camera, scene.viewport);
  const int width = scene.viewport.width, height = scene.viewport.height;
  const double inner = kHalfExtent * (1.0 - 1.0 / kSide) * (1.0 - 1e-6);
  std::uint64_t must_cover = 0, holes = 0;
  for (int py = 0; py < height; ++py) {
    for (int px = 0; px < width; ++px) {
      const double ndc_x = (px + 0.5) / width * 2 - 1, ndc_y = (py + 0.5) / height * 2 - 1;
      const glm::dvec3 ray = cam.forward + ndc_x * cam.tan_half_fov_x * cam.right +
                             ndc_y * cam.tan_half_fov_y * cam.up;
      if (!(ray.y < 0)) {
        continue;
      }
      const glm::dvec3 hit = cam.position + ((lowest - cam.position.y) / ray.y) * ray;
      if (std::abs(hit.x) >= inner || std::abs(hit.z) >= inner) {
        continue;
      }
      ++must_cover;
      holes += frame.image.primitive[std::size_t(py) * width + px] == raster::kNoPrimitive;
    }
  }
  return {must_cover, holes};
}

TEST_CASE("aGeoMipMapFrameShowsNoBackgroundThroughAnySeamOverACameraSweep", "[geomipmap]") {
  FieldScene f;
  build(f, false, 4.0);
  const double lowest = *std::min_element(f.samples.begin(), f.samples.end());
  const double highest = *std::max_element(f.samples.begin(), f.samples.end());
  std::uint64_t checked = 0, coarse = 0, culled = 0;
  for (int view = 0; view < 12; ++view) {
    Scene& scene = f.scene;
    const double a = 0.7 * view;
    scene.camera.position = {1500.0 * std::sin(a), highest + 20.0 + 37.0 * (view % 5),
                             1500.0 * std::cos(1.3 * a)};
    scene.camera.yaw_deg = 29.0 * view;
    scene.camera.pitch_deg = view < 9 ? -25.0 - 5.0 * view : -4.0 - view;
    scene.terrain.heightfield->geomipmap->pixel_error = 0.5 + (view % 4) * 2.5;
    const SceneResources resources = load_scene_resources(scene);
    const Frame frame = render_frame(scene, resources, geometry_request(Backend::kReference));
    const auto [must_cover, holes] = seam_holes(scene, frame, lowest);
    INFO("view " << view);
    CHECK(holes == 0);
    checked += must_cover;
    for (int level = 1; level < 5; ++level) {
      coarse += test::frame_counter(frame, "tiles drawn at level " + std::to_string(level));
    }
    culled += test::frame_counter(frame, "tiles outside the frustum");
  }
  // The sweep must test something: many pixels, coarse tiles beside fine ones, culling.
  CHECK(checked > 200000);
  CHECK(coarse > 100);
  CHECK(culled > 100);
}

TEST_CASE("everyCpuBackendDrawsTheGeoMipMapMeshTheSimdOneInTheReferencesBytes", "[geomipmap]") {
  FieldScene f;
  build(f, false, 1.0);
  look_over_the_ridges(f.scene);
  const SceneResources resources = load_scene_resources(f.scene);
  const Frame reference = render_frame(f.scene, resources, geometry_request(Backend::kReference));
  const Frame simd = render_frame(f.scene, resources, geometry_request(Backend::kSimd));
  const Frame precise =
      render_frame(f.scene, resources, geometry_request(Backend::kReferenceDouble));
  CHECK(simd.image.srgb == reference.image.srgb);
  CHECK(simd.image.primitive == reference.image.primitive);
  CHECK(simd.image.depth == reference.image.depth);
  // Double rounds the same vertices once less: the same triangles win nearly everywhere, and
  // every covered pixel's height lies within the field's samples (the B-spline's hull).
  const float lowest = *std::min_element(f.samples.begin(), f.samples.end());
  const float highest = *std::max_element(f.samples.begin(), f.samples.end());
  std::uint64_t covered = 0, same = 0;
  for (std::size_t k = 0; k < reference.image.primitive.size(); ++k) {
    if (reference.image.primitive[k] == raster::kNoPrimitive) {
      continue;
    }
    ++covered;
    same += precise.image.primitive[k] == reference.image.primitive[k];
    const float h = reference.image.world_height[k];
    CHECK((h >= lowest - 1e-3f && h <= highest + 1e-3f));
  }
  CHECK(covered > 30000);
  CHECK(double(same) > 0.99 * double(covered));
  CHECK(test::frame_counter(reference, "mesh vertices") > 1000);
  CHECK(test::frame_counter(reference, "triangles in the mesh") ==
        reference.stats.raster.triangles);
}

TEST_CASE("aGeoMipMapFrameOnAHighBaseHeightKeepsItsGeometryExactly", "[geomipmap]") {
  // Heights are camera-relative, the base added in double (field_mesh.h): the field lifted by
  // 1e6 with the camera gives the same depths and triangles bit for bit (a float lattice of
  // world heights would hold them to 1/16 there, terraces a frame shows).
  FieldScene f;
  build(f, false, 1.0);
  look_over_the_ridges(f.scene);
  const SceneResources resources = load_scene_resources(f.scene);
  const Frame low = render_frame(f.scene, resources, geometry_request(Backend::kReference));
  Scene high = f.scene;
  high.terrain.base_height = 1e6;
  high.camera.position[1] += 1e6;
  const Frame lifted =
      render_frame(high, load_scene_resources(high), geometry_request(Backend::kReference));
  CHECK(lifted.image.depth == low.image.depth);
  CHECK(lifted.image.primitive == low.image.primitive);
}

TEST_CASE("occlusionCullingOfGeoMipMapTilesChangesNoOutputAndSkipsTiles", "[geomipmap][skip]") {
  FieldScene f;
  build(f, true, 1.0);
  // On the plateau, looking toward the valley below its edge. The occluders are whole tiles'
  // floors in front of the near plane: the camera stands just inside the last row of tiles
  // (lattice rows 240..256 begin at z = 1743.5), over the middle of a column of tiles (x from
  // 0 to 249), so the floor of the plateau tile before it covers the valley's tiles.
  f.scene.camera.position = {125.0, 420.0, 1752.0};
  f.scene.camera.yaw_deg = 0.0;
  f.scene.camera.pitch_deg = -2.0;
  const SceneResources resources = load_scene_resources(f.scene);
  FrameSkips without;
  without.occluded_tiles = false;
  for (Backend backend : {Backend::kReference, Backend::kReferenceDouble}) {
    const Frame on = render_frame(f.scene, resources, geometry_request(backend));
    const Frame off = render_frame(f.scene, resources, geometry_request(backend, without));
    INFO(backend_name(backend));
    CHECK(on.image.srgb == off.image.srgb);
    CHECK(on.image.depth == off.image.depth);
    CHECK(on.image.world_height == off.image.world_height);
    // The primitive output names the triangle in the frame's drawn mesh, which the occluded
    // tiles leave: the ids after them differ (docs/heightfields.md), the pixels they name not.
    CHECK(on.image.primitive.size() == off.image.primitive.size());
    CHECK(test::frame_counter(on, "tiles occluded") > 20);
    CHECK(test::frame_counter(off, "tiles occluded") == 0);
    CHECK(test::frame_counter(on, "tiles drawn") < test::frame_counter(off, "tiles drawn"));
    // The occluded tiles' triangles face the camera inside the frustum: without the skip they
    // are set up and rasterised, and lose every depth test.
    CHECK(test::frame_counter(on, "triangles set up") <
          test::frame_counter(off, "triangles set up"));
  }
}

TEST_CASE("geomipmapIsRefusedWhereItIsNotBuiltNamingTheField", "[geomipmap]") {
  const std::string field =
      "terrain.heightfield={\"file\": \"f.pfm\", \"extent\": [0, 0, 10, 10], \"geomipmap\": {}}";
  const auto refused = [&](std::vector<std::string> overrides, const std::string& path,
                           const std::string& words) {
    overrides.insert(overrides.begin(), field);
    INFO(overrides.back());
    try {
      resolve_scene("default", overrides);
      FAIL("accepted");
    } catch (const SceneError& e) {
      CHECK(e.path() == path);
      CHECK_THAT(e.what(), Catch::Contains(words));
    }
  };
  refused({"terrain.heightfield.fractal=true"}, "terrain.heightfield.fractal", "allowed false");
  refused({"terrain.heightfield.level_of_detail=true"}, "terrain.heightfield.level_of_detail",
          "allowed false");
  refused({"lighting.shadows=true"}, "lighting.shadows", "allowed false");
  refused({"lighting.sky_occlusion=true"}, "lighting.sky_occlusion", "allowed false");
  refused({"water.reflect_terrain=true"}, "water.reflect_terrain", "allowed false");
  refused({"terrain.planet={\"radius\": 100000}"}, "terrain.planet.radius", "allowed 0");
  refused({"terrain.heightfield.geomipmap.tile_cells=24"},
          "terrain.heightfield.geomipmap.tile_cells", "not a power of two");
  refused({"terrain.heightfield.geomipmap.tile_cells=512"},
          "terrain.heightfield.geomipmap.tile_cells", "512");
  refused({"terrain.heightfield.geomipmap.pixel_error=0"},
          "terrain.heightfield.geomipmap.pixel_error", "0");
  refused({"terrain.heightfield.geomipmap.pixel_error=nan"},
          "terrain.heightfield.geomipmap.pixel_error", "pixel_error");
  // null: the projected grid again.
  CHECK_FALSE(resolve_scene("default", {field, "terrain.heightfield.geomipmap=null"})
                  .terrain.heightfield->geomipmap.has_value());
}

TEST_CASE("theGlBackendRefusesAGeoMipMapSceneRatherThanDrawTheGrid", "[geomipmap]") {
  FieldScene f;
  build(f, false, 1.0);
  const std::filesystem::path scene = f.dir.path() / "scene.json";
  std::ofstream(scene) << scene_json_text(f.scene);
  const std::filesystem::path out = f.dir.path() / "gl.png";
  const test::CliResult r =
      test::run({"render", scene.string(), "--backend", "gl", "-o", out.string()});
  INFO(r.out << r.err);
  CHECK(r.code != 0);
  CHECK_FALSE(std::filesystem::exists(out));
  if (gl_backend_built() && r.err.find("no GL context") == std::string::npos) {
    test::require_refused(r, "terrain.heightfield.geomipmap is set", out);
  }
}

TEST_CASE("aGeoMipMapFrameBeyondTheMemoryBudgetIsRefusedBeforeItsMeshIsBuilt", "[geomipmap]") {
  FieldScene f;
  build(f, false, 0.01);  // every tile at level 0
  f.scene.camera.position = {0.0, 2000.0, 0.0};
  f.scene.camera.pitch_deg = -90.0;
  const SceneResources resources = load_scene_resources(f.scene);
  FrameRequest request = geometry_request(Backend::kReference);
  request.max_bin_bytes = 1u << 20;
  CHECK_THROWS_WITH(render_frame(f.scene, resources, request),
                    Catch::Contains("GeoMipMap mesh") && Catch::Contains("pixel_error"));
}

}  // namespace
}  // namespace relief
