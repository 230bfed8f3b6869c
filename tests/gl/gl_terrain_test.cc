// The GL compute stages 1-4 (gpu/gl_terrain.h) against the CPU reference stages in float, on
// Mesa's llvmpipe (any GL 4.5 where there is one): whole frames of every preset and of cameras
// and terrains that stress the float paths, stage 3 alone at random points in both coordinate
// forms and every interpolant, and the frame's need flags. The bounds, and why llvmpipe must
// be bit-identical: docs/gl-backend.md.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <catch2/catch.hpp>

#include "core/fbm.h"
#include "core/octave_coordinates.h"
#include "core/scene/scene_json.h"
#include "core/surface.h"
#include "core/terrain_stages.h"
#include "core/vertex_culling.h"
#include "gpu/gl_terrain.h"
#include "tests/gl/gl_terrain_support.h"
#include "tests/gl/gl_test_context.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// Odd sizes: the last row's work group overhangs the pitch, and the padding columns are
// checked too.
constexpr int kWidth = 90;
constexpr int kHeight = 77;

bool exact() {
  return test::gl_is_exact();
}

TEST_CASE("glTerrainStagesMatchTheCpuOnEveryPreset", "[gl]") {
  for (const char* preset : {"default", "alpine", "badlands", "craters", "dunes", "island", "lake",
                             "lava", "plain", "planet"}) {
    const test::GlTerrainRun run = test::run_cpu_and_gl(preset, {}, kWidth, kHeight);
    test::check_gl_terrain(run, exact(), preset);
  }
}

TEST_CASE("glTerrainStagesMatchTheCpuWhereFloatIsStressed", "[gl]") {
  // docs/terrain-spec.md's cases B, C and E: non-integer lacunarity 1e9 out, a camera 1e12
  // out, and H = 0.05 with 24 octaves, whose octaves 8 to 23 take the exact coordinate form
  // (Dekker's two-product and two-sum: wrong without `precise`); then the warp with a rotated
  // start, the two other interpolants, and cameras looking down and at the horizon.
  const std::vector<std::pair<const char*, std::vector<std::string>>> cases = {
      {"default", {"terrain.r=2.17", "camera.position=[1e9,700,2.5e8]"}},
      {"default", {"camera.position=[1e12,700,-1e12]"}},
      {"default", {"terrain.H=0.05", "terrain.last_octave=23"}},
      {"lava", {"terrain.warp.r0=[3,4]", "terrain.warp.t0=[0.5,-0.25]"}},
      {"alpine", {"terrain.interpolant=\"linear\"", "camera.pitch_deg=-35"}},
      {"dunes", {"terrain.interpolant=\"cubic\"", "camera.pitch_deg=12"}},
      {"default", {"terrain.lod.fractional=false", "terrain.lod.bias=0.37"}},
      // §3's sketch far from the origin, seen from outside its extent and over it.
      {"island",
       {"camera.position=[1004000,1400,1014500]",
        "terrain.sketch.extent=[986000,986000,1014000,1014000]"}},
      {"island", {"camera.position=[-20000,300,-25000]", "camera.pitch_deg=-20"}},
      // A planet (docs/planet.md) inside the equal-angle band (b about 0.13) and near the
      // surface (the plain projected grid on the sphere, the horizon cutting rows).
      {"planet", {"camera.position=[0,60000,0]", "camera.pitch_deg=-30"}},
      {"planet", {"camera.position=[0,700,0]", "camera.pitch_deg=-8"}},
  };
  int exact_octaves = 0;
  for (const auto& [preset, overrides] : cases) {
    const test::GlTerrainRun run = test::run_cpu_and_gl(preset, overrides, kWidth, kHeight);
    std::string what = preset;
    for (const std::string& o : overrides) {
      what += " " + o;
    }
    test::check_gl_terrain(run, exact(), what);
    for (int n = 0; n < run.cpu_fbm.count; ++n) {
      exact_octaves += run.cpu_fbm.exact_coordinates[n];
    }
  }
  CHECK(exact_octaves > 0);  // the exact form was exercised
}

TEST_CASE("glTerrainStagesMatchTheCpuOnAHeightFieldWithItsLevels", "[gl]") {
  // terrain.heightfield without the fractal, its levels of detail read from stage 2's count
  // (sketch.comp's levels > 1 branch): near vertices on level 0, far ones blending coarser
  // levels; with and without the levels.
  test::TempDir dir("gl-heightfield");
  const std::vector<float> values = test::random_unit_samples(65 * 49, 17);
  const std::string file = (dir.path() / "f.pfm").string();
  std::ofstream(file, std::ios::binary) << test::pfm_bytes(65, 49, values);
  for (const std::string levels : {"true", "false"}) {
    std::string field = "terrain.heightfield={\"file\":\"";
    field.append(file)
        .append("\",\"extent\":[-3000,-2000,3000,2000],\"height\":[0,900],")
        .append("\"level_of_detail\":")
        .append(levels)
        .append("}");
    const std::vector<std::string> overrides = {
        field, "terrain.base_height=0", "camera.position=[0,1200,2500]", "camera.pitch_deg=-15"};
    const test::GlTerrainRun run = test::run_cpu_and_gl("default", overrides, kWidth, kHeight);
    std::string what = "heightfield, levels ";
    test::check_gl_terrain(run, exact(), what.append(levels));
  }
}

// Stage 3 alone, from stage 2's streams uploaded from the CPU: random positions out to 1e7
// units, octave counts below 0, inside [1, N] and above N, some vertices invalid.
TEST_CASE("glFbmMatchesTheCpuAtRandomPointsInEveryCoordinateForm", "[gl]") {
  test::gl_context();
  test::TestRandom random(20240917);
  for (const auto& [preset, overrides] :
       std::vector<std::pair<const char*, std::vector<std::string>>>{
           {"default", {"terrain.H=0.05", "terrain.last_octave=23"}},
           {"lava", {}},
           {"alpine", {"terrain.interpolant=\"linear\""}},
           {"dunes", {"terrain.interpolant=\"cubic\"", "terrain.r=2.17"}}}) {
    const Scene scene = resolve_scene(preset, overrides);
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan plan = make_frame_plan(scene, lattice);
    const GridLayout layout = make_grid_layout(61, 23);
    GridBuffers<float> cpu(layout);
    for (std::size_t k = 0; k < layout.size(); ++k) {
      const double reach = std::pow(10.0, random.uniform(-3.0, 7.0));
      cpu.dx[k] = float(random.uniform(-reach, reach));
      cpu.dz[k] = float(random.uniform(-reach, reach));
      cpu.nu[k] = float(random.uniform(-1.0, double(plan.terrain.octaves.count) + 2.0));
      cpu.valid[k] = random.uniform(0.0, 1.0) < 0.9 ? 1 : 0;
    }
    gpu::GlTerrain terrain(layout, lattice);
    terrain.upload(gpu::GlStream::kDx, cpu.dx);
    terrain.upload(gpu::GlStream::kDz, cpu.dz);
    terrain.upload(gpu::GlStream::kNu, cpu.nu);
    terrain.upload_valid(cpu.valid);
    FbmParams<float> direct = make_fbm_params<float>(plan.terrain);
    for (int n = 0; n < direct.count; ++n) {
      direct.exact_coordinates[n] = 0;
    }
    FbmParams<float> chosen = make_fbm_params<float>(plan.terrain);
    choose_coordinate_forms(
        plan.terrain,
        octave_reach<float>(IndexRange{0, layout.size()}, cpu.dx, cpu.dz, cpu.nu, cpu.valid),
        chosen);
    const std::vector<std::pair<const char*, FbmParams<float>>> forms = {
        {"every octave exact", make_fbm_params<float>(plan.terrain)},
        {"every octave direct", direct},
        {"forms from the reach", chosen}};
    for (const auto& [form, params] : forms) {
      INFO(preset << ", " << form);
      const bool from_reach = form == std::string("forms from the reach");
      terrain.evaluate_fbm(params,
                           from_reach ? gpu::OctaveForms::kFromReach : gpu::OctaveForms::kAsGiven);
      evaluate_fbm<float>(params, lattice, IndexRange{0, layout.size()}, cpu.dx, cpu.dz, cpu.nu,
                          cpu.valid, cpu.height);
      std::vector<float> height(layout.size());
      terrain.read(gpu::GlStream::kHeight, height);
      const FbmParams<float> used = terrain.fbm_params();
      for (int n = 0; n < params.count; ++n) {
        CHECK(used.exact_coordinates[n] == params.exact_coordinates[n]);
      }
      double worst = 0;
      std::size_t identical = 0;
      for (std::size_t k = 0; k < layout.size(); ++k) {
        worst = std::max(worst, std::abs(double(height[k]) - cpu.height[k]));
        identical +=
            height[k] == cpu.height[k] && std::signbit(height[k]) == std::signbit(cpu.height[k]);
      }
      INFO(identical << " of " << layout.size() << " identical, worst " << worst);
      // The same inputs: + - * and floor only, except the warp's division and square root
      // (docs/gl-backend.md); the warped terrains are checked frame by frame above.
      if (exact() || !plan.terrain.warp.enabled) {
        CHECK(identical == layout.size());
      }
    }
  }
}

// The frame's culling (core/vertex_culling.h): stage 3 only where a need flag is set, stage 4
// only at kDraw vertices; the others keep the defaults.
TEST_CASE("glStagesHonourTheNeedFlags", "[gl]") {
  test::gl_context();
  const Scene scene = resolve_scene(
      "lake", {"grid.width=" + std::to_string(kWidth), "grid.height=" + std::to_string(kHeight)});
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const FramePlan plan = make_frame_plan(scene, lattice);
  TerrainParams<float> params = make_terrain_params<float>(plan);
  GridBuffers<float> cpu(plan.layout), gl(plan.layout);
  const RowRange all{0, plan.layout.height};
  project_domain<float>(params.domain, params.domain_rows, all, cpu.domain());
  test::TestRandom random(7);
  std::vector<std::uint8_t> need(plan.layout.size());
  std::size_t drawn = 0;
  for (std::size_t k = 0; k < need.size(); ++k) {
    const double u = random.uniform(0.0, 1.0);
    need[k] = !cpu.valid[k] ? 0 : (u < 0.3 ? 0 : (u < 0.5 ? kEvaluate : kEvaluate | kDraw));
    drawn += (need[k] & kDraw) != 0;
  }
  REQUIRE(drawn > 0);
  choose_coordinate_forms(
      plan.terrain,
      octave_reach<float>(IndexRange{0, plan.layout.size()}, cpu.dx, cpu.dz, cpu.nu, cpu.valid),
      params.fbm);
  evaluate_fbm_rows<float>(params.fbm, lattice, all, cpu, need);
  surface_pass<float>(params.surface, all, surface_inputs(cpu, need), cpu.surface());

  gpu::GlTerrain terrain(plan.layout, lattice);
  terrain.set_need(need);
  terrain.run(make_terrain_params<float>(plan));
  terrain.read_all(gl);
  const gpu::TerrainDifferences d = gpu::terrain_differences(cpu, gl);
  CHECK(d.valid_mismatches == 0);
  CHECK(d.default_mismatches == 0);
  for (std::size_t k = 0; k < need.size(); ++k) {
    if (!need[k]) {
      REQUIRE(gl.height[k] == 0.0f);
    }
    if (!(need[k] & kDraw)) {
      REQUIRE(gl.ny[k] == 1.0f);
      REQUIRE(gl.slope[k] == 0.0f);
    }
  }
  if (exact()) {
    CHECK(d.identical == d.vertices);
  }
  // Back to every valid vertex.
  terrain.set_need({});
  terrain.run(make_terrain_params<float>(plan));
  terrain.read_all(gl);
  GridBuffers<float> every(plan.layout);
  run_terrain_stages(plan, every);
  CHECK(gpu::terrain_differences(every, gl).valid_mismatches == 0);
  if (exact()) {
    CHECK(gpu::terrain_differences(every, gl).identical == d.vertices);
  }
}

// What a draw pass binds: one buffer per stream, of the stream's size, named and distinct.
TEST_CASE("glTerrainStreamsAreBuffersADrawPassCanBind", "[gl]") {
  test::gl_context();
  const Scene scene = test::small_scene(40);
  const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
  const GridLayout layout = make_grid_layout(40, 40);
  const gpu::GlTerrain terrain(layout, lattice);
  CHECK(terrain.layout().pitch == 48);
  std::vector<unsigned int> names;
  for (const gpu::GlStream stream : gpu::kGlStreams) {
    INFO(gpu::gl_stream_name(stream));
    if (gpu::is_bent_stream(stream)) {
      CHECK(terrain.buffer(stream) == 0);  // a planet frame's, allocated by its first bend
      continue;
    }
    const unsigned int name = terrain.buffer(stream);
    REQUIRE(name != 0);
    REQUIRE(glIsBuffer(name));
    GLint64 bytes = 0;
    glGetNamedBufferParameteri64v(name, GL_BUFFER_SIZE, &bytes);
    const std::size_t element = stream == gpu::GlStream::kValid ? 1 : sizeof(float);
    CHECK(static_cast<std::size_t>(bytes) == layout.size() * element);
    for (const unsigned int other : names) {
      CHECK(other != name);
    }
    names.push_back(name);
  }
}

}  // namespace
}  // namespace relief
