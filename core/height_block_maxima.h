// Max-height skipping for rays over the cast shadows' horizon cache (core/sun_horizons.h;
// castledragmire's max-height skip): per level, the largest height of each block of cells, in
// tiers of blocks doubling in size, each raised to the finer levels' blocks inside it (a ray
// holds to the finest level at its point, whose surface a coarser level's block must bound
// too), and per level the largest height of it and every finer one. A rising ray above a
// block's (or a level's) largest height stays above everything in it to its exit
// (core/water_reflection.h).
#pragma once

#include <cmath>
#include <cstddef>

#include "core/grid_buffers.h"
#include "core/sun_horizons.h"

namespace relief {

inline constexpr int kReflectionBlockLog2 = 3;
inline constexpr int kReflectionBlock = 1 << kReflectionBlockLog2;  // cells per block side
inline constexpr int kMaxReflectionTiers = 8;  // 8 x 2^7 = 1024 >= kMaxShadowResolution

// Per level of the cache, the largest height of each block of kReflectionBlock^2 cells (the
// samples on its edges included, and the finer levels' blocks that overlap it), and the
// largest of all levels.
template <class Real>
struct HeightBlockMaxima {
  // Tier 0's blocks hold kReflectionBlock cells per side, each next tier's twice as many (the
  // maxima of 2 x 2 blocks of the tier below), up to the last with more than one block.
  int tiers = 0;
  int blocks[kMaxReflectionTiers]{};  // per side of a level, in each tier
  int first_level = 0, end_level = 0;
  Real top = -HUGE_VAL;
  // Per level, the largest height of it and every finer level (inside its square): a ray
  // above it leaves the level's square without meeting anything there.
  Real level_top[kMaxShadowLevels]{};
  AlignedVector<Real> block_max[kMaxReflectionTiers];

  std::size_t index(int tier, int level, int block_row, int block_column) const {
    const std::size_t b = std::size_t(blocks[tier]);
    return (std::size_t(level - first_level) * b + block_row) * b + block_column;
  }
  Real at(int tier, int level, int block_row, int block_column) const {
    return block_max[tier][index(tier, level, block_row, block_column)];
  }
};

// From the cache's heights of levels [first_level, end_level) (built, within the cache's; laid
// out by `levels`), each level's blocks raised to the finer levels' inside them.
template <class Real>
void build_height_block_maxima(const ShadowParams<Real>& levels, const SunHorizonCache<Real>& cache,
                               int first_level, int end_level, HeightBlockMaxima<Real>& out);

}  // namespace relief
