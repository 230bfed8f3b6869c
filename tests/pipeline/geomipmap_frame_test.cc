// terrain.heightfield.geomipmap through whole frames (pipeline/cpu_backend_mesh.cc): over a sweep
// of cameras no pixel shows the background where its ray must meet the field (the seam test of
// tests/raster/geomipmap_seam_test.cc, now through every stage of a frame); every CPU backend
// draws it (simd the reference's bytes, reference-double close); occlusion culling is a skip
// (the same outputs, fewer tiles); the scene rules refuse what is not built. The GL backend's
// mesh: tests/gl/gl_geomipmap_test.cc.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/camera.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "raster/raster_types.h"
#include "tests/support/bspline_oracle.h"
#include "tests/support/field_scene.h"
#include "tests/support/frame_counters.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::build;
using test::FieldScene;
using test::geometry_request;
using test::kHalfExtent;
using test::kSide;
using test::look_over_the_ridges;
using test::seam_holes;

TEST_CASE("aGeoMipMapFrameShowsNoBackgroundThroughAnySeamOverACameraSweep", "[geomipmap]") {
  FieldScene f;
  build(f, false, 4.0);
  const double lowest = *std::min_element(f.samples.begin(), f.samples.end());
  const double highest = *std::max_element(f.samples.begin(), f.samples.end());
  std::uint64_t checked = 0, coarse = 0, culled = 0;
  for (int view = 0; view < 12; ++view) {
    Scene& scene = f.scene;
    test::sweep_view(scene, view, highest);
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
  test::look_from_the_plateau(f.scene);
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
    // The primitive output numbers the triangles stably (Mesh::tile_first_id): an occluded
    // tile's triangles keep their numbers, so the ids after them do not shift.
    CHECK(on.image.primitive == off.image.primitive);
    CHECK(test::frame_counter(on, "tiles occluded") > 20);
    CHECK(test::frame_counter(off, "tiles occluded") == 0);
    CHECK(test::frame_counter(on, "tiles drawn") < test::frame_counter(off, "tiles drawn"));
    // The occluded tiles' triangles face the camera inside the frustum: without the skip they
    // are set up and rasterised, and lose every depth test.
    CHECK(test::frame_counter(on, "triangles set up") <
          test::frame_counter(off, "triangles set up"));
  }
}

// The sun's horizon over the field's own surface (the tests' B-spline of its samples, in
// double) from world (x, z) at field height h, or the surface there where the mesh's chord lies
// below it (a coarse tile's): the largest rise over run toward the sun, marched in steps of a
// quarter sample out to 3000 units.
double exact_horizon(const std::vector<float>& samples, double x, double z, double h, double ax,
                     double az) {
  const double cell = 2 * kHalfExtent / kSide;
  const auto surface = [&](double px, double pz) {
    return test::bspline_at(samples.data(), kSide, kSide, (px + kHalfExtent) / cell - 0.5,
                            (pz + kHalfExtent) / cell - 0.5);
  };
  const double from = std::max(h, surface(x, z));
  double horizon = -HUGE_VAL;
  for (double t = cell / 4; t <= 3000.0; t += cell / 4) {
    horizon = std::max(horizon, (surface(x + t * ax, z + t * az) - from) / t);
  }
  return horizon;
}

TEST_CASE("castShadowsOverAGeoMipMapMeshFollowExactRayCastingOverTheField",
          "[geomipmap][shadows]") {
  for (const double base : {0.0, 1e6 + 0.37}) {  // the mesh's and the cache's heights alike
    FieldScene f;
    build(f, false, 1.0);
    look_over_the_ridges(f.scene);
    f.scene.terrain.base_height = base;
    f.scene.camera.position[1] += base;
    f.scene.lighting.sun_elevation_deg = 6.0;  // the ridges' slopes reach 0.1 to 0.3
    f.scene.lighting.sun_azimuth_deg = 100.0;
    Scene shadowed = f.scene;
    shadowed.lighting.shadows = true;
    const SceneResources resources = load_scene_resources(shadowed);
    FrameRequest request = geometry_request(Backend::kReference);
    request.outputs.linear = true;
    request.outputs.normal = true;
    const Frame off = render_frame(f.scene, resources, request);
    const Frame on = render_frame(shadowed, resources, request);
    // Where exact ray casting over the field puts a pixel's point (rebuilt from its ray and its
    // height) well inside the shadow, facing the sun, it is darker; well out of it, unchanged.
    const double elevation = 6.0 * M_PI / 180.0;
    const double radius = shadowed.sky.sun_disc_deg * M_PI / 180.0;
    const double ax = std::sin(100.0 * M_PI / 180.0), az = -std::cos(100.0 * M_PI / 180.0);
    const glm::dvec3 sun(ax * std::cos(elevation), std::sin(elevation), az * std::cos(elevation));
    const CameraFrame cam = make_camera_frame(shadowed.camera, shadowed.viewport);
    const int width = shadowed.viewport.width, height = shadowed.viewport.height;
    std::uint64_t dark = 0, dark_agree = 0, lit = 0, lit_agree = 0;
    for (int py = 0; py < height; py += 2) {
      for (int px = 0; px < width; px += 2) {
        const std::size_t k = std::size_t(py) * width + px;
        for (int c = 0; c < 3; ++c) {  // shadows only darken
          REQUIRE(on.image.linear[3 * k + c] <= off.image.linear[3 * k + c]);
        }
        if (on.image.primitive[k] == raster::kNoPrimitive) {
          continue;
        }
        const glm::dvec3 n(on.image.normal[3 * k], on.image.normal[3 * k + 1],
                           on.image.normal[3 * k + 2]);
        const double ndc_x = (px + 0.5) / width * 2 - 1, ndc_y = (py + 0.5) / height * 2 - 1;
        const glm::dvec3 ray = cam.forward + ndc_x * cam.tan_half_fov_x * cam.right +
                               ndc_y * cam.tan_half_fov_y * cam.up;
        const double h = on.image.world_height[k];
        if (!(ray.y < 0) || glm::dot(n, sun) < 0.3) {
          continue;
        }
        const glm::dvec3 p = cam.position + ((h - cam.position.y) / ray.y) * ray;
        const double horizon = exact_horizon(f.samples, p.x, p.z, h - base, ax, az);
        const bool changed = on.image.linear[3 * k + 1] < off.image.linear[3 * k + 1];
        if (horizon > std::tan(elevation + radius) + 0.05) {
          ++dark;
          dark_agree += changed;
        } else if (horizon < std::tan(elevation - radius) - 0.05) {
          ++lit;
          lit_agree += !changed;
        }
      }
    }
    INFO("base " << base << ": " << dark_agree << " of " << dark << " pixels in the shadow darker, "
                 << lit_agree << " of " << lit << " in the sun unchanged");
    CHECK(dark > 300);
    CHECK(lit > 300);
    CHECK(double(dark_agree) >= 0.95 * double(dark));
    CHECK(double(lit_agree) >= 0.95 * double(lit));
    CHECK(test::frame_counter(on, "pixels beyond the shadow cache") == 0);
  }
}

// `request` with `skips`.
FrameRequest with_skips(FrameRequest request, const FrameSkips& skips) {
  request.skips = skips;
  return request;
}

TEST_CASE("shadowsSkyLightAndReflectionsOverAGeoMipMapMeshChangeNoByteWithTheirSkipsOff",
          "[geomipmap][shadows]") {
  FieldScene f;
  build(f, false, 1.0);
  look_over_the_ridges(f.scene);
  Scene& scene = f.scene;
  scene.lighting.sun_elevation_deg = 9.0;
  scene.lighting.shadows = true;
  scene.lighting.sky_occlusion = true;
  const SceneResources resources = load_scene_resources(scene);
  FrameSkips levels;  // every cache level built, every pixel's share evaluated
  levels.unread_shadow_levels = false;
  levels.lit_shadows = false;
  FrameSkips tiles;  // every tile in the frustum drawn: another list of triangles
  tiles.occluded_tiles = false;
  for (const Backend backend : {Backend::kReference, Backend::kReferenceDouble}) {
    INFO(backend_name(backend));
    FrameRequest request = geometry_request(backend);
    request.outputs.linear = true;
    const Frame skipped = render_frame(scene, resources, request);
    const Frame all_levels = render_frame(scene, resources, with_skips(request, levels));
    const Frame all_tiles = render_frame(scene, resources, with_skips(request, tiles));
    CHECK(all_levels.image.linear == skipped.image.linear);
    CHECK(all_tiles.image.linear == skipped.image.linear);
    // The skip had levels to leave out, and no pixel fell past the levels it kept.
    CHECK(test::frame_counter(skipped, "cache levels built") <
          test::frame_counter(all_levels, "cache levels built"));
    CHECK(test::frame_counter(skipped, "pixels beyond the shadow cache") == 0);
  }
  // With water reflecting the terrain (the rays read every coarser level), simd's bytes.
  scene.terrain.water_level = -40.0;
  scene.water.reflect_terrain = true;
  const SceneResources wet = load_scene_resources(scene);
  FrameRequest request = geometry_request(Backend::kReference);
  const Frame reference = render_frame(scene, wet, request);
  CHECK(render_frame(scene, wet, with_skips(request, levels)).image.srgb == reference.image.srgb);
  request.backend = Backend::kSimd;
  CHECK(render_frame(scene, wet, request).image.srgb == reference.image.srgb);
  CHECK(test::frame_counter(reference, "mesh vertices") > 1000);
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
