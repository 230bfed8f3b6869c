// The GL backend's GeoMipMapping (pipeline/gl_frame_mesh.h, gpu/shaders/mesh.comp) against the
// CPU's (pipeline/cpu_backend_mesh.cc): the same mesh, its vertices' stages 2-4 the CPU's bits
// where the GL's doubles are IEEE's (llvmpipe), whole frames through relief crosscheck, no
// background through any seam over a camera sweep, the same culling counters, occlusion
// culling a skip, the session's streams shared with grid frames, and the refusals.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "gpu/gl_terrain.h"
#include "pipeline/frame_mesh.h"
#include "pipeline/gl_backend.h"
#include "pipeline/memory_budget.h"
#include "pipeline/scene_resources.h"
#include "tests/gl/gl_arithmetic.h"
#include "tests/gl/gl_test_context.h"
#include "tests/oracles/gl_interpolation_bound.h"
#include "tests/support/cli_support.h"
#include "tests/support/field_scene.h"
#include "tests/support/frame_counters.h"

namespace relief {
namespace {

// Float ulps between a and b (0: the same bits; both finite).
std::int64_t ulps_apart(float a, float b) {
  const auto ordered = [](float v) {
    const std::int32_t bits = std::bit_cast<std::int32_t>(v);
    return bits < 0 ? std::int64_t(INT32_MIN) - bits : std::int64_t(bits);
  };
  return std::abs(ordered(a) - ordered(b));
}

struct StreamComparison {
  std::size_t values = 0, exact = 0;
  std::int64_t worst_ulps = 0;
  std::size_t beyond = 0;  // values outside their bound
};

// The mesh's vertices of both sides, every float stream: the CPU's layout is a prefix of GL's
// (rows of kMeshRowVertices both), the rest GL's padding, which must be invalid. Where this GL's
// double arithmetic is IEEE's (gl_arithmetic().double_as_cpu: llvmpipe), every value must be
// the CPU's bits. Elsewhere GLSL promises double operations only float's precision; a GL with
// real double arithmetic a few double ulps off may flip a float rounding (one float ulp), and
// dx, dz (a lattice position less the camera's, both up to `reach` from the origin) carry an
// absolute error of a few double ulps of `reach` where they are far smaller than it.
StreamComparison compare_mesh_streams(const GridBuffers<float>& cpu, const GridBuffers<float>& gl,
                                      double reach) {
  REQUIRE(cpu.layout.pitch == gl.layout.pitch);
  REQUIRE(cpu.valid.size() <= gl.valid.size());
  const bool exact = test::gl_arithmetic().double_as_cpu;
  const double position_error = 16.0 * std::ldexp(reach, -52);
  StreamComparison c;
  const std::vector<std::pair<const AlignedVector<float>*, const AlignedVector<float>*>> streams = {
      {&cpu.dx, &gl.dx},         {&cpu.dz, &gl.dz},
      {&cpu.sigma, &gl.sigma},   {&cpu.nu, &gl.nu},
      {&cpu.height, &gl.height}, {&cpu.nx, &gl.nx},
      {&cpu.ny, &gl.ny},         {&cpu.nz, &gl.nz},
      {&cpu.slope, &gl.slope},   {&cpu.water_depth, &gl.water_depth}};
  for (std::size_t k = 0; k < gl.valid.size(); ++k) {
    if (k >= cpu.valid.size()) {
      CHECK(gl.valid[k] == 0);
      continue;
    }
    CHECK(gl.valid[k] == cpu.valid[k]);
    if (cpu.valid[k] == 0) {
      continue;
    }
    for (std::size_t s = 0; s < streams.size(); ++s) {
      const float a = (*streams[s].first)[k], b = (*streams[s].second)[k];
      REQUIRE(std::isfinite(b));
      const std::int64_t ulps = ulps_apart(a, b);
      c.worst_ulps = std::max(c.worst_ulps, ulps);
      c.exact += ulps == 0;
      ++c.values;
      const bool position = s < 2;
      const bool within = exact
                              ? ulps == 0
                              : ulps <= 1 || (position && std::abs(double(a) - double(b)) <=
                                                              test::float_ulp(a) + position_error);
      c.beyond += within ? 0 : 1;
    }
  }
  return c;
}

void check_mesh_stages(const Scene& scene, const std::string& what, std::size_t least_vertices) {
  const SceneResources resources = load_scene_resources(scene);
  const MeshStages cpu = cpu_mesh_stages(scene, resources);
  const GridBuffers<float> gl = gl_mesh_stages(scene, resources);
  const HeightFieldSettings& field = *scene.terrain.heightfield;
  double reach = 0;
  for (const double e : field.extent) {
    reach = std::max(reach, std::abs(e));
  }
  reach += std::max(std::abs(scene.camera.position[0]), std::abs(scene.camera.position[2]));
  const StreamComparison c = compare_mesh_streams(cpu.grid, gl, reach);
  INFO(what << ": " << cpu.mesh.vertex_column.size() << " vertices, " << c.exact << " of "
            << c.values << " values bit-identical, worst " << c.worst_ulps
            << " ulps; double arithmetic as the CPU's: " << test::gl_arithmetic().double_as_cpu);
  CHECK(cpu.mesh.vertex_column.size() >= least_vertices);
  CHECK(c.beyond == 0);
}

// A field of `columns` x `rows` hashed samples (0 ... 100) over [-300, -200, 440, 260], drawn by
// tiles of `tile_cells`, seen from above its middle.
Scene small_field_scene(const test::TempDir& dir, int columns, int rows, int tile_cells) {
  std::vector<float> samples(std::size_t(columns) * rows);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    samples[k] = float(((k * 2654435761u) >> 7) % 1000) / 10.0f;
  }
  const std::filesystem::path file =
      dir.path() / ("field" + std::to_string(columns) + "x" + std::to_string(rows) + ".pfm");
  std::ofstream(file, std::ios::binary) << test::pfm_bytes(columns, rows, samples);
  Scene scene;
  HeightFieldSettings field;
  field.image = file.string();
  field.extent = {-300.0, -200.0, 440.0, 260.0};
  field.height = {0.0, 1.0};
  field.geomipmap = GeoMipMapSettings{tile_cells, 0.5, true};
  scene.terrain.heightfield = field;
  scene.terrain.base_height = 0.0;
  scene.terrain.water_level = 40.0;
  scene.viewport.width = 160;
  scene.viewport.height = 120;
  scene.camera.position = {70.0, 420.0, 30.0};
  scene.camera.pitch_deg = -70.0;
  return scene;
}

TEST_CASE("glGeoMipMapMeshStagesMatchTheCpusBitForBitWhereItsDoublesAreIeees", "[gl][geomipmap]") {
  test::FieldScene f;
  test::build(f, false, 1.0);
  test::look_over_the_ridges(f.scene);
  check_mesh_stages(f.scene, "ridges", 1000);
  Scene water = f.scene;
  water.terrain.water_level = 30.0;  // stage 4's water depth
  check_mesh_stages(water, "ridges under water at 30", 1000);
  Scene lifted = f.scene;  // heights camera-relative, the base added in double
  lifted.terrain.base_height = 1e6 + 0.37;
  lifted.camera.position[1] += 1e6 + 0.37;
  check_mesh_stages(lifted, "ridges lifted by 1e6 + 0.37", 1000);
  Scene interpolating = f.scene;  // the coefficients overshoot the samples
  interpolating.terrain.heightfield->interpolating = true;
  check_mesh_stages(interpolating, "ridges, interpolating", 1000);
  Scene far_away = f.scene;  // large camera-relative positions: 4e4 off the field's centre
  far_away.camera.position = {3.0e4, 900.0, 3.0e4};
  far_away.camera.yaw_deg = -45.0;  // toward the field
  far_away.camera.pitch_deg = -1.5;
  far_away.camera.far = 1e6;
  far_away.terrain.heightfield->geomipmap->pixel_error = 0.02;
  check_mesh_stages(far_away, "the camera 4e4 off the field", 1000);
  // Not square (a swapped width and height, or a wrong row stride, shows), lattices past the
  // last texel (the edge texels extended), the smallest and the largest tiles, 2 x 2 samples.
  const test::TempDir dir("gl-geomipmap-small");
  check_mesh_stages(small_field_scene(dir, 37, 23, 16), "37 x 23 samples, tiles of 16", 500);
  check_mesh_stages(small_field_scene(dir, 37, 23, 2), "37 x 23 samples, tiles of 2", 500);
  check_mesh_stages(small_field_scene(dir, 23, 37, 256), "23 x 37 samples, tiles of 256", 500);
  check_mesh_stages(small_field_scene(dir, 2, 2, 2), "2 x 2 samples, tiles of 2", 9);
}

TEST_CASE("glGeoMipMapFramesShowNoBackgroundThroughAnySeamOverACameraSweep", "[gl][geomipmap]") {
  test::FieldScene f;
  test::build(f, false, 4.0);
  const double lowest = *std::min_element(f.samples.begin(), f.samples.end());
  const double highest = *std::max_element(f.samples.begin(), f.samples.end());
  std::uint64_t checked = 0, covered = 0, same_triangle = 0;
  for (int view = 0; view < 12; view += 2) {  // every other view of the CPU's sweep
    Scene& scene = f.scene;
    test::sweep_view(scene, view, highest);
    const SceneResources resources = load_scene_resources(scene);
    const Frame gl = render_frame(scene, resources, test::geometry_request(Backend::kGl));
    const Frame cpu = render_frame(scene, resources, test::geometry_request(Backend::kReference));
    const auto [must_cover, holes] = test::seam_holes(scene, gl, lowest);
    INFO("view " << view);
    CHECK(holes == 0);
    checked += must_cover;
    // The same mesh, numbered alike: the same triangle wins nearly everywhere (GL snaps as
    // the CPU does on llvmpipe; docs/gl-shading.md).
    for (std::size_t k = 0; k < cpu.image.primitive.size(); ++k) {
      if (cpu.image.primitive[k] != raster::kNoPrimitive) {
        ++covered;
        same_triangle += gl.image.primitive[k] == cpu.image.primitive[k];
      }
    }
    for (const char* counter : {"tiles drawn", "tiles outside the frustum", "mesh vertices"}) {
      CHECK(test::frame_counter(gl, counter) == test::frame_counter(cpu, counter));
    }
    CHECK(gl.stats.raster.triangles == cpu.stats.raster.triangles);
  }
  CHECK(checked > 100000);
  CHECK(double(same_triangle) > 0.999 * double(covered));
}

TEST_CASE("crosscheckOfAGeoMipMapSceneComparesTheMeshStagesAndTheFrames", "[gl][geomipmap]") {
  test::FieldScene f;
  test::build(f, false, 1.0);
  test::look_over_the_ridges(f.scene);
  f.scene.terrain.water_level = 20.0;
  const std::filesystem::path scene = f.dir.path() / "scene.json";
  std::ofstream(scene) << scene_json_text(f.scene);
  const std::filesystem::path out = f.dir.path() / "crosscheck";
  const test::CliResult r = test::run({"crosscheck", scene.string(), "--out", out.string()});
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);  // PASS
  CHECK_THAT(r.out, Catch::Contains("GeoMipMap mesh rows"));
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "crosscheck.json"));
  // Stages 2-4 of the mesh bit-identical on llvmpipe, as the projected grid's.
  CHECK(j["grid"]["vertices"].get<double>() > 1000);
  CHECK(j["grid"]["valid_mismatch"] == 0);
  CHECK(j["grid"]["max_height_error"] == 0.0);
  CHECK(j["grid"]["max_normal_angle_deg"] == 0.0);
  CHECK(j["pixels"]["primitive_mismatch"].get<double>() <=
        1e-3 * j["pixels"]["count"].get<double>());
  CHECK(j["srgb"]["max_error"].get<double>() <= 1.0 / 255 + 1e-7);
}

TEST_CASE("glOcclusionCullingOfGeoMipMapTilesChangesNoOutputAndSkipsTiles",
          "[gl][geomipmap][skip]") {
  test::FieldScene f;
  test::build(f, true, 1.0);
  test::look_from_the_plateau(f.scene);
  const SceneResources resources = load_scene_resources(f.scene);
  FrameSkips without;
  without.occluded_tiles = false;
  const Frame on = render_frame(f.scene, resources, test::geometry_request(Backend::kGl));
  const Frame off = render_frame(f.scene, resources, test::geometry_request(Backend::kGl, without));
  CHECK(on.image.srgb == off.image.srgb);
  CHECK(on.image.depth == off.image.depth);
  CHECK(on.image.world_height == off.image.world_height);
  CHECK(on.image.primitive == off.image.primitive);  // stable triangle numbers
  CHECK(test::frame_counter(on, "tiles occluded") > 20);
  CHECK(test::frame_counter(off, "tiles occluded") == 0);
  CHECK(on.stats.raster.triangles < off.stats.raster.triangles);
}

TEST_CASE("aGlGridFrameAfterAGeoMipMapFrameHasTheBytesOfAFreshOne", "[gl][geomipmap]") {
  test::FieldScene f;
  test::build(f, false, 1.0);
  test::look_over_the_ridges(f.scene);
  // The same field by a projected grid of the streams' shape the mesh leaves in the session
  // (two rows of 4096: the mesh has fewer than 8192 vertices), so the grid frame reuses them.
  Scene grid = f.scene;
  grid.terrain.heightfield->geomipmap.reset();
  grid.grid.width = kMeshRowVertices;
  grid.grid.height = 2;
  const SceneResources mesh_resources = load_scene_resources(f.scene);
  const SceneResources grid_resources = load_scene_resources(grid);
  forget_gl_scene();
  const Frame fresh = render_frame(grid, grid_resources, test::geometry_request(Backend::kGl));
  const Frame mesh = render_frame(f.scene, mesh_resources, test::geometry_request(Backend::kGl));
  const Frame after = render_frame(grid, grid_resources, test::geometry_request(Backend::kGl));
  CHECK(test::frame_counter(mesh, "tiles drawn") > 0);
  CHECK(after.image.srgb == fresh.image.srgb);
  CHECK(after.image.depth == fresh.image.depth);
  CHECK(after.image.primitive == fresh.image.primitive);
}

TEST_CASE("aGlGeoMipMapFrameWithEveryTileCulledDrawsTheBackgroundAlone", "[gl][geomipmap]") {
  test::FieldScene f;
  test::build(f, false, 1.0);
  f.scene.camera.position = {0.0, 500.0, 0.0};
  f.scene.camera.pitch_deg = 60.0;  // the sky: the frustum holds no tile
  const SceneResources resources = load_scene_resources(f.scene);
  const Frame gl = render_frame(f.scene, resources, test::geometry_request(Backend::kGl));
  const Frame cpu = render_frame(f.scene, resources, test::geometry_request(Backend::kReference));
  CHECK(test::frame_counter(gl, "tiles drawn") == 0);
  CHECK(gl.stats.raster.triangles == 0);
  CHECK(std::all_of(gl.image.primitive.begin(), gl.image.primitive.end(),
                    [](std::uint32_t p) { return p == raster::kNoPrimitive; }));
  REQUIRE(gl.image.srgb.size() == cpu.image.srgb.size());
  for (std::size_t k = 0; k < cpu.image.srgb.size(); ++k) {
    REQUIRE(std::abs(int(gl.image.srgb[k]) - int(cpu.image.srgb[k])) <= 1);
  }
}

TEST_CASE("aGlGeoMipMapFrameBeyondTheMemoryBudgetIsRefusedBeforeItsMeshIsBuilt",
          "[gl][geomipmap]") {
  test::FieldScene f;
  test::build(f, false, 0.01);  // every tile at level 0
  f.scene.camera.position = {0.0, 2000.0, 0.0};
  f.scene.camera.pitch_deg = -90.0;
  const SceneResources resources = load_scene_resources(f.scene);
  FrameRequest request = test::geometry_request(Backend::kGl);
  request.max_bin_bytes = 1u << 20;
  CHECK_THROWS_AS(render_frame(f.scene, resources, request), MemoryLimitError);
  CHECK_THROWS_WITH(render_frame(f.scene, resources, request), Catch::Contains("GeoMipMap mesh") &&
                                                                   Catch::Contains("GL side") &&
                                                                   Catch::Contains("pixel_error"));
  request.max_bin_bytes = UINT64_MAX;  // the session is still usable
  CHECK(render_frame(f.scene, resources, request).image.width == f.scene.viewport.width);
}

TEST_CASE("glTerrainMeshPassesRefuseInputsThatDoNotFit", "[gl][geomipmap]") {
  test::gl_context();
  const NoiseLattice lattice = make_noise_lattice(1, 32);
  const std::vector<std::int32_t> three = {0, 1, 2}, two = {0, 1};
  SECTION("rows that are not whole work groups") {
    gpu::GlTerrain terrain(make_grid_layout(33, 4), lattice);
    CHECK_THROWS_WITH(terrain.set_mesh_vertices(two, two), Catch::Contains("work groups"));
  }
  const GridLayout layout = make_grid_layout(kMeshRowVertices, 2);
  gpu::GlTerrain terrain(layout, lattice);  // no sketch: no field's texels
  SECTION("columns and rows of different lengths") {
    CHECK_THROWS_WITH(terrain.set_mesh_vertices(three, two),
                      Catch::Contains("3 columns and 2 rows"));
  }
  SECTION("more vertices than the streams hold") {
    const std::vector<std::int32_t> many(layout.size() + 1, 0);
    CHECK_THROWS_WITH(terrain.set_mesh_vertices(many, many), Catch::Contains("the streams hold"));
  }
  SECTION("passes before the vertices, or without the field's texels") {
    FieldMesh field;
    field.cell_x = field.cell_z = 1.0;
    CHECK_THROWS_WITH(terrain.mesh_domain(field, 0.0, 0.0), Catch::Contains("no mesh vertices"));
    CHECK_THROWS_WITH(terrain.mesh_heights(0.0), Catch::Contains("no mesh vertices"));
    CHECK_THROWS_WITH(terrain.mesh_surface(field, SurfaceParams<float>{}),
                      Catch::Contains("no mesh vertices"));
    terrain.set_mesh_vertices(two, two);
    CHECK_NOTHROW(terrain.mesh_domain(field, 0.0, 0.0));  // needs no texels
    CHECK_THROWS_WITH(terrain.mesh_heights(0.0), Catch::Contains("no field's texels"));
    CHECK_THROWS_WITH(terrain.mesh_surface(field, SurfaceParams<float>{}),
                      Catch::Contains("no field's texels"));
  }
  CHECK(glGetError() == GL_NO_ERROR);
}

}  // namespace
}  // namespace relief
