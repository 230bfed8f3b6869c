// The picture of a relief stress run (--sheet FILE.png): one thumbnail per case, in the order of
// the table, read left to right and top to bottom, so that what the numbers say can be seen
// (an empty sky where the camera is inside the terrain, noise where an octave aliases).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "eval/stress_run.h"

namespace relief {

class StressSheet {
 public:
  static constexpr int kCellWidth = 120, kCellHeight = 96, kColumns = 8, kGap = 4;

  // The case's image from `rows`: the first rendered row of `backend` (simd, say), else the
  // first rendered row; a refused case gets a dark red cell, a skipped one a grey cell.
  void add_case(const std::vector<StressRow>& rows, const std::string& backend);

  // The sheet as a PNG carrying `description` (image_io.h).
  std::vector<unsigned char> encode_png(const std::string& description) const;

 private:
  struct Cell {
    std::vector<std::uint8_t> rgb;  // kCellWidth x kCellHeight, rows top to bottom
  };
  std::vector<Cell> cells_;
};

}  // namespace relief
