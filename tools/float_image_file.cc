#include "tools/float_image_file.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "image/image_io.h"
#include "tools/atomic_file.h"
#include "tools/image_library.h"

namespace relief {

namespace {

bool ends_with(std::string_view name, std::string_view extension) {
  return name.size() >= extension.size() &&
         std::equal(
             extension.begin(), extension.end(), name.end() - extension.size(),
             [](char e, char c) { return e == std::tolower(static_cast<unsigned char>(c)); });
}

std::vector<unsigned char> encode_exr(int width, int height, int channels,
                                      std::span<const float> values, std::size_t stride,
                                      std::span<const ImageText> metadata) {
  std::string error;
  std::vector<unsigned char> bytes;
  try {
    bytes = image_library().encode_exr(width, height, channels, values, stride, metadata, error);
  } catch (const ImageLibraryError& e) {
    error = e.what();
  }
  if (bytes.empty()) {
    throw OutputError("cannot encode the EXR image: " +
                      (error.empty() ? std::string("OpenImageIO gave no reason") : error));
  }
  return bytes;
}

}  // namespace

std::optional<FloatFormat> float_format_of(std::string_view name) {
  if (ends_with(name, ".pfm")) {
    return FloatFormat::kPfm;
  }
  if (ends_with(name, ".exr")) {
    return FloatFormat::kExr;
  }
  return std::nullopt;
}

std::string_view float_extension(FloatFormat format) {
  return format == FloatFormat::kExr ? ".exr" : ".pfm";
}

std::vector<unsigned char> encode_float_image(FloatFormat format, int width, int height,
                                              int channels, std::span<const float> values,
                                              std::size_t stride,
                                              std::span<const ImageText> metadata) {
  if (format == FloatFormat::kExr) {
    return encode_exr(width, height, channels, values, stride, metadata);
  }
  return encode_pfm(width, height, channels, values, stride);
}

}  // namespace relief
