// terrain.heightfield's file (core/height_sketch.h samples it): a grey PNG of 8 or 16 bits, a
// one-channel PFM, RAW16, or a one-channel float EXR or TIFF (through the image reader the
// command line installs), each refused with the field, the value and what is allowed when it
// is not one (truncated, too large, NaN or infinite samples, heights beyond the scene's range,
// a RAW16 size that is no whole number of rows), before it is decoded whole where the header
// tells.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/height_sketch.h"
#include "core/scene/scene.h"

namespace relief {

enum class HeightFieldFormat { kPng, kPfm, kRaw16, kImage };

// EXR and TIFF fields are read by a reader the command line installs (its OpenImageIO module,
// tools/image_library.h), so that linking the library pulls no image library in. The image:
// width x height x channels floats, top row first; values left empty when only the header is
// asked for. Asked for the pixels, `image` arrives with the width, height and channels the
// header gave: a file whose header now differs is refused before anything is allocated.
// Returns false with `error` set when the file cannot be read as an image.
struct HeightFieldImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> values;
};
using HeightFieldImageReader = bool (*)(const std::string& path, bool header_only,
                                        HeightFieldImage& image, std::string& error);
// Installs the reader (null: none; EXR and TIFF fields are then refused, saying why).
void set_height_field_image_reader(HeightFieldImageReader reader);

// The size of a height field's file and its samples, from the header (RAW16: the file's size),
// for the memory estimate before anything is read whole; nullopt when the file cannot be opened
// or its header is not one the loader takes (loading the scene reports why).
struct HeightFieldPeek {
  HeightFieldFormat format = HeightFieldFormat::kPng;
  std::uintmax_t file_bytes = 0;
  std::uint64_t width = 0, height = 0;
  bool levels_of_detail = false;  // built after loading (no fractal, level_of_detail on)
};
std::optional<HeightFieldPeek> peek_height_field(const HeightFieldSettings& settings);

// The memory loading takes at its peak: the file, its decoding and the float heights with their
// block extremes (HeightSketch::blocks).
std::uintmax_t height_field_load_bytes(const HeightFieldPeek& peek);

// The field's samples as world heights. Throws SceneError naming terrain.heightfield.file (or
// .raw_width) when the file is not one of the formats or breaks their rules.
HeightSketch load_height_field(const HeightFieldSettings& settings);

}  // namespace relief
