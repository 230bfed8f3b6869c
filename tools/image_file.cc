#include "tools/image_file.h"

#include <algorithm>
#include <cmath>

#include "core/input_file.h"
#include "core/scene/json_input.h"
#include "tools/image_library.h"

namespace relief {

struct ImageFile::Input {
  std::unique_ptr<ImageReader> image;
};

namespace {

std::string named(const std::filesystem::path& path) {
  return brief_text(path.string());
}

// OpenImageIO's message, on one line (it may hold several, one per plugin tried).
std::string oiio_reason(std::string message) {
  for (char& c : message) {
    c = (c == '\n' || c == '\t') ? ' ' : c;
  }
  return brief_text(message.empty() ? std::string("unknown error") : message, 3 * kBriefChars);
}

}  // namespace

ImageFile::ImageFile(const std::filesystem::path& path)
    : path_(path), input_(std::make_unique<Input>()) {
  try {
    // Only a regular file of a bounded size reaches OpenImageIO; the descriptor is closed
    // again at once, OpenImageIO opens the file by name.
    const InputFile check(path, kMaxImageFileBytes);
  } catch (const InputFileError& e) {
    throw ImageFileError(named(path) + " " + e.what());
  }
  std::string error;
  try {
    input_->image = image_library().open(path.string(), error);
  } catch (const ImageLibraryError& e) {
    throw ImageFileError(named(path) + " cannot be read: " + e.what());
  }
  if (!input_->image) {
    throw ImageFileError(named(path) + " cannot be read as an image: " + oiio_reason(error));
  }
  const ImageHeader& header = input_->image->header();
  if (header.deep || header.depth != 1) {
    throw ImageFileError(named(path) + " is a " + (header.deep ? "deep" : "volume") +
                         " image; only flat 2-D images are compared");
  }
  if (header.width < 1 || header.height < 1 || header.channels < 1) {
    throw ImageFileError(named(path) + " holds no pixels");
  }
  width_ = header.width;
  height_ = header.height;
  channels_ = header.channels;
}

ImageFile::~ImageFile() = default;

std::string ImageFile::format() const {
  return input_->image->header().format;
}

std::optional<std::string> ImageFile::text(const std::string& key) const {
  return input_->image->text(key);
}

std::uintmax_t ImageFile::float_bytes() const {
  return std::uintmax_t(width_) * std::uintmax_t(height_) * std::uintmax_t(channels_) *
         sizeof(float);
}

FloatImage ImageFile::read() {
  FloatImage image;
  image.width = width_;
  image.height = height_;
  image.channels = channels_;
  image.channel_names = input_->image->header().channel_names;
  image.pixels.resize(float_bytes() / sizeof(float));
  std::string error;
  if (!input_->image->read(image.pixels.data(), error)) {
    throw ImageFileError(named(path_) + " cannot be read: " + oiio_reason(error));
  }
  return image;
}

NonFiniteCount count_non_finite(const FloatImage& image) {
  NonFiniteCount count;
  const std::size_t channels = std::size_t(std::max(image.channels, 1));
  for (std::size_t k = 0; k < image.pixels.size(); ++k) {
    const float v = image.pixels[k];
    if (std::isfinite(v)) {
      continue;
    }
    if (count.total() == 0) {
      const std::size_t pixel = k / channels;
      count.x = int(pixel % std::size_t(std::max(image.width, 1)));
      count.y = int(pixel / std::size_t(std::max(image.width, 1)));
      count.channel = int(k % channels);
    }
    ++(std::isnan(v) ? count.nan : count.infinite);
  }
  return count;
}

std::string NonFiniteCount::describe() const {
  return std::to_string(nan) + " NaN and " + std::to_string(infinite) +
         " infinite channel value(s), the first at (" + std::to_string(x) + ", " +
         std::to_string(y) + ") channel " + std::to_string(channel);
}

}  // namespace relief
