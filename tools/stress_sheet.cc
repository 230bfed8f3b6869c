#include "tools/stress_sheet.h"

#include <algorithm>

#include "image/image_io.h"
#include "image/png_text.h"

namespace relief {

namespace {

// `row`'s image box-filtered into a cell, centred with its aspect kept (rows top to bottom).
std::vector<std::uint8_t> thumbnail(const StressRow& row, int cell_w, int cell_h) {
  std::vector<std::uint8_t> cell(std::size_t(cell_w) * cell_h * 3, 0);
  const double scale = std::min(double(cell_w) / row.width, double(cell_h) / row.height);
  const int w = std::clamp(int(row.width * scale), 1, cell_w);
  const int h = std::clamp(int(row.height * scale), 1, cell_h);
  const int x0 = (cell_w - w) / 2, y0 = (cell_h - h) / 2;
  for (int y = 0; y < h; ++y) {
    // Source rows [sy0, sy1), counted from the top; the image's rows run bottom to top.
    const int sy0 = int(std::int64_t(y) * row.height / h);
    const int sy1 = std::max(sy0 + 1, int(std::int64_t(y + 1) * row.height / h));
    for (int x = 0; x < w; ++x) {
      const int sx0 = int(std::int64_t(x) * row.width / w);
      const int sx1 = std::max(sx0 + 1, int(std::int64_t(x + 1) * row.width / w));
      unsigned sum[3] = {0, 0, 0};
      for (int sy = sy0; sy < sy1; ++sy) {
        const std::size_t line = std::size_t(row.height - 1 - sy) * row.width;
        for (int sx = sx0; sx < sx1; ++sx) {
          for (int c = 0; c < 3; ++c) {
            sum[c] += row.srgb[3 * (line + sx) + c];
          }
        }
      }
      const unsigned n = unsigned(sy1 - sy0) * unsigned(sx1 - sx0);
      for (int c = 0; c < 3; ++c) {
        cell[3 * (std::size_t(y0 + y) * cell_w + x0 + x) + c] = std::uint8_t(sum[c] / n);
      }
    }
  }
  return cell;
}

}  // namespace

void StressSheet::add_case(const std::vector<StressRow>& rows, const std::string& backend) {
  const StressRow* chosen = nullptr;
  for (const StressRow& row : rows) {
    const bool drawn = row.status == StressStatus::kOk && !row.srgb.empty();
    if (drawn && (chosen == nullptr || (row.backend == backend && chosen->backend != backend))) {
      chosen = &row;
    }
  }
  Cell cell;
  if (chosen != nullptr) {
    cell.rgb = thumbnail(*chosen, kCellWidth, kCellHeight);
  } else {
    const bool refused = std::any_of(rows.begin(), rows.end(), [](const StressRow& r) {
      return r.status == StressStatus::kRefused;
    });
    const std::uint8_t fill[3] = {std::uint8_t(refused ? 96 : 64), 32, 32};
    cell.rgb.resize(std::size_t(kCellWidth) * kCellHeight * 3);
    for (std::size_t k = 0; k < cell.rgb.size(); ++k) {
      cell.rgb[k] = refused ? fill[k % 3] : 64;
    }
  }
  cells_.push_back(std::move(cell));
}

std::vector<unsigned char> StressSheet::encode_png(const std::string& description) const {
  const int count = std::max<int>(1, int(cells_.size()));
  const int columns = std::min(kColumns, count), rows = (count + kColumns - 1) / kColumns;
  const int width = columns * kCellWidth + (columns + 1) * kGap;
  const int height = rows * kCellHeight + (rows + 1) * kGap;
  std::vector<std::uint8_t> rgb(std::size_t(width) * height * 3, 255);
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    const int left = kGap + int(k % kColumns) * (kCellWidth + kGap);
    const int top = kGap + int(k / kColumns) * (kCellHeight + kGap);
    for (int y = 0; y < kCellHeight; ++y) {
      const std::size_t line = std::size_t(height - 1 - (top + y)) * width;  // bottom to top
      std::copy_n(cells_[k].rgb.begin() + std::ptrdiff_t(y) * kCellWidth * 3, kCellWidth * 3,
                  rgb.begin() + std::ptrdiff_t(3 * (line + left)));
    }
  }
  const ImageText text[] = {{"Software", "relief stress"}, {"Description", description}};
  return encode_png_rgb(width, height, rgb, text);
}

}  // namespace relief
