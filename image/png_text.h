// Text chunks in a PNG that an encoder produced (png_encoder.h): the image's metadata
// (image/image_metadata.h) added without a PNG library. Each entry becomes one chunk placed
// right after IHDR (ISO/IEC 15948 §5.6: text chunks may go anywhere between IHDR and IEND;
// first, so that a reader stopping early still finds them): tEXt (§11.3.4.3) when the text is
// ASCII, else iTXt (§11.3.4.5) with UTF-8 text, uncompressed, no language tag. The pixels and
// every other chunk are left as they were.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace relief {

struct ImageText {
  std::string keyword;  // 1 to 79 printable Latin-1 characters, no leading or trailing space
  std::string text;     // UTF-8, no NUL
};

// A keyword or text that no PNG reader may accept, or bytes that are not a PNG starting with
// IHDR: a programming error, since Relief makes both.
class PngTextError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// `png` with one text chunk per entry inserted after IHDR.
std::vector<unsigned char> insert_png_text(std::span<const unsigned char> png,
                                           std::span<const ImageText> entries);

// The text chunks of a PNG (tEXt, and iTXt without compression), in file order: what
// insert_png_text wrote, for tests and tools. Stops at IEND or at the first chunk whose length
// runs past the end; a chunk with a wrong CRC is skipped.
std::vector<ImageText> read_png_text(std::span<const unsigned char> png);

}  // namespace relief
