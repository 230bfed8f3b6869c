// terrain.heightfield's file (core/height_sketch.h samples it): a grey PNG of 8 or 16 bits, a
// one-channel PFM, or RAW16, each refused with the field, the value and what is allowed when it
// is not one (truncated, too large, NaN or infinite samples, heights beyond the scene's range,
// a RAW16 size that is no whole number of rows), before it is decoded whole where the header
// tells.
#pragma once

#include <cstdint>
#include <optional>

#include "core/height_sketch.h"
#include "core/scene/scene.h"

namespace relief {

enum class HeightFieldFormat { kPng, kPfm, kRaw16 };

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
