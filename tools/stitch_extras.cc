// The extra outputs of an image's shards stitched (relief stitch -o IMAGE.png --float F ...;
// stitch_files.h): the float, depth, normal, height and octave files and the primitive ids,
// each the bytes one render writes. A companion is taken only when its size and CRC-32 are
// those its shard's PNG recorded when it was written beside it: a file of another render
// (an older shard, a shard of another image given the same name) is refused, not stitched.
#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/json_input.h"
#include "image/crc32.h"
#include "image/image_io.h"
#include "tools/atomic_file.h"
#include "tools/float_image_file.h"
#include "tools/image_library.h"
#include "tools/stitch_files.h"

namespace relief {

namespace {

// The floats of a companion, rows bottom to top (width * rows * channels), decoded from the
// file a shard wrote: a PFM exactly as encode_pfm writes one (header and then the values), or
// an EXR read through OpenImageIO (32-bit float channels, rows top to bottom).
std::vector<float> companion_floats(const std::vector<unsigned char>& bytes,
                                    const std::filesystem::path& file, const std::string& what,
                                    int width, int rows, int channels) {
  const std::size_t count = std::size_t(width) * std::size_t(rows) * std::size_t(channels);
  std::vector<float> values(count);
  const std::optional<FloatFormat> format = float_format_of(file.string());
  if (format == FloatFormat::kPfm) {
    const std::string header = pfm_header(width, rows, channels);
    if (bytes.size() != header.size() + count * sizeof(float) ||
        std::memcmp(bytes.data(), header.data(), header.size()) != 0) {
      throw ShardError(what + " is not a " + std::to_string(width) + "x" + std::to_string(rows) +
                       " PFM of " + std::to_string(channels) + " channel(s) as relief writes it");
    }
    std::memcpy(values.data(), bytes.data() + header.size(), count * sizeof(float));
    return values;
  }
  if (format != FloatFormat::kExr) {
    throw ShardError(what + " is neither .pfm nor .exr");
  }
  std::string error;
  const std::unique_ptr<ImageReader> reader = image_library().open(file.string(), error);
  if (!reader) {
    throw ShardError(what + " cannot be read: " + error);
  }
  const ImageHeader& h = reader->header();
  if (h.width != width || h.height != rows || h.channels != channels || h.depth != 1 || h.deep) {
    throw ShardError(what + " is " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                     " with " + std::to_string(h.channels) + " channel(s), not " +
                     std::to_string(width) + "x" + std::to_string(rows) + " with " +
                     std::to_string(channels));
  }
  std::vector<float> top_first(count);
  if (!reader->read(top_first.data(), error)) {
    throw ShardError(what + " cannot be read: " + error);
  }
  const std::size_t row = std::size_t(width) * std::size_t(channels);
  for (int y = 0; y < rows; ++y) {
    std::memcpy(values.data() + row * std::size_t(rows - 1 - y),
                top_first.data() + row * std::size_t(y), row * sizeof(float));
  }
  return values;
}

}  // namespace

std::filesystem::path companion_path(const ImageShard& shard, const ShardCompanion& companion) {
  // From the PNG's resolved directory, as companion_file_name recorded it.
  const std::filesystem::path file(companion.file);
  if (file.is_absolute()) {
    return file;
  }
  std::error_code error;
  const std::filesystem::path png = std::filesystem::weakly_canonical(shard.file, error);
  return (error ? std::filesystem::path(shard.file) : png).parent_path() / file;
}

void add_extra_memory(MemoryEstimate& estimate, const ShardOutputKind& kind,
                      const std::vector<ImageShard>& shards) {
  const ImageShardRecord& r0 = shards.front().record;
  std::uintmax_t largest_file = 0;
  int tallest = 0;
  for (const ImageShard& s : shards) {
    const ShardCompanion& c = *find_companion(s.record, kind.kind);
    const std::filesystem::path file = companion_path(s, c);
    const std::uintmax_t size = shard_file_size(file);
    if (size != c.bytes) {
      throw ShardError("shard " + brief_text(s.file) + "'s " + std::string(kind.kind) + " output " +
                       brief_text(file.string()) + " holds " + std::to_string(size) +
                       " bytes, not the " + std::to_string(c.bytes) +
                       " its shard wrote (written again since, damaged or missing)");
    }
    largest_file = std::max(largest_file, size);
    tallest = std::max(tallest, s.record.rows);
  }
  // Floats, or 4 bytes of primitive id, per channel and pixel.
  const std::uintmax_t pixel = 4 * std::uintmax_t(kind.channels == 0 ? 1 : kind.channels);
  const std::uintmax_t image = pixel * std::uintmax_t(r0.width) * std::uintmax_t(r0.height);
  const std::uintmax_t band = pixel * std::uintmax_t(r0.width) * std::uintmax_t(tallest);
  estimate.add(std::string(kind.kind) + " image and its encoding", 2 * image);
  // The file, its values and (EXR) the rows as read.
  estimate.add(std::string(kind.kind) + " of one shard", largest_file + 2 * band);
}

std::vector<unsigned char> stitch_extra(const ShardOutputKind& kind, const std::string& output,
                                        const std::vector<ImageShard>& shards) {
  const int width = shards.front().record.width;
  const int height = shards.front().record.height;
  const int channels = kind.channels == 0 ? 1 : kind.channels;
  const std::size_t row = std::size_t(width) * std::size_t(channels);
  std::vector<float> floats;
  std::vector<unsigned char> ids;
  if (kind.channels == 0) {
    ids.resize(row * std::size_t(height) * 4);
  } else {
    floats.resize(row * std::size_t(height));
  }
  for (const ImageShard& s : shards) {
    const ShardCompanion& c = *find_companion(s.record, kind.kind);
    const std::filesystem::path file = companion_path(s, c);
    const std::string label =
        "shard " + brief_text(s.file) + "'s " + std::string(kind.kind) + " output";
    const std::string what = label + " " + brief_text(file.string());
    const std::vector<unsigned char> bytes = read_shard_file(file.string(), label);
    if (bytes.size() != c.bytes || crc32(bytes) != c.crc) {
      throw ShardError(what +
                       " is not the file that shard wrote: its size or CRC-32 differs "
                       "from the shard's record (written again since, or damaged)");
    }
    // The shard's PNG row `top` is framebuffer row height - 1 - top: its rows start here.
    const std::size_t first = std::size_t(height - s.record.top - s.record.rows);
    const int rows = s.record.rows;
    if (kind.channels == 0) {
      if (bytes.size() != row * std::size_t(rows) * 4) {
        throw ShardError(what + " holds " + std::to_string(bytes.size()) + " bytes, not the " +
                         std::to_string(row * std::size_t(rows) * 4) + " of " +
                         std::to_string(width) + "x" + std::to_string(rows) + " 32-bit ids");
      }
      std::memcpy(ids.data() + row * first * 4, bytes.data(), bytes.size());
      continue;
    }
    const std::vector<float> values = companion_floats(bytes, file, what, width, rows, channels);
    std::memcpy(floats.data() + row * first, values.data(), values.size() * sizeof(float));
  }
  if (kind.channels == 0) {
    return ids;
  }
  return encode_float_image(float_format_of(output).value_or(FloatFormat::kPfm), width, height,
                            channels, floats, row, shards.front().text);
}

}  // namespace relief
