// CpuBackend's cast shadows, sky light and reflections (cpu_backend.h, core/sun_horizons.h,
// core/sky_horizons.h, core/water_reflection.h): the horizon cache's levels and rows to build,
// their heights through the frame's own stage-3 kernels, their sweeps along the rows and the
// columns, the reflections' block maxima, and what the tiles read of them.
#include <algorithm>
#include <mutex>

#include "pipeline/cpu_backend.h"

namespace relief {

template <class Real>
std::size_t CpuBackend<Real>::shadow_rows() const {
  // Cast shadows read the cache while the sun is up; sky light and the water's reflections
  // whenever they are on.
  if ((shadow_.enabled == 0 || shadow_.sun_set != 0) && shadow_.sky == 0 &&
      shadow_.reflections == 0) {
    return 0;
  }
  // Levels [first_level, end_level): the others no pixel reads (shadow_level_range).
  return std::size_t(shadow_.end_level - shadow_.first_level) *
         std::size_t(shadow_plan_.resolution);
}

template <class Real>
bool CpuBackend<Real>::sweeps_horizons() const {
  // The sweeps serve cast shadows (the sun up) and sky light; the reflections read heights.
  return (shadow_.enabled != 0 && shadow_.sun_set == 0) || shadow_.sky != 0;
}

template <class Real>
void CpuBackend<Real>::run_horizon_cache(StageId id, std::size_t begin, std::size_t end) {
  if (id == StageId::kShadowHeights) {
    run_shadow_heights(begin, end);
    return;
  }
  // The sweeps: the units are the cache's rows (sun horizons) or columns (sky horizons, as
  // many), level after level; one call of a sweep never spans two levels.
  const bool rows = id == StageId::kSunHorizons;
  const auto sweep = rows ? &sweep_sun_horizons<Real> : &sweep_sky_columns<Real>;
  HorizonWork work;
  const int n = shadow_plan_.resolution;
  const std::size_t first = std::size_t(shadow_.first_level) * std::size_t(n);
  end += first;
  for (std::size_t unit = first + begin; unit < end;) {
    const int level = int(unit / n), line = int(unit % n);
    const int lines_here = int(std::min<std::size_t>(end - unit, std::size_t(n - line)));
    work += sweep(shadow_, level, RowRange{line, line + lines_here}, horizons_);
    unit += std::size_t(lines_here);
  }
  const std::lock_guard<std::mutex> lock(work_mutex_);
  (rows ? horizon_work_ : sky_work_) += work;
}

template <class Real>
void CpuBackend<Real>::run_shadow_heights(std::size_t begin, std::size_t end) {
  // Stage 3 through the frame's own kernels, one cache row at a time (sun_horizons.h).
  const int n = shadow_plan_.resolution;
  thread_local AlignedVector<Real> dx, dz, nu;
  dx.resize(n);
  dz.resize(n);
  nu.resize(n);
  FbmWork work;
  const std::size_t first = std::size_t(shadow_.first_level) * std::size_t(n);
  for (std::size_t unit = first + begin; unit < first + end; ++unit) {
    const int level = int(unit / n), row = int(unit % n);
    shadow_row_positions<Real>(shadow_, level, row, dx, dz, nu);
    const std::span<Real> heights(horizons_.height.data() + horizons_.index(level, row, 0),
                                  std::size_t(n));
    const FbmWork row_work = kernels_.fractal(
        shadow_fbm_, terrain_values_, IndexRange{0, std::size_t(n)}, dx, dz, nu, {}, heights);
    work.points += row_work.points;
    work.octaves += row_work.octaves;
    if (params_.sketch.enabled != 0 && plan_.terrain.sketch != nullptr) {  // §3's base
      // A height field's level of detail by the cache level's own spacing (nu, as stage 2's).
      kernels_.sketch(params_.sketch, plan_.terrain.sketch->heights, IndexRange{0, std::size_t(n)},
                      dx, dz, nu, {}, heights);
    }
    raise_to_water_surface(shadow_, heights);
  }
  const std::lock_guard<std::mutex> lock(work_mutex_);
  shadow_fbm_work_.points += work.points;
  shadow_fbm_work_.octaves += work.octaves;
}

template <class Real>
void CpuBackend<Real>::choose_cache_levels() {
  if (!water_in_view()) {  // no pixel has water in front: no reflected ray, no cache for one
    shadow_.reflections = 0;
  }
  if (shadow_rows() == 0 || (!request_.skips.unread_shadow_levels && shadow_.reflections == 0)) {
    return;
  }
  const LevelRange range = shadow_level_range(shadow_plan_, drawn_);
  if (request_.skips.unread_shadow_levels) {
    shadow_.first_level = range.first;
    shadow_.end_level = range.end;
  }
  // The reflected rays read those levels alone, with the skip or without; with them the range
  // ends at the coarsest level, so the rows' sweeps continue as far either way: the skip
  // changes no bit of them (core/water_reflection.h).
  reflection_levels_ = shadow_;
  reflection_levels_.first_level = range.first;
  reflection_levels_.end_level = range.end;
}

template <class Real>
void CpuBackend<Real>::build_reflection_maxima() {
  if (shadow_.reflections != 0 && shadow_rows() > 0) {  // every row's heights written
    build_height_block_maxima(reflection_levels_, horizons_, reflection_levels_.first_level,
                              reflection_levels_.end_level, maxima_);
  }
}

template <class Real>
TileShadows<Real> CpuBackend<Real>::tile_shadows() const {
  // The water's reflections march over the cache's heights (core/water_reflection.h).
  const bool reflects = shadow_.reflections != 0 && shadow_rows() > 0;
  return TileShadows<Real>{shadow_.enabled != 0 ? &shadow_ : nullptr, &horizons_,
                           shadow_.sky != 0 ? &shadow_ : nullptr,
                           reflects ? &reflection_levels_ : nullptr, reflects ? &maxima_ : nullptr};
}

// The members defined here, for both backends (the class itself is instantiated once, in
// cpu_backend.cc).
#define RELIEF_INSTANTIATE_SHADOWS(Real)                                                \
  template std::size_t CpuBackend<Real>::shadow_rows() const;                           \
  template bool CpuBackend<Real>::sweeps_horizons() const;                              \
  template void CpuBackend<Real>::choose_cache_levels();                                \
  template void CpuBackend<Real>::build_reflection_maxima();                            \
  template TileShadows<Real> CpuBackend<Real>::tile_shadows() const;                    \
  template void CpuBackend<Real>::run_horizon_cache(StageId, std::size_t, std::size_t); \
  template void CpuBackend<Real>::run_shadow_heights(std::size_t, std::size_t);
RELIEF_INSTANTIATE_SHADOWS(float)
RELIEF_INSTANTIATE_SHADOWS(double)
#undef RELIEF_INSTANTIATE_SHADOWS

}  // namespace relief
