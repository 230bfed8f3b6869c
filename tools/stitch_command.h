// `relief stitch` (docs/shards.md): the parts that `--shard I/N` rendered, assembled.
//   relief stitch -o IMAGE.png SHARD.png...   the image from its row bands (relief render or
//                                              relief reference --shard): bytes identical to
//                                              one render; --float FILE, --depth FILE, ...
//                                              stitch the shards' extra outputs too
//   relief stitch --out DIR SHARD_DIR...      a path's frames from its shards' directories
//                                              (relief path --shard), copied into DIR
// A set that is incomplete (a shard missing: named with its rows or frames), mixed (shards of
// another image, scene, size or N), or damaged (a frame or band missing or unreadable) is
// refused with exit 2 and nothing written.
#pragma once

#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "pipeline/memory_budget.h"
#include "tools/shard.h"

namespace CLI {
class App;
}  // namespace CLI

namespace relief {

// The file for each of kShardOutputKinds (--float, --depth, ...; empty: not stitched).
using StitchExtras = std::array<std::string, std::size(kShardOutputKinds)>;

struct StitchOptions {
  std::vector<std::string> inputs;
  std::string output;   // -o: an image
  StitchExtras extras;  // with -o: the image's extra outputs
  std::string out_dir;  // --out: a path's frames
  MemoryBudget budget;
};

CLI::App* add_stitch_command(CLI::App& app, StitchOptions& options);

// Throws ShardError (bad input), MemoryLimitError, OutputError.
int run_stitch_command(const StitchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace relief
