#include "core/height_block_maxima.h"

#include <algorithm>
#include <vector>

namespace relief {

namespace {

// Level `level`'s blocks raised to the maxima of the next finer level's blocks they overlap
// (those hold the finer levels' already): a ray in the level's square holds to the finest
// level there, whose surface a block of this level must bound too. A finer block spans
// [low, high] samples of its level along each axis; in this level's samples that is
// origin + [low, high] spacing (half this level's), widened by a thousandth of a sample for
// the rounding; a block [8 b, 8 b + 8] overlaps [x0, x1] where 8 b <= x1 and 8 b + 8 >= x0.
template <class Real>
void add_finer_blocks(const ShadowParams<Real>& p, int level, HeightBlockMaxima<Real>& out) {
  const int blocks = out.blocks[0], finer = level - 1;
  const Real last = Real(p.resolution - 1), block = Real(kReflectionBlock);
  const Real scale = p.spacing[finer] * p.inv_spacing[level];
  const Real offset_i = (p.origin_u[finer] - p.origin_u[level]) * p.inv_spacing[level];
  const Real offset_j = (p.origin_v[finer] - p.origin_v[level]) * p.inv_spacing[level];
  const auto span = [&](int b, Real offset, int& first, int& end) {
    const Real low = offset + Real(b) * block * scale - Real(1e-3);
    const Real high = offset + std::min(last, Real(b + 1) * block) * scale + Real(1e-3);
    first = std::max(0, int(std::ceil(low / block - Real(1))));
    end = std::min(blocks, int(std::floor(high / block)) + 1);
  };
  for (int fbr = 0; fbr < blocks; ++fbr) {
    int row_first = 0, row_end = 0;
    span(fbr, offset_j, row_first, row_end);
    for (int fbc = 0; fbc < blocks; ++fbc) {
      int column_first = 0, column_end = 0;
      span(fbc, offset_i, column_first, column_end);
      const Real h = out.at(0, finer, fbr, fbc);
      for (int br = row_first; br < row_end; ++br) {
        for (int bc = column_first; bc < column_end; ++bc) {
          Real& m = out.block_max[0][out.index(0, level, br, bc)];
          m = std::max(m, h);
        }
      }
    }
  }
}

}  // namespace

template <class Real>
void build_height_block_maxima(const ShadowParams<Real>& p, const SunHorizonCache<Real>& c,
                               int first_level, int end_level, HeightBlockMaxima<Real>& out) {
  const int n = c.resolution;
  const int blocks = (n - 1 + kReflectionBlock - 1) / kReflectionBlock;
  const std::size_t levels = std::size_t(std::max(0, end_level - first_level));
  out.first_level = first_level;
  out.end_level = end_level;
  out.top = Real(-HUGE_VAL);
  out.tiers = 1;
  out.blocks[0] = blocks;
  while (out.blocks[out.tiers - 1] > 2 && out.tiers < kMaxReflectionTiers) {
    out.blocks[out.tiers] = (out.blocks[out.tiers - 1] + 1) / 2;
    ++out.tiers;
  }
  for (int tier = 0; tier < kMaxReflectionTiers; ++tier) {
    const std::size_t b = tier < out.tiers ? std::size_t(out.blocks[tier]) : 0;
    out.block_max[tier].assign(levels * b * b, Real(-HUGE_VAL));
  }
  std::vector<Real> row_max(std::size_t(n) * blocks);
  for (int level = first_level; level < end_level; ++level) {
    out.level_top[level] = out.top;  // the finer levels'
    // Per row, the largest sample of each block's columns (a sample on a block's edge
    // belongs to the blocks on both sides), then per block the largest of its rows'.
    for (int row = 0; row < n; ++row) {
      const Real* h = &c.height[c.index(level, row, 0)];
      Real* maxima = &row_max[std::size_t(row) * blocks];
      for (int bc = 0; bc < blocks; ++bc) {
        const int end = std::min(n, (bc + 1) * kReflectionBlock + 1);
        Real m = h[bc * kReflectionBlock];
        for (int column = bc * kReflectionBlock + 1; column < end; ++column) {
          m = std::max(m, h[column]);
        }
        maxima[bc] = m;
        out.level_top[level] = std::max(out.level_top[level], m);
      }
    }
    for (int br = 0; br < blocks; ++br) {
      const int end = std::min(n, (br + 1) * kReflectionBlock + 1);
      Real* block = &out.block_max[0][out.index(0, level, br, 0)];
      for (int row = br * kReflectionBlock; row < end; ++row) {
        const Real* maxima = &row_max[std::size_t(row) * blocks];
        for (int bc = 0; bc < blocks; ++bc) {
          block[bc] = std::max(block[bc], maxima[bc]);
        }
      }
    }
    out.top = std::max(out.top, out.level_top[level]);
    if (level > first_level) {
      add_finer_blocks(p, level, out);
    }
    for (int tier = 1; tier < out.tiers; ++tier) {  // 2 x 2 blocks of the tier below
      const int below = out.blocks[tier - 1];
      for (int br = 0; br < below; ++br) {
        for (int bc = 0; bc < below; ++bc) {
          Real& m = out.block_max[tier][out.index(tier, level, br / 2, bc / 2)];
          m = std::max(m, out.at(tier - 1, level, br, bc));
        }
      }
    }
  }
}

template void build_height_block_maxima<float>(const ShadowParams<float>&,
                                               const SunHorizonCache<float>&, int, int,
                                               HeightBlockMaxima<float>&);
template void build_height_block_maxima<double>(const ShadowParams<double>&,
                                                const SunHorizonCache<double>&, int, int,
                                                HeightBlockMaxima<double>&);

}  // namespace relief
