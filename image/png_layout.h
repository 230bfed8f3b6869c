// The layout of a whole PNG file (ISO/IEC 15948 §5.3, §7, §8.2), checked before a decoder sees
// it: stb_image trusts a chunk's length field and grows its buffer to it before reading the
// data (a 73-byte file made it allocate 2 GiB), and it inflates the image data for as long as
// the deflate stream goes on (up to 4 GiB from a few MiB of file). Relief therefore checks
// that every chunk lies within the file and bounds the inflated size by the header's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "image/png_header.h"

namespace relief {

struct PngLayout {
  std::string problem;                    // "" when the chunks are well-formed, else why not
  std::vector<unsigned char> image_data;  // the IDAT chunks' data, concatenated (§10.1)
};

// Walks the chunks after the signature up to IEND: each needs its 12 bytes of length, type and
// CRC and its data within the file, and a length of at most 2^31 - 1 (§5.3); an empty IDAT
// before the first with data is refused too (stb_image mishandles it). With `check_crc`, each
// chunk's CRC-32 (§5.3) must also be that of its type and data, so that a damaged file is told
// from a whole one (a decoder checks neither the CRCs nor zlib's Adler-32). `problem` says which
// chunk broke which rule, at which byte offset.
PngLayout png_layout(const unsigned char* bytes, std::size_t size, bool check_crc = false);

// The size of the filtered image data that `header` describes (one filter byte per row, rows
// of whole bytes; the seven reduced images of Adam7 when `interlaced`, §8.2), or 0 for a bit
// depth that the colour type does not allow (§11.2.2).
std::uint64_t png_filtered_image_bytes(const PngHeader& header, bool interlaced);

}  // namespace relief
