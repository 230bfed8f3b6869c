#include "image/png_text.h"

#include <algorithm>
#include <cstdint>
#include <string_view>

#include "image/byte_order.h"
#include "image/crc32.h"
#include "image/png_header.h"

namespace relief {

namespace {

// PNG's largest chunk length (§5.3: lengths are at most 2^31 - 1).
constexpr std::size_t kMaxChunkBytes = 0x7FFFFFFFu;

// §11.3.4.2: 1-79 bytes of Latin-1 32-126 or 161-255, no leading, trailing or double space.
void check_keyword(const std::string& keyword) {
  bool ok = !keyword.empty() && keyword.size() <= 79 && keyword.front() != ' ' &&
            keyword.back() != ' ' && keyword.find("  ") == std::string::npos;
  for (const char c : keyword) {
    const auto b = static_cast<unsigned char>(c);
    ok = ok && ((b >= 32 && b <= 126) || b >= 161);
  }
  if (!ok) {
    throw PngTextError("PNG text keyword '" + keyword + "' is not 1-79 printable characters");
  }
}

bool is_ascii(const std::string& text) {
  return std::all_of(text.begin(), text.end(),
                     [](char c) { return static_cast<unsigned char>(c) < 0x80; });
}

// Length, type, data, CRC of type and data (§5.3).
void append_chunk(std::vector<unsigned char>& out, std::string_view type,
                  const std::vector<unsigned char>& data) {
  if (data.size() > kMaxChunkBytes) {
    throw PngTextError("PNG text chunk of " + std::to_string(data.size()) + " bytes is too long");
  }
  append_big_endian_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::span<const unsigned char> type_bytes(
      reinterpret_cast<const unsigned char*>(type.data()), type.size());
  out.insert(out.end(), type_bytes.begin(), type_bytes.end());
  out.insert(out.end(), data.begin(), data.end());
  append_big_endian_u32(out, crc32(data, crc32(type_bytes)));
}

void append_text_chunk(std::vector<unsigned char>& out, const ImageText& entry) {
  check_keyword(entry.keyword);
  if (entry.text.find('\0') != std::string::npos) {
    throw PngTextError("PNG text '" + entry.keyword + "' contains a NUL character");
  }
  std::vector<unsigned char> data(entry.keyword.begin(), entry.keyword.end());
  data.push_back(0);  // keyword separator
  const bool ascii = is_ascii(entry.text);
  if (!ascii) {
    // iTXt: compression flag 0, method 0, empty language tag and translated keyword.
    data.insert(data.end(), {0, 0, 0, 0});
  }
  data.insert(data.end(), entry.text.begin(), entry.text.end());
  append_chunk(out, ascii ? "tEXt" : "iTXt", data);
}

}  // namespace

std::vector<unsigned char> insert_png_text(std::span<const unsigned char> png,
                                           std::span<const ImageText> entries) {
  if (!parse_png_header(png.data(), png.size())) {
    throw PngTextError("insert_png_text: the bytes are not a PNG starting with IHDR");
  }
  // Signature (8) and IHDR: length (4), type (4), 13 data bytes, CRC (4).
  constexpr std::size_t kAfterIhdr = 8 + 4 + 4 + 13 + 4;
  std::vector<unsigned char> out(png.begin(), png.begin() + kAfterIhdr);
  for (const ImageText& entry : entries) {
    append_text_chunk(out, entry);
  }
  out.insert(out.end(), png.begin() + kAfterIhdr, png.end());
  return out;
}

std::vector<ImageText> read_png_text(std::span<const unsigned char> png) {
  std::vector<ImageText> entries;
  std::size_t at = 8;
  while (at + 12 <= png.size()) {
    const std::size_t length = read_big_endian_u32(png.data() + at);
    if (length > png.size() - at - 12) {
      break;
    }
    const std::string type(png.begin() + at + 4, png.begin() + at + 8);
    const std::span<const unsigned char> data = png.subspan(at + 8, length);
    const bool crc_ok =
        crc32(png.subspan(at + 4, length + 4)) == read_big_endian_u32(png.data() + at + 8 + length);
    at += length + 12;
    if (type == "IEND") {
      break;
    }
    const auto separator = std::find(data.begin(), data.end(), 0);
    if (!crc_ok || separator == data.end() || (type != "tEXt" && type != "iTXt")) {
      continue;
    }
    ImageText entry{std::string(data.begin(), separator), {}};
    auto text = separator + 1;
    if (type == "iTXt") {
      // Compression flag and method, then the language tag and the translated keyword, each
      // ending in NUL; only uncompressed text is read.
      if (data.end() - text < 2 || *text != 0) {
        continue;
      }
      text = std::find(text + 2, data.end(), 0);
      text = text == data.end() ? text : std::find(text + 1, data.end(), 0);
      if (text == data.end()) {
        continue;
      }
      ++text;
    }
    entry.text.assign(text, data.end());
    entries.push_back(std::move(entry));
  }
  return entries;
}

}  // namespace relief
