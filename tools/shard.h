// --shard I/N (docs/shards.md): which part of a job one process does, so that a long
// camera path or a large image is split across machines and stitched back (relief stitch)
// into bytes identical to one render. Relief's frames are bit-identical across runs and
// thread counts, so any machine may render any part. The parts are a pure function of the
// job's size and N:
//   - a path of F frames: shard I takes frames [floor(I F / N), floor((I + 1) F / N));
//   - an image H rows high: its T = ceil(H / U) steps of U rows, shard I taking steps
//     [floor(I T / N), floor((I + 1) T / N)) counted from the bottom, the framebuffer's row 0.
//     relief render: U = 64, a row of 64 x 64 tiles (the rasteriser's unit, render_frame_rows);
//     relief reference with S x S samples a pixel: U = lcm(64, S) / S, whole tiles of the
//     supersampled frame and whole output pixels (ground_truth_shard_unit).
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

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

// Shard `s`'s framebuffer rows (bottom to top) of an image `height` rows high, in steps of
// `unit` rows (1 to 64). Throws ShardError when N exceeds its steps.
inline constexpr int kImageShardUnit = 64;  // relief render: a row of tiles
ShardSpan shard_rows(int height, const Shard& s, int unit = kImageShardUnit);

// The extra outputs an image shard may carry beside its PNG: each option of relief render's
// (relief reference writes "float"), the file's channels (1 or 3 floats, PFM or EXR by its
// name; 0: the raw 32-bit primitive ids of --primitive, bottom row first).
struct ShardOutputKind {
  std::string_view kind;    // in the record
  std::string_view option;  // of relief render and relief stitch
  int channels = 0;
};
inline constexpr ShardOutputKind kShardOutputKinds[] = {
    {"float", "--float", 3},   {"depth", "--depth", 1},     {"normal", "--normal", 3},
    {"height", "--height", 1}, {"octaves", "--octaves", 1}, {"primitive", "--primitive", 0}};

// One such output of a shard: its file (relative to the PNG's directory, or absolute where no
// relative path leads there), its size and its CRC-32, so that relief stitch takes only the
// file this shard wrote.
struct ShardCompanion {
  std::string kind;
  std::string file;
  std::uint64_t bytes = 0;
  std::uint32_t crc = 0;
};

// The text chunk an image shard carries beside the scene (image_metadata.h), and what it says:
// {"index": I, "count": N, "backend": B, "width": W, "height": H, "top": Y, "rows": R,
//  "unit": U, "outputs": {KIND: {"file": F, "bytes": B, "crc32": C}, ...}}: the shard holds the
// PNG rows [Y, Y + R) of the W x H image (top to bottom), rendered by backend B, its bands cut
// in steps of U rows, and the same rows of each extra output.
inline constexpr std::string_view kShardKey = "relief:shard";
struct ImageShardRecord {
  Shard shard;
  std::string backend;  // who rendered it (frame.h, backend_name): shards of one image agree
  int width = 0, height = 0;
  int top = 0, rows = 0;
  int unit = kImageShardUnit;
  std::vector<ShardCompanion> companions;  // in kShardOutputKinds's order
};
std::string shard_record_text(const ImageShardRecord& record);
// Throws ShardError (naming `source`) for text that is not such a record.
ImageShardRecord parse_shard_record(std::string_view text, const std::string& source);

// The companion of `kind` in `record`, or null.
const ShardCompanion* find_companion(const ImageShardRecord& record, std::string_view kind);

// `file` as a shard's record names it: relative to the directory of `png` where it can be.
std::string companion_file_name(const std::string& png, const std::string& file);

// The record a path shard leaves beside its frames, "relief-shard-I-of-N.json":
// {"command": "path", "index": I, "count": N, "frames": F}.
std::string path_shard_file_name(const Shard& s);
std::string path_shard_record_text(const Shard& s, int frames);

}  // namespace relief
