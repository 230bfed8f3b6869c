// Images read from files for relief compare: any format OpenImageIO reads (PNG, EXR, PFM,
// TIFF, ...), as floats, the first subimage only (as idiff without -a). Files are checked
// before OpenImageIO opens them (core/input_file.h): only a regular file of at most
// kMaxImageFileBytes, so that a FIFO, a directory or /dev/zero is refused at once instead of
// blocking or filling memory (idiff waits for ever on a FIFO).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "tools/image_compare.h"

namespace relief {

// The largest image file compare reads: a 16384 x 16384 RGBA image of 32-bit floats without
// compression (4 GiB), four times the largest image Relief writes (16384^2 RGB floats).
inline constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t{4} << 30;

// A file that cannot be read as an image; the message names the file and says why.
class ImageFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An image file opened and its header read; the pixels are read by read(). Throws
// ImageFileError.
class ImageFile {
 public:
  explicit ImageFile(const std::filesystem::path& path);
  ~ImageFile();
  ImageFile(const ImageFile&) = delete;
  ImageFile& operator=(const ImageFile&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  std::string format() const;  // OpenImageIO's name of it: "png", "openexr", "pnm"
  // A string attribute of the header ("relief:scene" of an EXR Relief wrote, a PNG's text
  // chunk); nullopt where the file has none (PFM holds no metadata).
  std::optional<std::string> text(const std::string& key) const;
  std::uintmax_t float_bytes() const;  // the pixels as floats

  // The pixels as floats, top row first (as the file stores them, and idiff counts rows).
  FloatImage read();

 private:
  struct Input;  // OpenImageIO's ImageInput, kept out of this header
  std::filesystem::path path_;
  std::unique_ptr<Input> input_;
  int width_ = 0, height_ = 0, channels_ = 0;
};

// The channel values of an image that are not finite: how many are NaN, how many infinite,
// and where the first is (x, y as stored, channel).
struct NonFiniteCount {
  std::uint64_t nan = 0, infinite = 0;
  int x = 0, y = 0, channel = 0;
  std::uint64_t total() const { return nan + infinite; }
  // "3 NaN and 1 infinite channel value(s), the first at (x, y) channel c"
  std::string describe() const;
};
NonFiniteCount count_non_finite(const FloatImage& image);

}  // namespace relief
