// CpuBackend's bookkeeping (cpu_backend.h): the work each stage did, tallied as
// its units run on whatever threads, the counters a stage's time reports, and the set-up
// triangles and bins checked against the memory budget.
#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/input_file.h"
#include "core/octave_coordinates.h"
#include "pipeline/cpu_backend.h"
#include "pipeline/memory_budget.h"

namespace relief {

raster::RasterState frame_raster_state(const Scene& scene) {
  raster::RasterState state;
  state.width = scene.viewport.width;
  state.height = scene.viewport.height;
  state.viewport = {0.0, 0.0, double(scene.viewport.width), double(scene.viewport.height)};
  state.cull = raster::CullMode::kBack;
  state.depth_test = raster::DepthTest::kGreater;
  state.depth_clear = 0.0f;
  return state;
}

template <class Real>
bool CpuBackend<Real>::water_in_view() const {
  if (!plan_.water_enabled) {
    return false;
  }
  // Interpolated heights round to within 1e-12 of their range in double, to within it in
  // float: a margin of 1e-9 relative keeps every pixel that could be under water.
  const double level = plan_.relative_water_level;
  return min_drawn_height_ < level + 1e-9 * (std::abs(level) + std::abs(min_drawn_height_)) ||
         !request_.skips.water;
}

template <class Real>
void CpuBackend<Real>::tally_setup() {
  raster_stats_.triangles = frame_triangles().count();
  for (const raster::SetupChunk& chunk : chunks_) {
    raster_stats_.setup += chunk.triangles.size();
    raster_stats_.setup_bytes += chunk.triangles.capacity() * sizeof(raster::RasterTriangle);
  }
  const raster::BinSize bins = raster::bin_size(chunks_, tiles_);
  raster_stats_.bin_entries = bins.entries;
  raster_stats_.bin_bytes = bins.bytes;
  // The set-up triangles and the bins depend on the frame's triangles: counted here, not in
  // the up-front estimate (pipeline/job_memory.h).
  // A GeoMipMap frame's mesh has taken its share first (check_mesh_memory; <= max_bin_bytes).
  const std::uint64_t budget = request_.max_bin_bytes - mesh_bytes_;
  if (bins.bytes + raster_stats_.setup_bytes > budget) {
    raster_stats_.bins_refused = true;
    throw MemoryLimitError("the rasteriser's set-up triangles and bins for this frame need " +
                           format_bytes(bins.bytes + raster_stats_.setup_bytes) +
                           ", more than the " + format_bytes(budget) +
                           " left of the memory budget; lower viewport.width/height");
  }
}

template <class Real>
void CpuBackend<Real>::tally_rows(RowRange rows, const NeedCount& count) {
  // The largest nu of the rows' vertices to evaluate: octaves above it are never summed.
  double max_nu = 0;
  for (std::size_t k = plan_.layout.index(0, rows.begin); k < plan_.layout.index(0, rows.end);
       ++k) {
    if (need_[k] & kEvaluate) {
      max_nu = std::max(max_nu, double(grid_.nu[k]));
    }
  }
  // How far each octave reaches over the valid vertices, skipped or not: the octaves'
  // coordinate forms must not depend on the skips (octave_coordinates.h).
  const OctaveReach reach = octave_reach<Real>(
      IndexRange{plan_.layout.index(0, rows.begin), plan_.layout.index(0, rows.end)}, grid_.dx,
      grid_.dz, grid_.nu, grid_.valid);
  const std::lock_guard<std::mutex> lock(work_mutex_);
  needs_.evaluate += count.evaluate;
  needs_.draw += count.draw;
  needs_.valid_draw += count.valid_draw;
  max_nu_ = std::max(max_nu_, max_nu);
  reach_.merge(reach);
}

template <class Real>
void CpuBackend<Real>::tally_fbm(const FbmWork& work) {
  const std::lock_guard<std::mutex> lock(work_mutex_);
  fbm_work_.points += work.points;
  fbm_work_.octaves += work.octaves;
}

template <class Real>
void CpuBackend<Real>::tally_draws(RowRange rows, const NeedCount& count) {
  // The lowest drawn vertex: with none below the water level no pixel shows terrain under
  // water (a covered pixel's height interpolates its triangle's three: tile_pass.h).
  double lowest = HUGE_VAL;
  for (std::size_t k = plan_.layout.index(0, rows.begin); k < plan_.layout.index(0, rows.end);
       ++k) {
    if (grid_.valid[k] && (need_[k] & kDraw)) {
      lowest = std::min(lowest, double(grid_.height[k]));
    }
  }
  // Where pixels can lie in the sun's frame: the cache levels built (core/sun_horizons.h). A
  // mesh's triangles are taken in the rows' share of its list (every row range a disjoint
  // share, together the whole list).
  DrawnExtent drawn;
  if (shadow_rows() > 0 && (request_.skips.unread_shadow_levels || shadow_.reflections != 0)) {
    if (mesh_mode()) {
      const std::size_t triangles = mesh_.indices.size() / 3, height = plan_.layout.height;
      drawn = mesh_drawn_extent<Real>(
          shadow_plan_, mesh_.indices, triangles * std::size_t(rows.begin) / height,
          triangles * std::size_t(rows.end) / height, grid_.dx, grid_.dz, grid_.height);
    } else {
      drawn = drawn_extent<Real>(shadow_plan_, plan_.layout, rows, grid_.dx, grid_.dz, grid_.height,
                                 grid_.valid, need_);
    }
  }
  const std::lock_guard<std::mutex> lock(work_mutex_);
  draws_.evaluate += count.evaluate;
  draws_.draw += count.draw;
  draws_.valid_draw += count.valid_draw;
  min_drawn_height_ = std::min(min_drawn_height_, lowest);
  drawn_.merge(drawn);
}

template <class Real>
void CpuBackend<Real>::describe(StageId id, StageTime& time) const {
  const std::lock_guard<std::mutex> lock(work_mutex_);
  const auto count = [&](const char* name, std::uint64_t value) {
    time.counters.push_back({name, value});
  };
  const GridLayout& layout = plan_.layout;
  switch (id) {
    case StageId::kProjectedDomain:
      if (mesh_mode()) {
        describe_mesh(time);
        return;
      }
      count("grid vertices", std::uint64_t(layout.width) * layout.height);
      return;
    case StageId::kVertexNeeds:
      count("vertices to evaluate", needs_.evaluate);
      count("vertices to draw by the height bounds", needs_.draw);
      return;
    case StageId::kDrawNeeds:
      count("vertices to draw", draws_.draw);
      return;
    case StageId::kFractal:
      count("vertices evaluated", fbm_work_.points);
      count("point-octaves summed", fbm_work_.octaves);
      count("octaves in the table", std::uint64_t(params_.fbm.count));
      count("octaves with exact coordinates",
            std::uint64_t(std::count(params_.fbm.exact_coordinates,
                                     params_.fbm.exact_coordinates + params_.fbm.count, 1)));
      return;
    case StageId::kSurface:
      count("normals computed", draws_.valid_draw);
      count("water depths computed", params_.surface.water_enabled ? draws_.valid_draw : 0);
      return;
    case StageId::kShadowHeights:
      count("cache levels", std::uint64_t(shadow_plan_.levels));
      count("cache levels built", std::uint64_t(shadow_.end_level - shadow_.first_level));
      count("cache samples evaluated", shadow_fbm_work_.points);
      count("cache point-octaves summed", shadow_fbm_work_.octaves);
      return;
    case StageId::kSunHorizons:
      count("samples swept", horizon_work_.samples);
      count("coarser samples read past a row's end", horizon_work_.continuation);
      count("hull points skipped for good", horizon_work_.popped);
      return;
    case StageId::kSkyHorizons:
      count("samples swept", sky_work_.samples);
      count("coarser samples read past a column's end", sky_work_.continuation);
      count("hull points skipped for good", sky_work_.popped);
      return;
    case StageId::kVertexTransform:
      count("vertices transformed", transformed_);
      if (params_.transform.gouraud != 0) {  // gradient mode lit the same vertices
        count("vertices lit (Gouraud)", transformed_);
      }
      return;
    case StageId::kTriangleSetup: {
      std::uint64_t submitted = 0;
      for (const raster::SetupChunk& chunk : chunks_) {
        submitted += chunk.submitted;
      }
      count(mesh_mode() ? "triangles in the mesh" : "triangles in the grid",
            raster_stats_.triangles);
      count("triangles submitted", submitted);
      count("triangles set up", raster_stats_.setup);
      return;
    }
    case StageId::kBinning:
      count("bin entries", raster_stats_.bin_entries);
      return;
    case StageId::kTiles: {
      const TileWork& w = times_.work;
      const ShadeWork& shade = w.shade;
      count("tiles", std::uint64_t(tiles_.count()));
      count("tiles rasterised", w.tiles_drawn);
      count("triangles rasterised (per tile)", w.tile_triangles);
      count("pixels covered", w.covered_pixels);
      count("pixels shaded as terrain", shade.terrain_pixels);
      count("pixels shaded as background", shade.background_pixels);
      count("texture fetches", shade.texture_fetches);
      count("dither samples", shade.dither_samples);
      count("specular terms", shade.specular_pixels);
      count("normals turned to face the eye", shade.facing_normals);
      count("water pixels", shade.water_pixels);
      count("fogged pixels", shade.fogged_pixels);
      if (shade_.clouds != 0) {
        count("view rays through the cloud layer", shade.cloud_view_paths);
        count("sun rays through the cloud layer", shade.cloud_sun_paths);
        count("cloud lattice samples", shade.cloud_lookups);
      }
      if (shadow_.enabled != 0) {
        const ShadowWork& shadow = w.shadow;
        count("shadow lookups", shadow.pixels);
        count("pixels proven lit by four comparisons", shadow.lit);
        count("pixels with the sun disc's share evaluated", shadow.evaluated);
        count("pixels in full shadow", shadow.dark);
        count("pixels beyond the shadow cache", shadow.outside);
        if (shade_.water_enabled != 0 && shade_.terrain_water != 0) {
          const ShadowWork& water = w.water_shadow;
          count("water surface shadow lookups", water.pixels);
          count("water surface points proven lit", water.lit);
          count("water surface points in full shadow", water.dark);
        }
      }
      if (shadow_.reflections != 0 && shade_.terrain_water != 0) {
        const ReflectionWork& r = w.reflection;
        count("reflected rays marched", r.rays);
        count("reflected rays' height lookups", r.lookups);
        count("blocks skipped below a reflected ray", r.skipped);
        count("levels skipped below a reflected ray", r.levels);
        count("reflected rays meeting the terrain", r.hits);
        count("reflected rays above every height", r.above);
        count("reflected rays leaving the cache", r.left);
      }
      if (shadow_.sky != 0) {
        count("sky lookups", w.sky.pixels);
        count("pixels under the whole sky", w.sky.open);
        count("pixels beyond the sky's cache", w.sky.outside);
      }
      return;
    }
    default:
      return;
  }
}

// The members defined here, for both backends (the class itself is instantiated once, in
// cpu_backend.cc).
#define RELIEF_INSTANTIATE_WORK(Real)                                      \
  template void CpuBackend<Real>::tally_rows(RowRange, const NeedCount&);  \
  template void CpuBackend<Real>::tally_fbm(const FbmWork&);               \
  template void CpuBackend<Real>::tally_draws(RowRange, const NeedCount&); \
  template void CpuBackend<Real>::tally_setup();                           \
  template bool CpuBackend<Real>::water_in_view() const;                   \
  template void CpuBackend<Real>::describe(StageId, StageTime&) const;
RELIEF_INSTANTIATE_WORK(float)
RELIEF_INSTANTIATE_WORK(double)
#undef RELIEF_INSTANTIATE_WORK

}  // namespace relief
