// The Highway kernels of the culling stages and of the triangle set-up's per-vertex passes
// (simd/vertex_outcodes.h, simd/vertex_snap.h) against the portable loops, on every target
// this CPU runs: the same bits for every vertex, hostile ones included (NaN, infinities,
// denormals, zeros, w <= 0, coordinates at the guard band and the snap limit, snapping ties).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame_plan.h"
#include "core/lattice.h"
#include "core/scene/scene_json.h"
#include "core/terrain_stages.h"
#include "core/vertex_culling.h"
#include "pipeline/simd_setup.h"
#include "raster/triangle_setup.h"
#include "simd/vertex_outcodes.h"
#include "tests/simd/clip_cloud.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::check_prepared;
using test::clip_cloud;
using test::ClipCloud;
using test::hostile;
using test::same_bytes;

TEST_CASE("simdOutcodesAreTheCullingStagesOutcodesOnEveryTarget", "[simd]") {
  const EachTarget targets;
  for (const char* preset : {"default", "lake"}) {
    Scene scene = resolve_scene(preset, {"grid.width=61", "grid.height=47"});
    const NoiseLattice lattice = make_noise_lattice(scene.terrain.seed, scene.terrain.lattice_size);
    const FramePlan plan = make_frame_plan(scene, lattice);
    GridBuffers<float> grid(plan.layout);
    run_terrain_stages(plan, grid);
    const CullParams<float> params = make_cull_params<float>(plan);
    const RowRange rows{1, plan.layout.height - 2};
    // The grid as it is, then with hostile heights and coordinates (invalid vertices may hold
    // anything; valid ones at the frustum's planes, huge, tiny or not finite).
    for (int variant = 0; variant < 2; ++variant) {
      if (variant == 1) {
        test::TestRandom random(11);
        for (std::size_t k = 0; k < grid.layout.size(); ++k) {
          grid.dx[k] = hostile(random, 1e4);
          grid.dz[k] = hostile(random, 1e4);
          grid.height[k] = hostile(random, 1e3);
          grid.valid[k] = random.uniform(0, 1) < 0.9 ? 1 : 0;
        }
      }
      for (const bool own_heights : {false, true}) {
        const std::span<const float> height =
            own_heights ? std::span<const float>(grid.height) : std::span<const float>();
        std::vector<std::uint8_t> expected(plan.layout.size(), 0xee), got;
        vertex_outcodes<float>(params, rows, grid.dx, grid.dz, height, grid.valid, expected);
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          got.assign(plan.layout.size(), 0xee);
          simd::vertex_outcodes(params, rows, grid.dx, grid.dz, height, grid.valid, got);
          INFO(preset << ", " << target << ", variant " << variant << ", own heights "
                      << own_heights);
          CHECK(same_bytes(got, expected));
        }
      }
    }
  }
}

TEST_CASE("simdVertexSnappingIsThePortableSnappingOnEveryTarget", "[simd]") {
  const EachTarget targets;
  raster::RasterState state;
  state.width = 1280;
  state.height = 1024;
  state.viewport = {0, 0, 1280, 1024};
  const raster::TriangleSetup portable(state);
  raster::TriangleSetup kernels(state);
  kernels.set_snap_kernels(&simd_snap_kernels());
  const std::size_t count = 4099;  // not a multiple of any vector
  const ClipCloud cloud = clip_cloud(count, portable.snap_constants());
  const raster::ClipVertices vertices{cloud.x, cloud.y, cloud.z, cloud.w};
  const std::span<const std::uint8_t> none;
  for (const auto& [valid, need] :
       {std::pair{std::span<const std::uint8_t>(cloud.valid),
                  std::span<const std::uint8_t>(cloud.need)},
        std::pair{none, std::span<const std::uint8_t>(cloud.need)},
        std::pair{std::span<const std::uint8_t>(cloud.valid), none}, std::pair{none, none}}) {
    for (const auto& [begin, end] : {std::pair<std::size_t, std::size_t>{0, count},
                                     std::pair<std::size_t, std::size_t>{3, 3 + 7},
                                     std::pair<std::size_t, std::size_t>{17, count - 5}}) {
      raster::PreparedVertices want, got;
      portable.prepare_vertices(vertices, begin, end, valid, need, want);
      std::size_t snapped = 0;
      for (const std::uint8_t f : want.flags) {
        snapped += (f & raster::PreparedVertices::kSnapped) != 0;
      }
      CHECK(snapped > 0);  // the comparison covers snapped vertices
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        kernels.prepare_vertices(vertices, begin, end, valid, need, got);
        INFO(target << ", vertices " << begin << " to " << end << ", valid " << valid.size()
                    << ", need " << need.size());
        check_prepared(got, want);
      }
    }
  }
}

}  // namespace
}  // namespace relief
