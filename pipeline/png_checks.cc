#include "pipeline/png_checks.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include <stb_image.h>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/scene_json.h"
#include "image/png_header.h"
#include "image/png_layout.h"
#include "pipeline/builtin_sketches.h"

namespace relief {

// stb says why it failed through a global that some failures leave as it was (an invalid
// deflate block sets nothing), so a reason left by an earlier texture could be reported. This
// sets it to a known value first: stb_info on no bytes fails with "unknown image type".
namespace {
constexpr std::string_view kNoStbReason = "unknown image type";
}  // namespace

void reset_stb_failure_reason() {
  static constexpr unsigned char kNothing[1] = {0};
  int unused = 0;
  stbi_info_from_memory(kNothing, 0, &unused, &unused, &unused);
}

// Why stb failed, or `fallback` when it did not say.
std::string stb_failure_reason_or(const char* fallback) {
  const char* reason = stbi_failure_reason();
  return reason && *reason && reason != kNoStbReason ? reason : fallback;
}

PngHeader png_header_or_throw(const std::vector<unsigned char>& bytes, const std::string& field,
                              const std::string& path) {
  const std::optional<PngHeader> png = parse_png_header(bytes.data(), bytes.size());
  if (!png) {
    throw SceneError(path, "scene: " + field + " is not a PNG image (no PNG signature and header)");
  }
  return *png;
}

std::vector<unsigned char> read_png_file(
    const std::string& file_name, const std::string& field, const std::string& path,
    const std::function<void(const std::vector<unsigned char>&)>& check_header,
    std::uintmax_t max_bytes) {
  std::vector<unsigned char> bytes;
  try {
    InputFile file(file_name, max_bytes);
    bytes.resize(kPngHeaderBytes);
    bytes.resize(file.read(bytes.data(), bytes.size()));
    check_header(bytes);  // before the rest of the file is read
    const std::string rest = file.read_rest();
    bytes.insert(bytes.end(), rest.begin(), rest.end());
  } catch (const InputFileError& e) {
    throw SceneError(path, "scene: " + field + " " + e.what());
  }
  return bytes;
}

void check_png_image_data(const std::vector<unsigned char>& png, const std::string& field,
                          const std::string& path) {
  const PngLayout layout = png_layout(png.data(), png.size());
  if (!layout.problem.empty()) {
    throw SceneError(path, "scene: " + field + " could not be decoded: " + layout.problem);
  }
  const PngHeader header = *parse_png_header(png.data(), png.size());
  const std::uint64_t filtered_bytes = png_filtered_image_bytes(header, header.interlace != 0);
  if (filtered_bytes == 0) {
    throw SceneError(path, "scene: " + field + " has bit depth " +
                               std::to_string(header.bit_depth) + " with colour type " +
                               std::to_string(header.colour_type) +
                               ", a combination PNG does not allow");
  }
  // Inflated once into a buffer one byte larger than the header needs (at most 4096 x 16385
  // bytes, 8-bit RGBA): stb's own inflate grows its buffer for as long as the stream goes on,
  // so a small file could make it allocate gigabytes. Costs a second inflate of the data.
  std::vector<char> inflated(filtered_bytes + 1);
  reset_stb_failure_reason();
  const int inflated_bytes =
      stbi_zlib_decode_buffer(inflated.data(), static_cast<int>(inflated.size()),
                              reinterpret_cast<const char*>(layout.image_data.data()),
                              static_cast<int>(layout.image_data.size()));
  const std::string inflate_error = inflated_bytes < 0 ? stb_failure_reason_or("") : "";
  if ((inflated_bytes >= 0 && std::uint64_t(inflated_bytes) > filtered_bytes) ||
      inflate_error == "output buffer limit") {
    throw SceneError(path, "scene: " + field + " could not be decoded: its image data inflates " +
                               "to more than the " + std::to_string(filtered_bytes) +
                               " bytes its " + std::to_string(header.width) + "x" +
                               std::to_string(header.height) + " header gives");
  }
  if (inflated_bytes < 0) {
    throw SceneError(path, "scene: " + field + " could not be decoded: corrupt image data" +
                               (inflate_error.empty() ? "" : " (" + inflate_error + ")"));
  }
}

Grey16Image decode_grey16_png(const std::vector<unsigned char>& png, const std::string& field,
                              const std::string& path, std::uintmax_t max_bytes) {
  static_assert(limits::kMaxHeightFieldFileBytes < (1u << 31), "stb takes an int size");
  if (png.size() > max_bytes || png.size() > limits::kMaxHeightFieldFileBytes) {
    throw SceneError(path,
                     "scene: " + field + " is larger than " + std::to_string(max_bytes) + " bytes");
  }
  check_png_image_data(png, field, path);
  const PngHeader header = png_header_or_throw(png, field, path);
  int width = 0, height = 0, channels = 0;
  reset_stb_failure_reason();
  stbi_us* grey = stbi_load_16_from_memory(png.data(), static_cast<int>(png.size()), &width,
                                           &height, &channels, 1);
  if (!grey || std::uint32_t(width) != header.width || std::uint32_t(height) != header.height) {
    stbi_image_free(grey);
    throw SceneError(path, "scene: " + field + " could not be decoded: " +
                               (grey ? std::string("its header and data disagree")
                                     : stb_failure_reason_or("corrupt image data")));
  }
  Grey16Image image{width, height, {}};
  image.levels.assign(grey, grey + std::size_t(width) * std::size_t(height));
  stbi_image_free(grey);
  return image;
}

PngPeek peek_png(const std::string& name, std::uintmax_t max_bytes) {
  static constexpr std::string_view kBuiltin = "builtin:";
  PngPeek peek;
  if (name.rfind(kBuiltin, 0) == 0) {
    const std::span<const unsigned char> png =
        builtin_sketch_png(std::string_view(name).substr(kBuiltin.size()));
    peek.header = parse_png_header(png.data(), png.size());
    peek.file_bytes = png.size();
    return peek;
  }
  try {
    InputFile file(name, max_bytes);
    unsigned char header[kPngHeaderBytes];
    peek.header = parse_png_header(header, file.read(header, sizeof header));
    peek.file_bytes = file.size();
  } catch (const InputFileError&) {
  }
  return peek;
}

}  // namespace relief
