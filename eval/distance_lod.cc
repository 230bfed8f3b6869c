#include "eval/distance_lod.h"

#include <algorithm>

#include "core/det_math.h"
#include "core/limits.h"
#include "core/lod_rule.h"

namespace relief {

template <class Real>
void apply_distance_lod(const DistanceLod& lod, RowRange rows, GridBuffers<Real>& grid) {
  for (std::size_t k = grid.layout.index(0, rows.begin); k < grid.layout.index(0, rows.end); ++k) {
    if (!grid.valid[k]) {
      continue;
    }
    const double dx = double(grid.dx[k]), dz = double(grid.dz[k]);
    const double distance_sq = dx * dx + dz * dz + lod.gap_sq;
    // Distances below the guard take every octave, as stage 2 does for spacings below it.
    const double nu =
        lod_octave_count(lod.c0, lod.c1, lod.nu_max, limits::kMinSpacingSq, distance_sq);
    grid.nu[k] = static_cast<Real>(nu);
  }
}

template void apply_distance_lod<float>(const DistanceLod&, RowRange, GridBuffers<float>&);
template void apply_distance_lod<double>(const DistanceLod&, RowRange, GridBuffers<double>&);

namespace {

class DistanceLodRule final : public OctaveCountRule {
 public:
  explicit DistanceLodRule(const DistanceLod& lod) : lod_(lod) {}
  void apply(RowRange rows, GridBuffers<float>& grid) const override {
    apply_distance_lod<float>(lod_, rows, grid);
  }
  void apply(RowRange rows, GridBuffers<double>& grid) const override {
    apply_distance_lod<double>(lod_, rows, grid);
  }

 private:
  DistanceLod lod_;
};

}  // namespace

std::shared_ptr<const OctaveCountRule> distance_lod_rule(const DistanceLod& lod) {
  return std::make_shared<DistanceLodRule>(lod);
}

}  // namespace relief
