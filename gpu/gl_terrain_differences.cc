#include "gpu/gl_terrain_differences.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/fbm.h"
#include "core/octave_coordinates.h"
#include "core/planet_bend.h"
#include "core/surface.h"

namespace relief::gpu {

namespace {

bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

// The values stages 2-4 leave at invalid vertices and in the padding.
bool at_defaults(const GridBuffers<float>& g, std::size_t k) {
  return g.dx[k] == 0.0f && g.dz[k] == 0.0f && g.sigma[k] == 0.0f && g.nu[k] == 1.0f &&
         g.valid[k] == 0 && g.height[k] == 0.0f && g.nx[k] == 0.0f && g.ny[k] == 1.0f &&
         g.nz[k] == 0.0f && g.slope[k] == 0.0f && g.water_depth[k] == 0.0f;
}

// The angle between two unit vectors, accurate for small angles too: atan2(|a x b|, a . b).
double angle(double ax, double ay, double az, double bx, double by, double bz) {
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz);
}

}  // namespace

TerrainDifferences terrain_differences(const GridBuffers<float>& r, const GridBuffers<float>& g) {
  TerrainDifferences d;
  double height_sq_sum = 0;
  for (int j = 0; j < r.layout.height; ++j) {
    for (int i = 0; i < r.layout.pitch; ++i) {
      const std::size_t k = r.layout.index(i, j);
      const bool valid_r = i < r.layout.width && r.valid[k];
      const bool valid_g = i < r.layout.width && g.valid[k];
      if (valid_r != valid_g) {
        ++d.valid_mismatches;
        continue;
      }
      if (!valid_r) {
        d.default_mismatches += at_defaults(r, k) && at_defaults(g, k) ? 0 : 1;
        continue;
      }
      ++d.vertices;
      const bool domain_same = same_bits(r.dx[k], g.dx[k]) && same_bits(r.dz[k], g.dz[k]) &&
                               same_bits(r.sigma[k], g.sigma[k]) && same_bits(r.nu[k], g.nu[k]);
      const bool height_same = same_bits(r.height[k], g.height[k]);
      const bool surface_same = same_bits(r.nx[k], g.nx[k]) && same_bits(r.ny[k], g.ny[k]) &&
                                same_bits(r.nz[k], g.nz[k]) && same_bits(r.slope[k], g.slope[k]) &&
                                same_bits(r.water_depth[k], g.water_depth[k]);
      d.identical_domain += domain_same ? 1 : 0;
      d.identical_height += height_same ? 1 : 0;
      d.identical_surface += surface_same ? 1 : 0;
      // A planet's bend (both sides bent, or neither: the plane).
      const bool bent = !r.bent_x.empty() && !g.bent_x.empty();
      const bool bent_same =
          !bent ||
          (same_bits(r.bent_x[k], g.bent_x[k]) && same_bits(r.bent_y[k], g.bent_y[k]) &&
           same_bits(r.bent_z[k], g.bent_z[k]) && same_bits(r.bent_drop[k], g.bent_drop[k]));
      d.identical += domain_same && height_same && surface_same && bent_same ? 1 : 0;
      if (bent) {
        const double bx = r.bent_x[k], by = r.bent_y[k], bz = r.bent_z[k];
        const double error = std::max(
            {std::abs(bx - g.bent_x[k]), std::abs(by - g.bent_y[k]), std::abs(bz - g.bent_z[k])});
        const double size = std::sqrt(bx * bx + by * by + bz * bz);
        if (error > 0) {
          d.bent_max_rel = std::max(d.bent_max_rel, size > 0 ? error / size : error);
        }
      }
      const double distance = std::hypot(double(r.dx[k]), double(r.dz[k]));
      const double domain =
          std::max(std::abs(double(r.dx[k]) - g.dx[k]), std::abs(double(r.dz[k]) - g.dz[k]));
      if (domain > 0) {
        d.domain_max_rel = std::max(d.domain_max_rel, domain / distance);
      }
      const double sigma = std::abs(double(r.sigma[k]) - g.sigma[k]);
      if (sigma > 0) {
        d.sigma_max_rel = std::max(d.sigma_max_rel, sigma / std::max(distance, double(r.sigma[k])));
      }
      d.nu_max_abs = std::max(d.nu_max_abs, std::abs(double(r.nu[k]) - g.nu[k]));
      const double height = std::abs(double(r.height[k]) - g.height[k]);
      d.height_max_abs = std::max(d.height_max_abs, height);
      height_sq_sum += height * height;
      d.normal_max_angle =
          std::max(d.normal_max_angle, angle(r.nx[k], r.ny[k], r.nz[k], g.nx[k], g.ny[k], g.nz[k]));
      d.slope_max_rel =
          std::max(d.slope_max_rel, std::abs(double(r.slope[k]) - g.slope[k]) / (1.0 + r.slope[k]));
      d.water_max_abs =
          std::max(d.water_max_abs, std::abs(double(r.water_depth[k]) - g.water_depth[k]));
    }
  }
  if (d.vertices > 0) {
    d.height_rms_abs = std::sqrt(height_sq_sum / double(d.vertices));
  }
  return d;
}

GridBuffers<float> staged_reference(const FramePlan& plan, const GridBuffers<float>& cpu,
                                    const GridBuffers<float>& gl) {
  const GridLayout& layout = cpu.layout;
  GridBuffers<float> staged(layout);
  // Stage 2: the CPU's.
  staged.dx = cpu.dx;
  staged.dz = cpu.dz;
  staged.sigma = cpu.sigma;
  staged.nu = cpu.nu;
  staged.valid = cpu.valid;
  // Stage 3 on the GL's stage 2.
  const IndexRange all{0, layout.size()};
  TerrainParams<float> params = make_terrain_params<float>(plan);
  choose_coordinate_forms(plan.terrain, octave_reach<float>(all, gl.dx, gl.dz, gl.nu, gl.valid),
                          params.fbm);
  evaluate_fbm<float>(params.fbm, *plan.terrain.lattice, all, gl.dx, gl.dz, gl.nu, gl.valid,
                      staged.height);
  if (params.sketch.enabled != 0) {  // §3's sketch, stage 3's second part
    add_sketch<float>(params.sketch, plan.terrain.sketch->heights, all, gl.dx, gl.dz, gl.nu,
                      gl.valid, staged.height);
  }
  // Stage 4 on the GL's stages 2 and 3.
  const SurfaceInputs<float> inputs{gl.dx, gl.dz, gl.height, gl.valid, {}};
  surface_pass<float>(params.surface, RowRange{0, layout.height}, inputs, staged.surface());
  if (params.planet.enabled != 0) {  // the bend and the normals' rotation (planet_bend.h)
    staged.allocate_bent();
    bend_vertices<float>(params.planet, all, gl.dx, gl.dz, gl.height, gl.valid, staged.bent());
    bend_normals<float>(params.planet, all, gl.dx, gl.dz, gl.valid, staged.nx, staged.ny,
                        staged.nz);
  }
  return staged;
}

}  // namespace relief::gpu
