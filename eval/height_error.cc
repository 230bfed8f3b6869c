#include "eval/height_error.h"

#include <algorithm>
#include <cmath>

#include "core/octave_coordinates.h"
#include "core/stage_params.h"
#include "core/terrain_stages.h"

namespace relief {

VertexHeightError vertex_height_error(const Scene& scene, const NoiseLattice& lattice,
                                      Backend backend, const HeightSketch* sketch) {
  const TerrainRun<float> run = run_terrain_stages<float>(scene, lattice, backend, sketch);
  const GridLayout& layout = run.plan.layout;
  GridBuffers<double> exact(layout);
  for (std::size_t k = 0; k < layout.size(); ++k) {
    exact.dx[k] = run.grid.dx[k];
    exact.dz[k] = run.grid.dz[k];
    exact.nu[k] = run.grid.nu[k];
    exact.valid[k] = run.grid.valid[k];
  }
  // The double stage 3 at those points (terrain_stages.h, run_terrain_stages' fractal step).
  TerrainParams<double> params = make_terrain_params<double>(run.plan);
  choose_coordinate_forms(
      run.plan.terrain,
      octave_reach<double>(IndexRange{0, layout.size()}, exact.dx, exact.dz, exact.nu, exact.valid),
      params.fbm);
  evaluate_fbm_rows<double>(params.fbm, lattice, RowRange{0, layout.height}, exact, exact.valid);
  add_sketch_rows<double>(params.sketch, run.plan.terrain.sketch, RowRange{0, layout.height}, exact,
                          exact.valid);

  VertexHeightError out;
  out.amplitude = scene.terrain.amplitude;
  double sum_sq = 0;
  for (std::size_t k = 0; k < layout.size(); ++k) {
    if (run.grid.valid[k]) {
      const double e = std::abs(double(run.grid.height[k]) - exact.height[k]);
      out.max = std::max(out.max, e);
      sum_sq += e * e;
      ++out.vertices;
    }
  }
  out.rms = out.vertices > 0 ? std::sqrt(sum_sq / double(out.vertices)) : 0.0;  // count > 0
  return out;
}

}  // namespace relief
