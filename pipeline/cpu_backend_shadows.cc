// CpuBackend's cast shadows and sky light (cpu_backend.h, core/sun_horizons.h,
// core/sky_horizons.h): the horizon cache's rows to build, their heights through the frame's
// own stage-3 kernels, and their sweeps along the rows and the columns.
#include <algorithm>
#include <mutex>

#include "pipeline/cpu_backend.h"

namespace relief {

template <class Real>
std::size_t CpuBackend<Real>::shadow_rows() const {
  // Cast shadows read the cache while the sun is up; sky light whenever it is on.
  if ((shadow_.enabled == 0 || shadow_.sun_set != 0) && shadow_.sky == 0) {
    return 0;
  }
  // Levels [first_level, end_level): the others no pixel reads (shadow_level_range).
  return std::size_t(shadow_.end_level - shadow_.first_level) *
         std::size_t(shadow_plan_.resolution);
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

// The members defined here, for both backends (the class itself is instantiated once, in
// cpu_backend.cc).
#define RELIEF_INSTANTIATE_SHADOWS(Real)                                                \
  template std::size_t CpuBackend<Real>::shadow_rows() const;                           \
  template void CpuBackend<Real>::run_horizon_cache(StageId, std::size_t, std::size_t); \
  template void CpuBackend<Real>::run_shadow_heights(std::size_t, std::size_t);
RELIEF_INSTANTIATE_SHADOWS(float)
RELIEF_INSTANTIATE_SHADOWS(double)
#undef RELIEF_INSTANTIATE_SHADOWS

}  // namespace relief
