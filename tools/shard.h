// --shard I/N (docs/shards.md): which part of a job one process does, so that a long
// camera path or a large image is split across machines and stitched back (relief stitch)
// into bytes identical to one render. Relief's frames are bit-identical across runs and
// thread counts, so any machine may render any part. The parts are a pure function of the
// job's size and N:
//   - a path of F frames: shard I takes frames [floor(I F / N), floor((I + 1) F / N));
//   - an image H rows high: its T = ceil(H / 64) rows of 64 x 64 tiles, shard I taking tile
//     rows [floor(I T / N), floor((I + 1) T / N)) counted from the bottom, the framebuffer's
//     row 0 (whole tiles: a tile row is the rasteriser's unit, render_frame_rows).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace CLI {
class App;
}  // namespace CLI

namespace relief {

inline constexpr int kMaxShards = 4096;
// The most frames relief path renders (path_command.cc), and so the most a path shard names.
inline constexpr int kMaxPathFrames = 10000;

struct Shard {
  int index = 0;
  int count = 1;
};

// A --shard value or a shard's record that cannot be used: bad input (exit 2).
class ShardError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// --shard I/N on `command`, into `text` ("" when not given).
void add_shard_option(CLI::App* command, std::string& text, std::string_view unit);

// "I/N" (0 <= I < N <= kMaxShards) or "auto/N": I from SLURM_ARRAY_TASK_ID (a Slurm job array
// submitted with --array=0-(N-1)), else JOB_COMPLETION_INDEX (a Kubernetes Indexed Job).
// `environment` reads a variable (std::getenv's contract: null when unset). Throws ShardError
// naming --shard, the value and the allowed forms.
Shard parse_shard(std::string_view text,
                  const std::function<const char*(const char*)>& environment);

// [begin, end): frames, or framebuffer rows.
struct ShardSpan {
  int begin = 0;
  int end = 0;
};

// Shard `s`'s frames of a path of `frames`. Throws ShardError when N > frames (a shard would
// have none).
ShardSpan shard_frames(int frames, const Shard& s);

// Shard `s`'s framebuffer rows (bottom to top) of an image `height` rows high. Throws
// ShardError when N exceeds its tile rows.
ShardSpan shard_rows(int height, const Shard& s);

// The text chunk an image shard carries beside the scene (image_metadata.h), and what it says:
// {"index": I, "count": N, "width": W, "height": H, "top": Y, "rows": R}, the shard holding the
// PNG rows [Y, Y + R) of the W x H image (top to bottom).
inline constexpr std::string_view kShardKey = "relief:shard";
struct ImageShardRecord {
  Shard shard;
  int width = 0, height = 0;
  int top = 0, rows = 0;
};
std::string shard_record_text(const ImageShardRecord& record);
// Throws ShardError (naming `source`) for text that is not such a record.
ImageShardRecord parse_shard_record(std::string_view text, const std::string& source);

// The record a path shard leaves beside its frames, "relief-shard-I-of-N.json":
// {"command": "path", "index": I, "count": N, "frames": F}.
std::string path_shard_file_name(const Shard& s);
std::string path_shard_record_text(const Shard& s, int frames);

}  // namespace relief
