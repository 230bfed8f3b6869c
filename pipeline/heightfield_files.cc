#include "pipeline/heightfield_files.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/png_header.h"
#include "pipeline/geotiff_reference.h"
#include "pipeline/heightfield_checks.h"
#include "pipeline/png_checks.h"

namespace relief {

namespace {

using namespace heightfield_checks;

// A PFM's header is read from the file's first bytes: "Pf", two sides of at most 5 digits and a
// scale fit in a few dozen (longer padding is refused, saying so).
constexpr std::size_t kPfmHeaderBytes = 128;

HeightFieldImageReader image_reader = nullptr;  // set_height_field_image_reader

HeightFieldFormat format_of(const HeightFieldSettings& s) {
  if (s.image.rfind("builtin:", 0) == 0) {
    refuse(s,
           "names a built-in image; allowed: a file (the built-in island is a sketch: "
           "terrain.sketch.image = \"builtin:island\")");
  }
  if (has_extension(s.image, ".png")) {
    return HeightFieldFormat::kPng;
  }
  if (has_extension(s.image, ".pfm")) {
    return HeightFieldFormat::kPfm;
  }
  if (has_extension(s.image, ".r16") || has_extension(s.image, ".raw")) {
    return HeightFieldFormat::kRaw16;
  }
  if (has_extension(s.image, ".exr") || has_extension(s.image, ".tif") ||
      has_extension(s.image, ".tiff")) {
    return HeightFieldFormat::kImage;
  }
  refuse(s,
         "has no height format's extension; allowed: .png (grey, 8 or 16 bits), .pfm (one "
         "channel), .r16 / .raw (RAW16), .exr, .tif / .tiff (one channel)");
}

// A PFM's header: "Pf", width, height and scale separated by white space, then one white-space
// byte before the samples (little-endian when scale < 0).
struct PfmHeader {
  std::uint64_t width = 0, height = 0;
  bool little_endian = true;
  std::size_t bytes = 0;  // header length
};

PfmHeader parse_pfm_header(const HeightFieldSettings& s, const unsigned char* data,
                           std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::size_t at = 0;
  const auto token = [&]() {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) {
      ++at;
    }
    const std::size_t begin = at;
    while (at < text.size() && !std::isspace(static_cast<unsigned char>(text[at]))) {
      ++at;
    }
    return text.substr(begin, at - begin);
  };
  const std::string_view magic = token();
  if (magic == "PF") {
    refuse(s, "is a three-channel PFM (PF); allowed: one channel (Pf)");
  }
  if (magic != "Pf") {
    refuse(s, "is not a PFM (it does not begin with Pf)");
  }
  // The header as read, for messages: white space shown as single spaces, other bytes that do
  // not print as '?'.
  const auto shown = [&](std::size_t end) {
    std::string out;
    for (const char c : text.substr(0, std::min(end, text.size()))) {
      const auto u = static_cast<unsigned char>(c);
      if (std::isspace(u)) {
        if (out.empty() || out.back() != ' ') {
          out.push_back(' ');
        }
      } else {
        out.push_back(std::isprint(u) ? c : '?');
      }
    }
    return brief_text(out);
  };
  PfmHeader header;
  const std::string_view width = token(), height = token(), scale = token();
  const auto whole = [](std::string_view t, std::uint64_t& v) {
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), v);
    return !t.empty() && error == std::errc() && end == t.data() + t.size();
  };
  double scale_value = 0;
  const auto [scale_end, scale_error] =
      std::from_chars(scale.data(), scale.data() + scale.size(), scale_value);
  if (!whole(width, header.width) || !whole(height, header.height) || scale.empty() ||
      scale_error != std::errc() || scale_end != scale.data() + scale.size() ||
      !std::isfinite(scale_value) || scale_value == 0 || at >= text.size()) {
    refuse(s, "has a malformed PFM header \"" + shown(at) +
                  "\"; allowed: Pf, width and height in decimal digits and a finite non-zero "
                  "scale, separated by white space, then one white-space byte, all within the "
                  "first " +
                  std::to_string(kPfmHeaderBytes) + " bytes");
  }
  if (text[at] == '\r' && at + 1 < text.size() && text[at + 1] == '\n') {
    refuse(s,
           "ends its PFM header with CR LF; allowed: one white-space byte (LF) before the "
           "samples");
  }
  header.little_endian = scale_value < 0;
  header.bytes = at + 1;
  return header;
}

// An EXR or TIFF through the installed reader: one channel (a height map; several would leave
// the height to guess), refused naming the field otherwise.
HeightFieldImage read_image(const HeightFieldSettings& s, bool header_only, int width = 0,
                            int height = 0) {
  if (image_reader == nullptr) {
    refuse(s,
           "is an EXR or TIFF file, which this program cannot read (the relief command line "
           "reads them through its image module); allowed here: .png, .pfm, .r16, .raw");
  }
  HeightFieldImage image;
  image.width = width;  // the header's, when the pixels are asked for
  image.height = height;
  image.channels = header_only ? 0 : 1;
  std::string error;
  if (!image_reader(s.image, header_only, image, error)) {
    refuse(s, "could not be read as an image: " + brief_text(error));
  }
  if (image.channels != 1) {
    refuse(s, "has " + std::to_string(image.channels) +
                  " channels; allowed: one (the heights), as a grey EXR or a one-band TIFF");
  }
  return image;
}

HeightFieldPeek peek_or_throw(const HeightFieldSettings& s) {
  HeightFieldPeek peek;
  peek.format = format_of(s);
  peek.levels_of_detail = !s.fractal && s.level_of_detail;
  if (s.raw_width != 0 && peek.format != HeightFieldFormat::kRaw16) {
    throw SceneError("terrain.heightfield.raw_width",
                     "scene: terrain.heightfield.raw_width = " + std::to_string(s.raw_width) +
                         " is for RAW16 files, but " + field_text(s) +
                         " is not one; allowed: 0 (or a .r16 / .raw file)");
  }
  if (peek.format == HeightFieldFormat::kPng) {
    const PngPeek png = peek_png(s.image, limits::kMaxHeightFieldFileBytes);
    if (!png.header) {
      file_size(s, limits::kMaxHeightFieldFileBytes);  // names why it cannot be read
      refuse(s, "is not a PNG image");
    }
    peek.file_bytes = png.file_bytes;
    peek.width = png.header->width;
    peek.height = png.header->height;
  } else if (peek.format == HeightFieldFormat::kPfm) {
    unsigned char head[kPfmHeaderBytes];
    std::size_t got = 0;
    try {
      InputFile file(s.image, limits::kMaxHeightFieldFileBytes);
      got = file.read(head, sizeof head);
      peek.file_bytes = file.size();
    } catch (const InputFileError& e) {
      refuse(s, e.what());
    }
    const PfmHeader header = parse_pfm_header(s, head, got);
    peek.width = header.width;
    peek.height = header.height;
  } else if (peek.format == HeightFieldFormat::kImage) {
    peek.file_bytes = file_size(s, limits::kMaxHeightFieldFileBytes);  // a regular file first
    const HeightFieldImage header = read_image(s, true);
    peek.width = std::uint64_t(header.width);
    peek.height = std::uint64_t(header.height);
  } else {
    peek.file_bytes = file_size(s, limits::kMaxHeightFieldFileBytes);
    const std::uintmax_t samples = peek.file_bytes / 2;
    if (peek.file_bytes % 2 != 0) {
      refuse(s, "is " + std::to_string(peek.file_bytes) +
                    " bytes, not a whole number of 16-bit samples");
    }
    if (s.raw_width == 0) {
      const auto side = static_cast<std::uint64_t>(std::llround(std::sqrt(double(samples))));
      if (side * side != samples) {
        refuse(s, "holds " + std::to_string(samples) +
                      " samples, not a square number; give terrain.heightfield.raw_width");
      }
      peek.width = peek.height = side;
    } else {
      if (samples % std::uintmax_t(s.raw_width) != 0) {
        throw SceneError("terrain.heightfield.raw_width",
                         "scene: terrain.heightfield.raw_width = " + std::to_string(s.raw_width) +
                             " does not divide the " + std::to_string(samples) + " samples of " +
                             field_text(s) + " into whole rows; allowed: the file's row length");
      }
      peek.width = std::uint64_t(s.raw_width);
      peek.height = samples / std::uint64_t(s.raw_width);
    }
  }
  check_side(s, peek.width, peek.height, "samples");
  if (peek.format == HeightFieldFormat::kPfm) {
    // Refused from the header and the file's size, before a sample is allocated or read.
    unsigned char head[kPfmHeaderBytes];
    std::size_t got = 0;
    try {
      got = InputFile(s.image, limits::kMaxHeightFieldFileBytes).read(head, sizeof head);
    } catch (const InputFileError& e) {
      refuse(s, e.what());
    }
    const std::uintmax_t expected =
        parse_pfm_header(s, head, got).bytes + peek.width * peek.height * sizeof(float);
    if (peek.file_bytes != expected) {
      refuse(s, "is " + std::to_string(peek.file_bytes) + " bytes; its header (" +
                    size_text(peek.width, peek.height) + ") asks for exactly " +
                    std::to_string(expected));
    }
  }
  return peek;
}

HeightSketch load_pfm(const HeightFieldSettings& s, const HeightFieldPeek& peek) {
  const int width = int(peek.width), height = int(peek.height);
  std::vector<float> values(std::size_t(width) * std::size_t(height));
  try {
    InputFile file(s.image, limits::kMaxHeightFieldFileBytes);
    unsigned char head[kPfmHeaderBytes];
    const std::size_t got = file.read(head, sizeof head);
    const PfmHeader header = parse_pfm_header(s, head, got);
    if (header.width != peek.width || header.height != peek.height) {
      refuse(s, "changed while it was read");  // before the samples' size is trusted
    }
    const std::uintmax_t expected = header.bytes + values.size() * sizeof(float);
    if (file.size() != expected) {
      refuse(s, "is " + std::to_string(file.size()) + " bytes; its header (" +
                    size_text(peek.width, peek.height) + ") asks for exactly " +
                    std::to_string(expected));
    }
    // The samples after the header: the bytes already read, then the rest in place.
    const std::size_t early = got - header.bytes;
    auto* bytes = reinterpret_cast<unsigned char*>(values.data());
    std::memcpy(bytes, head + header.bytes, early);
    const std::size_t rest = values.size() * sizeof(float) - early;
    if (file.read(bytes + early, rest) != rest) {
      refuse(s, "ends before its samples do");
    }
    if (header.little_endian != (std::endian::native == std::endian::little)) {
      for (float& v : values) {
        v = std::bit_cast<float>(__builtin_bswap32(std::bit_cast<std::uint32_t>(v)));
      }
    }
  } catch (const InputFileError& e) {
    refuse(s, e.what());
  }
  // PFM rows go from the bottom up; the field's row 0 is the picture's top (z0).
  for (int j = 0; j < height / 2; ++j) {
    std::swap_ranges(values.begin() + std::ptrdiff_t(j) * width,
                     values.begin() + std::ptrdiff_t(j + 1) * width,
                     values.begin() + std::ptrdiff_t(height - 1 - j) * width);
  }
  check_samples(s, values, width);
  return make_height_field(s, width, height, values, !s.fractal && s.level_of_detail,
                           s.interpolating);
}

HeightSketch load_raw16(const HeightFieldSettings& s, const HeightFieldPeek& peek) {
  std::vector<std::uint16_t> levels(std::size_t(peek.width) * std::size_t(peek.height));
  try {
    InputFile file(s.image, limits::kMaxHeightFieldFileBytes);
    const std::size_t bytes = levels.size() * sizeof(std::uint16_t);
    if (file.size() != bytes || file.read(levels.data(), bytes) != bytes) {
      refuse(s, "changed size while it was read");
    }
  } catch (const InputFileError& e) {
    refuse(s, e.what());
  }
  if constexpr (std::endian::native != std::endian::little) {
    for (std::uint16_t& v : levels) {
      v = static_cast<std::uint16_t>((v >> 8) | (v << 8));
    }
  }
  // Levels map into terrain.heightfield.height, whose range holds every world height.
  return make_height_sketch(s, int(peek.width), int(peek.height), levels, 65535,
                            !s.fractal && s.level_of_detail, s.interpolating);
}

HeightSketch load_image(const HeightFieldSettings& s, const HeightFieldPeek& peek) {
  HeightFieldImage image = read_image(s, false, int(peek.width), int(peek.height));
  if (std::uint64_t(image.width) != peek.width || std::uint64_t(image.height) != peek.height ||
      image.values.size() != std::size_t(image.width) * std::size_t(image.height)) {
    refuse(s, "changed while it was read");
  }
  check_samples(s, image.values, image.width);  // rows top first: row 0 at z0
  return make_height_field(s, image.width, image.height, image.values,
                           !s.fractal && s.level_of_detail, s.interpolating);
}

HeightSketch load_png(const HeightFieldSettings& s) {
  const std::string field = field_text(s);
  const auto check_header = [&](const std::vector<unsigned char>& header) {
    const PngHeader png = png_header_or_throw(header, field, kPath);
    if (png.colour_type != 0) {
      refuse(s, "has colour type " + std::to_string(png.colour_type) +
                    "; allowed: a grey PNG with one channel (colour type 0)");
    }
    if (png.bit_depth != 8 && png.bit_depth != 16) {
      refuse(s, "has " + std::to_string(png.bit_depth) + " bits per channel; allowed: 8 or 16");
    }
    check_side(s, png.width, png.height, "pixels");
  };
  const std::vector<unsigned char> bytes =
      read_png_file(s.image, field, kPath, check_header, limits::kMaxHeightFieldFileBytes);
  const Grey16Image grey = decode_grey16_png(bytes, field, kPath, limits::kMaxHeightFieldFileBytes);
  return make_height_sketch(s, grey.width, grey.height, grey.levels, 65535,
                            !s.fractal && s.level_of_detail, s.interpolating);
}

HeightSketch load_by_format(const HeightFieldSettings& settings, const HeightFieldPeek& peek) {
  switch (peek.format) {
    case HeightFieldFormat::kPng:
      return load_png(settings);
    case HeightFieldFormat::kPfm:
      return load_pfm(settings, peek);
    case HeightFieldFormat::kRaw16:
      return load_raw16(settings, peek);
    case HeightFieldFormat::kImage:
      return load_image(settings, peek);
  }
  return {};
}

}  // namespace

void set_height_field_image_reader(HeightFieldImageReader reader) {
  image_reader = reader;
}

std::optional<HeightFieldPeek> peek_height_field(const HeightFieldSettings& settings) {
  try {
    return peek_or_throw(settings);
  } catch (const SceneError&) {
    return std::nullopt;
  }
}

std::uintmax_t height_field_load_bytes(const HeightFieldPeek& peek) {
  const std::uintmax_t samples = std::uintmax_t(peek.width) * peek.height;
  // PNG: the file, the inflate check's buffer, stb's inflated rows and its 16-bit output, the
  // levels' copy; PFM: the floats read; RAW16: the levels. Then the heights with their levels of
  // detail (4 bytes, times 4/3 and a few rows: under 6) and the block extremes (2 x 4 bytes per
  // 16 samples, times 4/3 for the coarser blocks: under 1).
  // EXR and TIFF: the reader's floats, and OpenImageIO's own buffer as large again.
  const std::uintmax_t decode = peek.format == HeightFieldFormat::kImage ? 8 * samples
                                : peek.format == HeightFieldFormat::kPng
                                    ? peek.file_bytes + 8 * samples
                                : peek.format == HeightFieldFormat::kPfm ? 4 * samples
                                                                         : 2 * samples;
  return decode + (peek.levels_of_detail ? 7 : 5) * samples;
}

HeightSketch load_height_field(const HeightFieldSettings& settings) {
  const HeightFieldPeek peek = peek_or_throw(settings);
  // The placement first: a file that cannot be placed is refused before its samples are read.
  std::optional<std::array<double, 4>> placed;
  if (settings.georeferenced) {
    placed = georeferenced_extent(settings, int(peek.width), int(peek.height));
  }
  HeightSketch field = load_by_format(settings, peek);
  field.placed_extent = placed;
  // Interpolating coefficients overshoot the samples (core/field_prefilter.h); every stored
  // value must stay a height the stages are specified for.
  const double reach = std::max(-double(field.min_height), double(field.max_height));
  if (settings.interpolating && reach > limits::kMaxBaseHeight) {
    refuse(settings, "needs coefficients up to " + format_number(reach) +
                         " in magnitude for terrain.heightfield.interpolating; allowed: within "
                         "+-1e7 (lower the height range, or set interpolating to false)");
  }
  return field;
}

}  // namespace relief
