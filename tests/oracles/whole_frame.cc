#include "tests/oracles/whole_frame.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/fbm.h"
#include "core/height_sketch.h"
#include "core/input_file.h"
#include "core/octave_coordinates.h"
#include "core/shading_plan.h"
#include "core/sky_horizons.h"
#include "core/srgb.h"
#include "core/stage_params.h"
#include "core/sun_horizons.h"
#include "core/sun_visibility.h"
#include "core/vertex_transform.h"
#include "core/water_reflection.h"
#include "pipeline/cpu_backend.h"
#include "pipeline/memory_budget.h"

namespace relief {

TerrainFrame rasterize_terrain(const Scene& scene, const SceneResources& resources,
                               const raster::RasterLimits& limits) {
  return rasterize_terrain(scene, resources.terrain_values(), limits, resources.sketch_or_null());
}

TerrainFrame rasterize_terrain(const Scene& scene, const NoiseLattice& lattice,
                               const raster::RasterLimits& limits, const HeightSketch* sketch) {
  TerrainRun<float> terrain =
      run_terrain_stages<float>(scene, lattice, Backend::kReference, sketch);
  TerrainFrame frame{std::move(terrain.plan),
                     std::move(terrain.grid),
                     {},
                     {},
                     {},
                     {},
                     frame_raster_state(scene),
                     {},
                     {}};
  const TransformParams<float> transform = make_terrain_params<float>(frame.plan).transform;
  const std::size_t vertex_count = frame.plan.layout.size();
  frame.clip_x.resize(vertex_count);
  frame.clip_y.resize(vertex_count);
  frame.clip_z.resize(vertex_count);
  frame.clip_w.resize(vertex_count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertex_count, 16384),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      // A planet's bent positions (core/planet_bend.h), as the backend.
                      const GridBuffers<float>& g = frame.grid;
                      const bool bent = frame.plan.planet.enabled;
                      transform_vertices<float>(
                          transform, IndexRange{r.begin(), r.end()}, bent ? g.bent_x : g.dx,
                          bent ? g.bent_z : g.dz, bent ? g.bent_y : g.height, {},
                          ClipSpans<float>{frame.clip_x, frame.clip_y, frame.clip_z, frame.clip_w});
                    });
  frame.raster =
      raster::rasterize(frame.state, frame.clip(), frame.triangles(), frame.visibility, limits);
  if (frame.raster.bins_refused) {
    throw MemoryLimitError("the rasteriser's bins for this frame need " +
                           format_bytes(frame.raster.bin_bytes) + ", more than the " +
                           format_bytes(limits.max_bin_bytes) + " left of the memory budget");
  }
  return frame;
}

raster::ResolvedFrame resolve_for_shading(const TerrainFrame& frame) {
  const GridBuffers<float>& g = frame.grid;
  // On a planet the bent (dx, dz) and the drop (cpu_backend.cc's streams).
  const bool bent = frame.plan.planet.enabled;
  const std::span<const float> streams[] = {bent ? g.bent_x : g.dx,
                                            bent ? g.bent_z : g.dz,
                                            g.height,
                                            g.nx,
                                            g.ny,
                                            g.nz,
                                            g.slope,
                                            g.water_depth,
                                            g.bent_drop};
  raster::ResolvedFrame resolved;
  raster::resolve(frame.visibility,
                  raster::VertexPositions::from_clip(frame.clip(), frame.state.viewport),
                  frame.triangles(), std::span<const std::span<const float>>(streams, bent ? 9 : 8),
                  3, resolved);
  return resolved;
}

ShadingInputs shading_inputs(const TerrainFrame& frame, const raster::ResolvedFrame& r) {
  return ShadingInputs{
      frame.visibility.primitive,
      r.value[0],
      r.value[1],
      r.value[2],
      r.ddx[0],
      r.ddy[0],
      r.ddx[1],
      r.ddy[1],
      r.ddx[2],
      r.ddy[2],
      r.value[3],
      r.value[4],
      r.value[5],
      r.value[6],
      r.value[7],
      r.value.size() > 8 ? std::span<const float>(r.value[8]) : std::span<const float>{}};
}

template <class Real>
SunHorizonCache<Real> build_horizon_cache(const ShadowPlan& plan, const FramePlan& frame,
                                          const SceneResources& resources, int first, int end) {
  SunHorizonCache<Real> cache;
  const bool sun = plan.enabled && !plan.sun_set;
  if (!sun && !plan.sky && !plan.reflections) {
    return cache;
  }
  end = end < 0 ? plan.levels : end;
  ShadowParams<Real> params = make_shadow_params<Real>(plan);
  params.first_level = first;
  params.end_level = end;
  cache.allocate(plan.resolution, first, end, sun, plan.sky);
  FbmParams<Real> fbm = make_fbm_params<Real>(frame.terrain);
  choose_coordinate_forms(frame.terrain, shadow_octave_reach(plan), fbm);
  const SketchParams<Real> sketch =
      make_sketch_params<Real>(frame.terrain.sketch_plan, resources.sketch_or_null());
  const int n = plan.resolution;
  std::vector<Real> dx(n), dz(n), nu(n);
  for (int level = first; level < end; ++level) {
    for (int row = 0; row < n; ++row) {
      shadow_row_positions<Real>(params, level, row, dx, dz, nu);
      const std::span<Real> heights(cache.height.data() + cache.index(level, row, 0),
                                    std::size_t(n));
      evaluate_fbm<Real>(fbm, resources.terrain_values(), IndexRange{0, std::size_t(n)}, dx, dz, nu,
                         {}, heights);
      if (sketch.enabled != 0) {
        add_sketch<Real>(sketch, resources.sketch_or_null()->heights, IndexRange{0, std::size_t(n)},
                         dx, dz, nu, {}, heights);
      }
      raise_to_water_surface(params, heights);
    }
  }
  for (int level = first; (sun || plan.sky) && level < end; ++level) {
    sweep_sun_horizons<Real>(params, level, RowRange{0, n}, cache);
  }
  for (int level = first; plan.sky && level < end; ++level) {  // after every row's sweep
    sweep_sky_columns<Real>(params, level, RowRange{0, n}, cache);
  }
  return cache;
}

template SunHorizonCache<float> build_horizon_cache<float>(const ShadowPlan&, const FramePlan&,
                                                           const SceneResources&, int, int);
template SunHorizonCache<double> build_horizon_cache<double>(const ShadowPlan&, const FramePlan&,
                                                             const SceneResources&, int, int);

namespace {

// Each covered pixel's share of the sun disc and of the sky from one cache of
// build_horizon_cache; each empty where the scene has no shadows, or no sky light. With
// shadows and water, `water_sun`: the sun's share where the view ray meets the water surface
// before the pixel's ground (below the camera-relative level: the surface point lies along
// the ray at level / height of the way).
// With reflections, the terrain each water pixel's reflected ray meets over every level
// (core/water_reflection.h), its radiance and weight.
struct CacheShares {
  std::vector<float> sun, sky, water_sun;
  std::vector<float> reflection_r, reflection_g, reflection_b, reflection_weight;
};
CacheShares cache_shares(const Scene& scene, const SceneResources& resources,
                         const TerrainFrame& frame, const ShadeParams<float>& shade,
                         const ShadeResources& shade_resources, const ShadingInputs& inputs) {
  const ShadowPlan plan = make_shadow_plan(scene, frame.plan);
  CacheShares shares;
  if (!plan.enabled && !plan.sky && !plan.reflections) {
    return shares;
  }
  const ShadowParams<float> params = make_shadow_params<float>(plan);
  const SunHorizonCache<float> cache = build_horizon_cache<float>(plan, frame.plan, resources);
  const std::size_t pixels = inputs.primitive.size();
  shares.sun.assign(plan.enabled ? pixels : 0, 1.0f);
  shares.sky.assign(plan.sky ? pixels : 0, 1.0f);
  const bool water = plan.enabled && shade.water_enabled;
  shares.water_sun.assign(water ? pixels : 0, 1.0f);
  const bool reflections = plan.reflections && shade.terrain_reflections != 0;
  for (std::vector<float>* v : {&shares.reflection_r, &shares.reflection_g, &shares.reflection_b,
                                &shares.reflection_weight}) {
    v->assign(reflections ? pixels : 0, 0.0f);
  }
  HeightBlockMaxima<float> maxima;
  if (reflections) {
    build_height_block_maxima(params, cache, 0, plan.levels, maxima);
  }
  const ReflectionScene<float> reflection{&shade,
                                          shade_resources,
                                          &params,
                                          &cache,
                                          &maxima,
                                          plan.enabled ? &params : nullptr,
                                          plan.sky ? &params : nullptr};
  ReflectionWork reflection_work;
  ShadeWork reflection_shade_work;
  ShadowWork sun_work;
  SkyWork sky_work;
  for (std::size_t k = 0; k < pixels; ++k) {
    if (inputs.primitive[k] == raster::kNoPrimitive) {
      continue;
    }
    if (plan.enabled) {
      shares.sun[k] = sun_visibility<float>(params, cache, inputs.dx[k], inputs.height[k],
                                            inputs.dz[k], sun_work);
    }
    if (plan.sky) {
      shares.sky[k] = sky_visibility<float>(params, cache, inputs.dx[k], inputs.dz[k], sky_work);
    }
    if (water && inputs.height[k] < shade.water_level) {
      const float t = shade.water_level / inputs.height[k];  // both negative
      shares.water_sun[k] = sun_visibility<float>(params, cache, inputs.dx[k] * t,
                                                  shade.water_level, inputs.dz[k] * t, sun_work);
    }
    if (reflections && inputs.height[k] < shade.water_level) {
      Vec3<float> radiance;
      shares.reflection_weight[k] = reflected_terrain(reflection, inputs.dx[k], inputs.height[k],
                                                      inputs.dz[k], inputs.water_depth[k], radiance,
                                                      reflection_work, reflection_shade_work);
      shares.reflection_r[k] = radiance.x;
      shares.reflection_g[k] = radiance.y;
      shares.reflection_b[k] = radiance.z;
    }
  }
  return shares;
}

}  // namespace

FrameImage render_whole_frame(const Scene& scene, const SceneResources& resources) {
  const TerrainFrame frame = rasterize_terrain(scene, resources);
  const raster::ResolvedFrame resolved = resolve_for_shading(frame);
  const ShadingPlan plan = make_shading_plan(scene, frame.plan, resources.lattice.size);
  ShadeParams<float> params = make_shade_params<float>(plan);
  add_planet_shading(frame.plan, scene.terrain.base_height, params);
  const ShadeResources shade_resources{&resources.lattice, resources.textures};
  ShadingInputs inputs = shading_inputs(frame, resolved);
  const CacheShares shares = cache_shares(scene, resources, frame, params, shade_resources, inputs);
  inputs.sun = shares.sun;
  inputs.sky = shares.sky;
  inputs.water_sun = shares.water_sun;
  inputs.reflection_r = shares.reflection_r;
  inputs.reflection_g = shares.reflection_g;
  inputs.reflection_b = shares.reflection_b;
  inputs.reflection_weight = shares.reflection_weight;
  // Gradient mode: every vertex lit (core/vertex_transform.h), its Lambert term resolved.
  raster::ResolvedFrame lambert_resolved;
  if (plan.gradient.enabled) {
    TransformParams<float> transform = make_terrain_params<float>(frame.plan).transform;
    add_gouraud_lighting(plan, transform);
    const GridBuffers<float>& g = frame.grid;
    AlignedVector<float> lambert(frame.plan.layout.size());
    light_vertices<float>(transform, IndexRange{0, lambert.size()}, g.nx, g.ny, g.nz, {}, lambert);
    const std::span<const float> stream[] = {lambert};
    raster::resolve(
        frame.visibility, raster::VertexPositions::from_clip(frame.clip(), frame.state.viewport),
        frame.triangles(), std::span<const std::span<const float>>(stream, 1), 0, lambert_resolved);
    inputs.lambert = lambert_resolved.value[0];
  }
  FrameImage image;
  image.width = frame.state.width;
  image.height = frame.state.height;
  const std::size_t pixels = std::size_t(image.width) * image.height;
  image.linear.resize(3 * pixels);
  image.srgb.resize(3 * pixels);
  tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 8),
                    [&](const tbb::blocked_range<int>& r) {
                      shade_pixels<float>(params, shade_resources, inputs,
                                          RowRange{r.begin(), r.end()}, image.linear);
                    });
  for (std::size_t k = 0; k < 3 * pixels; ++k) {
    image.srgb[k] = srgb_byte(image.linear[k]);
  }
  return image;
}

}  // namespace relief
