#include "image/png_encoder.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <memory>
#include <optional>
#include <utility>

#include <libdeflate.h>

#include "core/frame_memory.h"
#include "image/byte_order.h"

namespace relief {

namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
// libdeflate's fastest level: the size/time trade-off above (level 6: 8% smaller, 2.8x slower).
constexpr int kDeflateLevel = 1;
// IDAT chunks of at most this many bytes (PNG lengths are below 2^31).
constexpr std::size_t kMaxIdatBytes = std::size_t{1} << 30;

// Length, type, data, and the CRC of type and data (§5.3).
void append_chunk(std::vector<unsigned char>& out, const char (&type)[5], const unsigned char* data,
                  std::size_t size) {
  append_big_endian_u32(out, static_cast<std::uint32_t>(size));
  const std::size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + size);
  append_big_endian_u32(out, static_cast<std::uint32_t>(libdeflate_crc32(
                                 0, out.data() + type_at, static_cast<std::size_t>(4 + size))));
}

// Bytes every one of which is written before it is read, from the frame allocator
// (core/frame_memory.h), not value-initialised: from a megabyte up the block is mapped with its
// pages populated in one call and kept for the next image, where a zero-filled vector paid a
// fault and a memset per 4 KiB page (with the compressor's buffer, a fifth of a one-image
// process's page faults).
class ScratchBytes {
 public:
  explicit ScratchBytes(std::size_t size)
      : size_(std::max<std::size_t>(size, 1)),
        data_(static_cast<unsigned char*>(allocate_frame_buffer(size_, kAlign))) {}
  ScratchBytes(const ScratchBytes&) = delete;
  ScratchBytes& operator=(const ScratchBytes&) = delete;
  ~ScratchBytes() { free_frame_buffer(data_, size_, kAlign); }
  unsigned char* data() const { return data_; }

 private:
  static constexpr std::size_t kAlign = 64;
  std::size_t size_;
  unsigned char* data_;
};

struct CompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// The PNG of `height` rows of `row_bytes` bytes each, `pixel_bytes` to a pixel (Sub's offset),
// colour type and bit depth as IHDR gives them; `row(y, out)` writes row y (top row first).
template <class RowWriter>
std::vector<unsigned char> encode_png(int width, int height, std::size_t pixel_bytes,
                                      unsigned char colour_type, unsigned char bit_depth,
                                      const RowWriter& row) {
  if (width < 1 || height < 1) {
    return {};  // PNG has no empty image (§11.2.1)
  }
  const std::size_t row_bytes = static_cast<std::size_t>(width) * pixel_bytes;
  // §7.3 and §9.2: each scanline is its filter type byte, then Sub's differences, byte x minus
  // byte x - pixel_bytes (the same byte of the pixel to the left, 0 left of the first), modulo
  // 256.
  const std::size_t filtered_bytes = (row_bytes + 1) * static_cast<std::size_t>(height);
  std::optional<ScratchBytes> filtered(std::in_place, filtered_bytes);
  std::vector<unsigned char> raw(row_bytes);
  for (int y = 0; y < height; ++y) {
    row(y, raw.data());
    unsigned char* out = filtered->data() + static_cast<std::size_t>(y) * (row_bytes + 1);
    out[0] = 1;  // Sub
    std::memcpy(out + 1, raw.data(), pixel_bytes);
    for (std::size_t x = pixel_bytes; x < row_bytes; ++x) {
      out[1 + x] = static_cast<unsigned char>(raw[x] - raw[x - pixel_bytes]);
    }
  }
  const std::unique_ptr<libdeflate_compressor, CompressorDeleter> compressor(
      libdeflate_alloc_compressor(kDeflateLevel));
  if (!compressor) {
    return {};
  }
  // The bound is not filled (the compressed stream is a third of it on a render): plain
  // memory, neither zeroed nor faulted in beyond what the compressor writes.
  const std::size_t zlib_bound = libdeflate_zlib_compress_bound(compressor.get(), filtered_bytes);
  const std::unique_ptr<unsigned char[]> zlib(new unsigned char[zlib_bound]);
  const std::size_t zlib_bytes = libdeflate_zlib_compress(compressor.get(), filtered->data(),
                                                          filtered_bytes, zlib.get(), zlib_bound);
  if (zlib_bytes == 0) {  // cannot happen within the bound; refused rather than trusted
    return {};
  }
  filtered.reset();
  std::vector<unsigned char> png;
  png.reserve(8 + 25 + zlib_bytes + 12 * (zlib_bytes / kMaxIdatBytes + 1) + 12);
  png.insert(png.end(), kSignature, kSignature + 8);
  // IHDR (§11.2.1): width, height, bit depth, colour type, deflate, adaptive filtering, no
  // interlace.
  std::vector<unsigned char> header;
  append_big_endian_u32(header, static_cast<std::uint32_t>(width));
  append_big_endian_u32(header, static_cast<std::uint32_t>(height));
  header.insert(header.end(), {bit_depth, colour_type, 0, 0, 0});
  append_chunk(png, "IHDR", header.data(), header.size());
  for (std::size_t at = 0; at < zlib_bytes; at += kMaxIdatBytes) {
    append_chunk(png, "IDAT", zlib.get() + at, std::min(kMaxIdatBytes, zlib_bytes - at));
  }
  append_chunk(png, "IEND", nullptr, 0);
  return png;
}

}  // namespace

std::vector<unsigned char> encode_png_rgb8(int width, int height,
                                           std::span<const std::uint8_t> rgb) {
  const std::size_t row_bytes = static_cast<std::size_t>(std::max(width, 0)) * 3;
  assert(rgb.size() == row_bytes * static_cast<std::size_t>(std::max(height, 0)));
  // Colour type 2 (RGB), 8 bits; rows stored bottom row first.
  return encode_png(width, height, 3, 2, 8, [&](int y, unsigned char* out) {
    std::memcpy(out, rgb.data() + static_cast<std::size_t>(height - 1 - y) * row_bytes, row_bytes);
  });
}

std::vector<unsigned char> encode_png_rgba8(int width, int height,
                                            std::span<const std::uint8_t> rgba) {
  const std::size_t row_bytes = static_cast<std::size_t>(std::max(width, 0)) * 4;
  assert(rgba.size() == row_bytes * static_cast<std::size_t>(std::max(height, 0)));
  // Colour type 6 (RGB with alpha), 8 bits; rows top row first.
  return encode_png(width, height, 4, 6, 8, [&](int y, unsigned char* out) {
    std::memcpy(out, rgba.data() + static_cast<std::size_t>(y) * row_bytes, row_bytes);
  });
}

std::vector<unsigned char> encode_png_grey16(int width, int height,
                                             std::span<const std::uint16_t> levels) {
  const std::size_t w = static_cast<std::size_t>(std::max(width, 0));
  assert(levels.size() == w * static_cast<std::size_t>(std::max(height, 0)));
  // Colour type 0 (greyscale), 16 bits, each sample big-endian (§7.1); rows top row first.
  return encode_png(width, height, 2, 0, 16, [&](int y, unsigned char* out) {
    const std::uint16_t* row = levels.data() + static_cast<std::size_t>(y) * w;
    for (std::size_t x = 0; x < w; ++x) {
      out[2 * x] = static_cast<unsigned char>(row[x] >> 8);
      out[2 * x + 1] = static_cast<unsigned char>(row[x] & 0xFF);
    }
  });
}

}  // namespace relief
