// librelief_images.so: every OpenImageIO call of the command line (image_library.h), loaded
// with dlopen only by the commands that need it. The code is what image_file.cc and
// float_image_file.cc ran when OpenImageIO was linked into the binary; image_compare.cc now
// computes ImageBufAlgo::compare's figures itself.
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "tools/image_library.h"

namespace relief {

namespace {

class OiioReader : public ImageReader {
 public:
  explicit OiioReader(std::unique_ptr<OIIO::ImageInput> input) : input_(std::move(input)) {
    const OIIO::ImageSpec& spec = input_->spec();
    header_.width = spec.width;
    header_.height = spec.height;
    header_.depth = spec.depth;
    header_.channels = spec.nchannels;
    header_.deep = spec.deep;
    header_.format = input_->format_name();
    header_.channel_names = spec.channelnames;
  }
  const ImageHeader& header() const override { return header_; }
  std::optional<std::string> text(const std::string& key) const override {
    const OIIO::ParamValue* value = input_->spec().find_attribute(key, OIIO::TypeString);
    if (value == nullptr) {
      return std::nullopt;
    }
    return std::string(value->get_ustring().string());
  }
  bool read(float* pixels, std::string& error) override {
    // OpenImageIO 2.4 answers true for a TIFF whose strips are cut short, leaving zeros and an
    // error behind: an error either way refuses the file.
    if (!input_->read_image(0, 0, 0, header_.channels, OIIO::TypeFloat, pixels) ||
        input_->has_error()) {
      error = input_->geterror();
      if (error.empty()) {
        error = "its pixels could not be read";
      }
      return false;
    }
    return true;
  }

 private:
  std::unique_ptr<OIIO::ImageInput> input_;
  ImageHeader header_;
};

class OiioLibrary : public ImageLibrary {
 public:
  std::unique_ptr<ImageReader> open(const std::string& path, std::string& error) const override {
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(input));
  }

  std::vector<unsigned char> encode_exr(int width, int height, int channels,
                                        std::span<const float> values, std::size_t stride,
                                        std::span<const ImageText> metadata,
                                        std::string& error) const override {
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeFloat);
    spec.channelnames =
        channels == 3 ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"Y"};
    spec.attribute("compression", "zip");
    // OpenImageIO stamps the time of writing unless DateTime is given; empty, it writes none,
    // so the same scene gives the same bytes on every run (docs/architecture.md, "Determinism").
    spec.attribute("DateTime", "");
    for (const ImageText& entry : metadata) {
      spec.attribute(entry.keyword, entry.text);
    }
    // Encoded in memory, so that the file is written like every other output (atomic_file.h).
    // Reserved for the uncompressed floats and headers: ZIP output stays within that (it
    // stores a block that would not shrink), so the vector does not double as it grows.
    std::size_t reserve = std::size_t(width) * std::size_t(height) * std::size_t(channels) * 4 +
                          (std::size_t{1} << 20);
    for (const ImageText& entry : metadata) {
      reserve += entry.keyword.size() + entry.text.size();
    }
    std::vector<unsigned char> bytes;
    bytes.reserve(reserve);
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    const std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("relief.exr");
    if (!out) {
      error = OIIO::geterror();
      return {};
    }
    if (!out->set_ioproxy(&proxy) || !out->open("relief.exr", spec)) {
      error = out->geterror();
      return {};
    }
    // Row 0 of `values` is the bottom row and EXR stores the top row first: start at the last
    // row and step backwards.
    const auto row_bytes = static_cast<OIIO::stride_t>(stride * sizeof(float));
    const float* top_row = values.data() + std::size_t(height - 1) * stride;
    if (!out->write_image(OIIO::TypeFloat, top_row, OIIO::AutoStride, -row_bytes) ||
        !out->close()) {
      error = out->geterror();
      return {};
    }
    return bytes;
  }
};

}  // namespace

}  // namespace relief

extern "C" __attribute__((visibility("default"))) const relief::ImageLibrary*
relief_image_library() {
  static const relief::OiioLibrary library;
  return &library;
}
