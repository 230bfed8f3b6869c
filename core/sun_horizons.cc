#include "core/sun_horizons.h"

#include <algorithm>
#include <cmath>

#include "core/horizon_lines.h"
#include "core/limits.h"
#include "core/lod_rule.h"
#include "core/sky_horizons.h"
#include "core/vertex_culling.h"

namespace relief {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// tan of an angle at or past +-90 degrees: +-1e30, past any slope a cache holds.
constexpr double kHugeTangent = 1e30;

double clamped_tangent(double angle_deg) {
  if (angle_deg >= 90.0) {
    return kHugeTangent;
  }
  if (angle_deg <= -90.0) {
    return -kHugeTangent;
  }
  return std::tan(angle_deg * kDegree);
}

// The octave count stage 2's rule gives a vertex spacing of `spacing` (frame_plan.h, LodPlan):
// the cache's heights are what the frame's grid would carry at its spacing.
double level_octaves(const LodPlan& lod, double spacing) {
  const double nu =
      lod_octave_count(lod.c0, lod.c1, lod.nu_max, limits::kMinSpacingSq, spacing * spacing);
  return lod.whole_octaves ? std::ceil(nu) : nu;
}

}  // namespace

ShadowGeometry shadow_geometry(const CameraFrame& camera, int viewport_height, int resolution) {
  // Pixels lie within the far plane's corner, or a little past it (depth has no far plane,
  // and the grid's margin cells reach beyond it): the levels are laid out to four times that;
  // a frame builds those its pixels and their occluders reach (shadow_level_range).
  // sqrt of at least 1; the viewport is at least 1 pixel high; inner >= 62 (N >= 128).
  const double corner = std::sqrt(1.0 + camera.tan_half_fov_x * camera.tan_half_fov_x +
                                  camera.tan_half_fov_y * camera.tan_half_fov_y);
  ShadowGeometry g;
  g.extent = 4.0 * camera.far * corner;
  // Level 0's spacing: four pixels' footprint at the near plane, rounded down to a power of
  // two; as many levels as cover the extent, at most kMaxShadowLevels (level 0 grows then).
  // Neither depends on where the camera is, so its moves never change the levels' lattices.
  const double inner = double(resolution / 2 - 2);  // centre to a level's usable edge, samples
  const double pixel_angle = 2.0 * camera.tan_half_fov_y / viewport_height;
  g.spacing = std::exp2(std::floor(
      std::log2(std::max(4.0 * pixel_angle * camera.near, g.extent / (inner * 0x1p+30)))));  // > 0
  g.levels = 1;
  while (g.levels < kMaxShadowLevels && inner * g.spacing * std::exp2(g.levels - 1) < g.extent) {
    ++g.levels;
  }
  while (inner * g.spacing * std::exp2(g.levels - 1) < g.extent) {
    g.spacing *= 2.0;
  }
  return g;
}

int shadow_cache_levels(const Scene& scene) {
  const bool planet = scene.terrain.planet && scene.terrain.planet->radius != 0.0;
  const bool sun_up = scene.lighting.sun_elevation_deg + scene.sky.sun_disc_deg > 0.0;
  const bool reflections = scene.water.reflect_terrain && scene.terrain.water_level;
  if (planet ||
      !((scene.lighting.shadows && sun_up) || scene.lighting.sky_occlusion || reflections)) {
    return 0;
  }
  return shadow_geometry(make_camera_frame(scene.camera, scene.viewport), scene.viewport.height,
                         scene.lighting.shadow_resolution)
      .levels;
}

ShadowPlan make_shadow_plan(const Scene& scene, const FramePlan& frame) {
  ShadowPlan plan;
  const LightingSettings& light = scene.lighting;
  const bool reflections = scene.water.reflect_terrain && frame.water_enabled;
  if ((!light.shadows && !light.sky_occlusion && !reflections) || frame.planet.enabled) {
    return plan;
  }
  plan.enabled = light.shadows;
  plan.sky = light.sky_occlusion;
  plan.reflections = reflections;
  plan.water = frame.water_enabled;
  plan.water_level = frame.relative_water_level;
  const double elevation = light.sun_elevation_deg, radius = scene.sky.sun_disc_deg;
  const double azimuth = light.sun_azimuth_deg * kDegree;
  plan.axis_x = std::sin(azimuth);
  plan.axis_z = -std::cos(azimuth);
  plan.sin_elevation = std::sin(elevation * kDegree);
  plan.cos_elevation = std::cos(elevation * kDegree);
  plan.sin_radius = std::sin(radius * kDegree);
  plan.lit_tangent = clamped_tangent(elevation - radius);
  plan.dark_tangent = clamped_tangent(elevation + radius);
  // With the sun set no pixel reads the sun's horizons; sky light and the reflections still
  // read the cache.
  plan.sun_set = elevation + radius <= 0.0;
  if (plan.sun_set && !plan.sky && !plan.reflections) {
    return plan;
  }

  const CameraFrame& camera = frame.camera;
  const ShadowGeometry geometry =
      shadow_geometry(camera, scene.viewport.height, light.shadow_resolution);
  // An occluder lies where the disc's lower edge still meets terrain: the whole height range
  // climbed at tan(elevation - radius) (> 0), or the pixels' own reach where the sun is that low.
  const double span = std::max(0.0, frame.bounds.world_max - frame.bounds.world_min);
  const double pixels = geometry.extent / 4.0;
  if (plan.enabled && !plan.sun_set) {
    plan.reach = plan.lit_tangent > 0.0 ? std::min(span / plan.lit_tangent, pixels) : pixels;
  }
  // The sky's: where the height range rises kSkyReachTangent (sky_horizons.h).
  plan.sky_reach = plan.sky ? std::min(span / kSkyReachTangent, pixels) : 0.0;
  const int n = light.shadow_resolution;
  plan.resolution = n;
  const int levels = geometry.levels;
  const double spacing = geometry.spacing;
  plan.levels = levels;
  const double cam_u = camera.position.x * plan.axis_x + camera.position.z * plan.axis_z;
  const double cam_v = camera.position.z * plan.axis_x - camera.position.x * plan.axis_z;
  for (int level = 0; level < levels; ++level) {
    const double s = spacing * std::exp2(level);
    plan.spacing[level] = s;
    // Anchored to the world lattice of spacing s: sample 0 at a whole multiple of s.
    // s > 0 (shadow_geometry).
    plan.origin_u[level] = (std::floor(cam_u / s) - n / 2) * s - cam_u;
    plan.origin_v[level] = (std::floor(cam_v / s) - n / 2) * s - cam_v;
    plan.nu[level] = level_octaves(frame.lod, s);
  }
  return plan;
}

OctaveReach shadow_octave_reach(const ShadowPlan& plan) {
  OctaveReach by_finest;
  for (int level = 0; level < plan.levels; ++level) {
    const int n = finest_octave(plan.nu[level]);
    const double last = double(plan.resolution - 1) * plan.spacing[level];
    double extent = 0;
    for (const double u : {plan.origin_u[level], plan.origin_u[level] + last}) {
      for (const double v : {plan.origin_v[level], plan.origin_v[level] + last}) {
        // A linear function's largest magnitude over a rectangle is at a corner.
        extent = std::max({extent, std::abs(u * plan.axis_x - v * plan.axis_z),
                           std::abs(u * plan.axis_z + v * plan.axis_x)});
      }
    }
    by_finest.extent[n] = std::max(by_finest.extent[n], extent * (1.0 + 1e-6));
  }
  return running_reach(by_finest);
}

template <class Real>
ShadowParams<Real> make_shadow_params(const ShadowPlan& plan) {
  ShadowParams<Real> p;
  p.enabled = plan.enabled ? 1 : 0;
  p.sun_set = plan.sun_set ? 1 : 0;
  p.resolution = plan.resolution;
  p.levels = plan.levels;
  p.end_level = plan.levels;
  p.axis_x = Real(plan.axis_x);
  p.axis_z = Real(plan.axis_z);
  for (int level = 0; level < plan.levels; ++level) {
    p.spacing[level] = Real(plan.spacing[level]);
    p.inv_spacing[level] = Real(1.0 / plan.spacing[level]);  // spacing > 0
    p.origin_u[level] = Real(plan.origin_u[level]);
    p.origin_v[level] = Real(plan.origin_v[level]);
    p.nu[level] = Real(plan.nu[level]);
  }
  p.sky = plan.sky ? 1 : 0;
  p.reach = Real(plan.reach);
  p.sky_reach = Real(plan.sky_reach);
  if (plan.levels > 0) {  // N >= 128: N / 32 >= 4
    p.blend_samples = Real(plan.resolution / 32);
    p.inv_blend_samples = Real(1.0 / double(plan.resolution / 32));
  }
  p.sin_elevation = Real(plan.sin_elevation);
  p.cos_elevation = Real(plan.cos_elevation);
  p.sin_radius = Real(plan.sin_radius);
  p.lit_tangent = Real(plan.lit_tangent);
  p.dark_tangent = Real(plan.dark_tangent);
  p.water = plan.water ? 1 : 0;
  p.water_level = Real(plan.water_level);
  p.reflections = plan.reflections ? 1 : 0;
  return p;
}

template <class Real>
void SunHorizonCache<Real>::allocate(int n, int first, int end, bool sun, bool with_sky) {
  resolution = n;
  first_level = first;
  end_level = end;
  const std::size_t samples = std::size_t(n) * n * std::size_t(std::max(0, end - first));
  height.resize(samples);
  tangent.resize(sun ? samples : 0);
  inv_distance.resize(sun ? samples : 0);
  sky.resize(with_sky ? samples : 0);
}

template <class Real>
DrawnExtent drawn_extent(const ShadowPlan& plan, const GridLayout& layout, RowRange rows,
                         std::span<const Real> dx, std::span<const Real> dz,
                         std::span<const Real> height, std::span<const std::uint8_t> valid,
                         std::span<const std::uint8_t> need) {
  const auto frame = [&](std::size_t k, double& u, double& v) {
    u = double(dx[k]) * plan.axis_x + double(dz[k]) * plan.axis_z;
    v = double(dz[k]) * plan.axis_x - double(dx[k]) * plan.axis_z;
  };
  constexpr int kNeighbours[6][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}};
  DrawnExtent drawn;
  for (int j = rows.begin; j < rows.end; ++j) {
    for (int i = 0; i < layout.width; ++i) {
      const std::size_t k = layout.index(i, j);
      if (!valid[k] || (need[k] & kDraw) == 0) {
        continue;
      }
      double u, v;
      frame(k, u, v);
      const double own = std::max(std::abs(u), std::abs(v));
      double edge = 0.0, low = double(height[k]);
      for (const auto& step : kNeighbours) {
        const int ni = i + step[0], nj = j + step[1];
        if (ni < 0 || nj < 0 || ni >= layout.width || nj >= layout.height) {
          continue;
        }
        const std::size_t m = layout.index(ni, nj);
        if (!valid[m]) {
          continue;
        }
        double mu, mv;
        frame(m, mu, mv);
        edge = std::max({edge, std::abs(mu - u), std::abs(mv - v)});
        low = std::min(low, double(height[m]));
      }
      drawn.nearest = std::min(drawn.nearest, own - edge - 1e-4 * own);
      drawn.farthest = std::max(drawn.farthest, (own + edge) * (1.0 + 1e-4));
      drawn.lowest = std::min(drawn.lowest, low);
    }
  }
  return drawn;
}

LevelRange shadow_level_range(const ShadowPlan& plan, const DrawnExtent& drawn_ground) {
  LevelRange range{plan.levels, plan.levels};
  if (!(drawn_ground.nearest < HUGE_VAL)) {
    return range;
  }
  // A drawn point under the water has its surface lookup (the glint's share, core/water.h)
  // nearer the camera, at level / height of its distance: no less than level / lowest, the
  // drawn triangles' lowest height (both negative; widened by 1e-4 for the pixels' float
  // interpolation), in any norm the distance is measured in.
  DrawnExtent drawn = drawn_ground;
  const double lowest = drawn.lowest * (1.0 + 1e-4);
  if ((plan.enabled || plan.reflections) && plan.water && lowest < plan.water_level &&
      drawn.nearest > 0.0) {
    drawn.nearest *= plan.water_level / lowest;  // in (0, 1)
  }
  const double span = double(plan.resolution - 1);
  const auto last_u = [&](int level) { return level_last_u(plan, level); };
  const auto last_v = [&](int level) { return plan.origin_v[level] + span * plan.spacing[level]; };
  range.first = plan.levels - 1;
  int widest = plan.levels - 1;  // the coarsest level a pixel reads
  for (int level = plan.levels - 1; level >= 0; --level) {
    const double outer = std::max({std::abs(plan.origin_u[level]), std::abs(last_u(level)),
                                   std::abs(plan.origin_v[level]), std::abs(last_v(level))});
    const double inner =
        std::min({-plan.origin_u[level], last_u(level), -plan.origin_v[level], last_v(level)});
    if (outer * (1.0 + 1e-4) >= drawn.nearest) {
      range.first = level;
    }
    if (inner >= drawn.farthest * (1.0 + 1e-4)) {
      widest = level;
    }
  }
  range.first = std::min(range.first, widest);
  // The coarsest level read: the widest's next coarser one too, in the widest's blend band.
  // Its rows continue to the occluders' reach (sweep_sun_horizons, in float: hence the
  // margin of 1e-4 and a spacing); a finer level's rows end nearer, and need no more.
  const int read = std::min(widest + 1, plan.levels - 1);
  const double target = (last_u(read) + plan.reach) * (1.0 + 1e-4) + plan.spacing[read];
  // Sky light's lines run toward all four sides: each reaches sky_reach past its level's far
  // end on its side (sky_horizons.h).
  const auto outer = [&](int level) {
    return std::max({-plan.origin_u[level], last_u(level), -plan.origin_v[level], last_v(level)});
  };
  const auto inner = [&](int level) {
    return std::min({-plan.origin_u[level], last_u(level), -plan.origin_v[level], last_v(level)});
  };
  const double sky_target = (outer(read) + plan.sky_reach) * (1.0 + 1e-4) + plan.spacing[read];
  int top = read;
  while (top + 1 < plan.levels && (last_u(top) < target || (plan.sky && inner(top) < sky_target))) {
    ++top;
  }
  range.end = top + 1;
  // A reflected ray (water_reflection.h) reaches terrain no pixel draws, past the farthest
  // drawn one: up to the coarsest level, four times the far plane's distance.
  if (plan.reflections) {
    range.end = plan.levels;
  }
  return range;
}

template <class Real>
void shadow_row_positions(const ShadowParams<Real>& p, int level, int row, std::span<Real> dx,
                          std::span<Real> dz, std::span<Real> nu) {
  const Real s = p.spacing[level];
  const Real v = p.origin_v[level] + Real(row) * s;
  for (int i = 0; i < p.resolution; ++i) {
    const Real u = p.origin_u[level] + Real(i) * s;
    dx[i] = u * p.axis_x - v * p.axis_z;
    dz[i] = u * p.axis_z + v * p.axis_x;
    nu[i] = p.nu[level];
  }
}

template <class Real>
HorizonWork sweep_sun_horizons(const ShadowParams<Real>& p, int level, RowRange rows,
                               SunHorizonCache<Real>& cache) {
  HorizonWork work;
  thread_local std::vector<HullPoint<Real>> hull;
  const bool sun = p.enabled != 0 && p.sun_set == 0;
  const bool sky = p.sky != 0;
  // One sweep toward the sun serves both: the sky's reach where it is the longer (a sample
  // past the sun's reach rises less than the disc's lower edge, so no share changes).
  const Real toward_sun_reach = sky ? std::max(p.reach, p.sky_reach) : p.reach;
  for (int row = rows.begin; row < rows.end; ++row) {
    sweep_horizon_line(
        p, cache, level, row, SweepDirection{false, 1}, toward_sun_reach, hull, work,
        [&](std::size_t k, Real along, Real h, const HullPoint<Real>* ahead, const auto& plane) {
          Real tangent = Real(kNoHorizonTangent);
          Real inv_run = p.inv_spacing[level];
          if (ahead != nullptr) {
            // run > 0: every point ahead lies farther along u (at least about a
            // spacing).
            inv_run = Real(1) / (ahead->along - along);
            tangent = (ahead->h - h) * inv_run;
          }
          if (sun) {
            cache.inv_distance[k] = inv_run;
            cache.tangent[k] = tangent;
          }
          if (sky) {
            cache.sky[k] = sky_openness(tangent, plane());
          }
        });
    if (sky) {  // away from the sun: the second of the sky's four directions
      sweep_horizon_line(
          p, cache, level, row, SweepDirection{false, -1}, p.sky_reach, hull, work,
          [&](std::size_t k, Real along, Real h, const HullPoint<Real>* ahead, const auto& plane) {
            cache.sky[k] = cache.sky[k] + sky_openness(horizon_tangent(along, h, ahead), plane());
          });
    }
  }
  return work;
}

template ShadowParams<float> make_shadow_params<float>(const ShadowPlan&);
template ShadowParams<double> make_shadow_params<double>(const ShadowPlan&);
template struct SunHorizonCache<float>;
template struct SunHorizonCache<double>;
template DrawnExtent drawn_extent<float>(const ShadowPlan&, const GridLayout&, RowRange,
                                         std::span<const float>, std::span<const float>,
                                         std::span<const float>, std::span<const std::uint8_t>,
                                         std::span<const std::uint8_t>);
template DrawnExtent drawn_extent<double>(const ShadowPlan&, const GridLayout&, RowRange,
                                          std::span<const double>, std::span<const double>,
                                          std::span<const double>, std::span<const std::uint8_t>,
                                          std::span<const std::uint8_t>);
template void shadow_row_positions<float>(const ShadowParams<float>&, int, int, std::span<float>,
                                          std::span<float>, std::span<float>);
template void shadow_row_positions<double>(const ShadowParams<double>&, int, int, std::span<double>,
                                           std::span<double>, std::span<double>);
template HorizonWork sweep_sun_horizons<float>(const ShadowParams<float>&, int, RowRange,
                                               SunHorizonCache<float>&);
template HorizonWork sweep_sun_horizons<double>(const ShadowParams<double>&, int, RowRange,
                                                SunHorizonCache<double>&);

}  // namespace relief
