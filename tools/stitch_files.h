// The files of a set of shards as relief stitch reads them (stitch_command.h): whole, bounded,
// and refused as bad input (ShardError) when they cannot be read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "image/png_text.h"
#include "pipeline/memory_budget.h"
#include "tools/shard.h"

namespace relief {

struct StitchOptions;

// A shard's file is its rows' pixels, deflated, or a band's floats: far below this.
inline constexpr std::uintmax_t kMaxShardFileBytes = std::uintmax_t(1) << 32;

// The whole of `file`; ShardError naming `what` and the file when it cannot be read or is
// larger than kMaxShardFileBytes.
std::vector<unsigned char> read_shard_file(const std::string& file, const std::string& what);

// The size of `file`, or 0 where it cannot be told (read_shard_file then says why).
std::uintmax_t shard_file_size(const std::filesystem::path& file);

// "I/N".
std::string shard_name(const Shard& s);

// An image shard's PNG as read: its record and its other text chunks, in file order.
struct ImageShard {
  std::string file;
  ImageShardRecord record;
  std::vector<ImageText> text;
};

// Where a shard's companion lies: its record's name, relative to the PNG's directory.
std::filesystem::path companion_path(const ImageShard& shard, const ShardCompanion& companion);

// The memory stitch_extra needs for `kind` of the image of `shards`, after checking that each
// shard's companion of that kind has the size its record gives (ShardError otherwise, before
// any is read).
void add_extra_memory(MemoryEstimate& estimate, const ShardOutputKind& kind,
                      const std::vector<ImageShard>& shards);

// The stitched file of `kind` (stitch_extras.cc): each shard's companion of that kind (which
// each has: complete_image_set checked) read, its size and CRC checked against the record, its
// rows put in place, encoded in the format `output`'s name asks for (PFM or EXR; raw ids for
// primitive) with the shards' text.
std::vector<unsigned char> stitch_extra(const ShardOutputKind& kind, const std::string& output,
                                        const std::vector<ImageShard>& shards);

// relief stitch --out DIR SHARD_DIR...: a path's frames (stitch_path.cc).
int stitch_path(const StitchOptions& options, std::ostream& out);

}  // namespace relief
