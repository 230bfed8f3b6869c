#include "tools/float_image_file.h"

#include <algorithm>
#include <cctype>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "pipeline/image_io.h"
#include "tools/atomic_file.h"

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
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeFloat);
  spec.channelnames =
      channels == 3 ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"Y"};
  spec.attribute("compression", "zip");
  // OpenImageIO stamps the time of writing unless DateTime is given; empty, it writes none, so
  // the same scene gives the same bytes on every run (docs/architecture.md, "Determinism").
  spec.attribute("DateTime", "");
  for (const ImageText& entry : metadata) {
    spec.attribute(entry.keyword, entry.text);
  }
  // Encoded in memory, so that the file is written like every other output (atomic_file.h).
  // Reserved for the uncompressed floats and headers: ZIP output stays within that (it stores
  // a block that would not shrink), so the vector does not double as it grows.
  std::size_t reserve =
      std::size_t(width) * std::size_t(height) * std::size_t(channels) * 4 + (std::size_t{1} << 20);
  for (const ImageText& entry : metadata) {
    reserve += entry.keyword.size() + entry.text.size();
  }
  std::vector<unsigned char> bytes;
  bytes.reserve(reserve);
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  const std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("relief.exr");
  const auto fail = [&](const std::string& reason) {
    return OutputError("cannot encode the EXR image: " +
                       (reason.empty() ? std::string("OpenImageIO gave no reason") : reason));
  };
  if (!out) {
    throw fail(OIIO::geterror());
  }
  if (!out->set_ioproxy(&proxy) || !out->open("relief.exr", spec)) {
    throw fail(out->geterror());
  }
  // Row 0 of `values` is the bottom row and EXR stores the top row first: start at the last
  // row and step backwards.
  const auto row_bytes = static_cast<OIIO::stride_t>(stride * sizeof(float));
  const float* top_row = values.data() + std::size_t(height - 1) * stride;
  if (!out->write_image(OIIO::TypeFloat, top_row, OIIO::AutoStride, -row_bytes) || !out->close()) {
    throw fail(out->geterror());
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
