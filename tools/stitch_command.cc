#include "tools/stitch_command.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include <stb_image.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/input_file.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/png_header.h"
#include "image/png_text.h"
#include "pipeline/png_checks.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/distinct_paths.h"
#include "tools/shard.h"

namespace relief {

namespace {

// A shard's PNG is its rows' pixels, deflated: far below this.
constexpr std::uintmax_t kMaxShardFileBytes = std::uintmax_t(1) << 31;

std::vector<unsigned char> read_whole(const std::string& file, const std::string& what) {
  try {
    InputFile in(file, kMaxShardFileBytes);
    const std::string bytes = in.read_rest();
    return {bytes.begin(), bytes.end()};
  } catch (const InputFileError& e) {
    throw ShardError(what + " " + brief_text(file) + ": " + e.what());
  }
}

struct ImageShard {
  std::string file;
  ImageShardRecord record;
  std::vector<ImageText> text;  // every text chunk but the shard record, in file order
};

ImageShard read_image_shard(const std::string& file) {
  const std::vector<unsigned char> png = read_whole(file, "shard");
  const std::optional<PngHeader> header = parse_png_header(png.data(), png.size());
  const std::string source = "shard " + brief_text(file);
  if (!header) {
    throw ShardError(source + " is not a PNG image");
  }
  ImageShard shard{file, {}, {}};
  std::optional<ImageShardRecord> record;
  for (ImageText& entry : read_png_text(png)) {
    if (entry.keyword == kShardKey) {
      record = parse_shard_record(entry.text, source);
    } else {
      shard.text.push_back(std::move(entry));
    }
  }
  if (!record) {
    throw ShardError(source + " has no " + std::string(kShardKey) +
                     " record: it is not a shard of relief render --shard");
  }
  shard.record = *record;
  if (header->colour_type != 2 || header->bit_depth != 8 || header->interlace != 0 ||
      int(header->width) != record->width || int(header->height) != record->rows) {
    throw ShardError(
        source + " is " + std::to_string(header->width) + "x" + std::to_string(header->height) +
        " (colour type " + std::to_string(header->colour_type) + ", " +
        std::to_string(header->bit_depth) + " bits), but its record says " +
        std::to_string(record->width) + "x" + std::to_string(record->rows) + " RGB, 8 bits");
  }
  return shard;
}

std::string shard_name(const Shard& s) {
  return std::to_string(s.index) + "/" + std::to_string(s.count);
}

// Every shard of one image once, each holding the rows shard_rows gives it (exit 2 otherwise).
std::vector<ImageShard> complete_image_set(std::vector<ImageShard> shards) {
  const ImageShard& first = shards.front();
  const ImageShardRecord& r0 = first.record;
  std::map<int, const ImageShard*> by_index;
  for (const ImageShard& s : shards) {
    const ImageShardRecord& r = s.record;
    const auto differs = [&](const std::string& what) {
      throw ShardError("shard " + brief_text(s.file) + " is not of the image of " +
                       brief_text(first.file) + ": its " + what + " differs");
    };
    if (r.shard.count != r0.shard.count) {
      differs("shard count (" + std::to_string(r.shard.count) + " against " +
              std::to_string(r0.shard.count) + ")");
    }
    if (r.width != r0.width || r.height != r0.height) {
      differs("image size");
    }
    if (s.text.size() != first.text.size() ||
        !std::equal(s.text.begin(), s.text.end(), first.text.begin(),
                    [](const ImageText& a, const ImageText& b) {
                      return a.keyword == b.keyword && a.text == b.text;
                    })) {
      differs("scene or software (its PNG text)");
    }
    const ShardSpan rows = shard_rows(r.height, r.shard);
    if (r.top != r.height - rows.end || r.rows != rows.end - rows.begin) {
      differs("row band (rows " + std::to_string(r.top) + " + " + std::to_string(r.rows) +
              ", where shard " + shard_name(r.shard) + " holds rows " +
              std::to_string(r.height - rows.end) + " + " + std::to_string(rows.end - rows.begin) +
              ")");
    }
    if (const auto [at, added] = by_index.emplace(r.shard.index, &s); !added) {
      throw ShardError("shards " + brief_text(at->second->file) + " and " + brief_text(s.file) +
                       " are both shard " + shard_name(r.shard));
    }
  }
  for (int i = 0; i < r0.shard.count; ++i) {
    if (!by_index.count(i)) {
      const ShardSpan rows = shard_rows(r0.height, {i, r0.shard.count});
      throw ShardError("shard " + shard_name({i, r0.shard.count}) + " (image rows " +
                       std::to_string(r0.height - rows.end) + " to " +
                       std::to_string(r0.height - rows.begin - 1) + ") is missing; " +
                       std::to_string(by_index.size()) + " of " + std::to_string(r0.shard.count) +
                       " given");
    }
  }
  std::sort(shards.begin(), shards.end(), [](const ImageShard& a, const ImageShard& b) {
    return a.record.shard.index < b.record.shard.index;
  });
  return shards;
}

int stitch_image(const StitchOptions& o, std::ostream& out) {
  if (!has_extension(o.output, ".png")) {
    throw ShardError("-o " + brief_text(o.output) + ": give a file name ending in .png");
  }
  std::vector<CommandPath> paths{{"-o", o.output, true}};
  for (const std::string& file : o.inputs) {
    paths.push_back({"SHARD", file, false});
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    throw ShardError(*conflict);
  }
  std::vector<ImageShard> shards;
  for (const std::string& file : o.inputs) {
    shards.push_back(read_image_shard(file));
  }
  shards = complete_image_set(std::move(shards));
  const int width = shards.front().record.width;
  const int height = shards.front().record.height;
  const std::uintmax_t row_bytes = 3 * std::uintmax_t(width);
  int tallest = 0;
  for (const ImageShard& s : shards) {
    tallest = std::max(tallest, s.record.rows);
  }
  MemoryEstimate estimate;
  estimate.add("image", row_bytes * std::uintmax_t(height));
  estimate.add("its PNG encoding (filtered rows and deflate's bound)",
               2 * (row_bytes + 1) * std::uintmax_t(height));
  estimate.add("one shard's file and pixels", 2 * row_bytes * std::uintmax_t(tallest));
  check_memory(estimate, o.budget, "stitching this image", "Give --max-memory more");

  std::vector<std::uint8_t> rgb(row_bytes * std::size_t(height));  // bottom row first
  for (const ImageShard& s : shards) {
    const std::vector<unsigned char> png = read_whole(s.file, "shard");
    const std::string field = "shard " + brief_text(s.file);
    try {
      check_png_image_data(png, field, "");
    } catch (const SceneError& e) {
      throw ShardError(e.what());
    }
    int w = 0, h = 0, channels = 0;
    reset_stb_failure_reason();
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3),
        stbi_image_free);
    if (!pixels || w != width || h != s.record.rows) {
      throw ShardError(field + " could not be decoded: " + stb_failure_reason_or("wrong size"));
    }
    for (int y = 0; y < h; ++y) {  // PNG row top + y is framebuffer row height - 1 - (top + y)
      std::memcpy(rgb.data() + row_bytes * std::size_t(height - 1 - (s.record.top + y)),
                  pixels.get() + row_bytes * std::size_t(y), row_bytes);
    }
  }
  const std::vector<unsigned char> png = encode_png_rgb(width, height, rgb, shards.front().text);
  if (png.empty()) {
    throw OutputError("-o " + o.output + ": the PNG could not be encoded (out of memory)");
  }
  write_file_atomically(o.output, png);
  out << "stitched " << shards.size() << " shards into " << o.output << " (" << width << "x"
      << height << ")\n";
  return kExitOk;
}

struct PathShard {
  std::filesystem::path dir;
  Shard shard;
  int frames = 0;
};

std::vector<PathShard> read_path_records(const std::vector<std::string>& dirs) {
  std::vector<PathShard> shards;
  for (const std::string& dir : dirs) {
    std::error_code error;
    if (!std::filesystem::is_directory(dir, error)) {
      throw ShardError("shard directory " + brief_text(dir) + " is not a directory");
    }
    bool any = false;
    for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
      const std::string name = entry.path().filename().string();
      if (!name.starts_with("relief-shard-") || !name.ends_with(".json")) {
        continue;
      }
      const std::vector<unsigned char> bytes = read_whole(entry.path().string(), "record");
      const nlohmann::json r = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
      const auto whole = [&](const char* key) {
        return r.is_object() && r.contains(key) && r[key].is_number_integer() &&
               r[key].get<long long>() >= 0 && r[key].get<long long>() <= 1 << 30;
      };
      if (!whole("index") || !whole("count") || !whole("frames") || !r.contains("command") ||
          r["command"] != "path") {
        throw ShardError("record " + brief_text(entry.path().string()) +
                         " is not a path shard's record of relief path --shard");
      }
      const PathShard s{dir, {r["index"].get<int>(), r["count"].get<int>()}, r["frames"]};
      // Bounded before anything is sized by them: a record is input like any other.
      if (s.frames < 1 || s.frames > kMaxPathFrames) {
        throw ShardError("record " + brief_text(entry.path().string()) + " names " +
                         std::to_string(s.frames) + " frames; allowed 1 to " +
                         std::to_string(kMaxPathFrames));
      }
      if (s.shard.count < 1 || s.shard.count > std::min(kMaxShards, s.frames) ||
          s.shard.index >= s.shard.count || name != path_shard_file_name(s.shard)) {
        throw ShardError("record " + brief_text(entry.path().string()) + " names shard " +
                         shard_name(s.shard));
      }
      shards.push_back(s);
      any = true;
    }
    if (!any) {
      throw ShardError("shard directory " + brief_text(dir) +
                       " holds no relief-shard-I-of-N.json record of relief path --shard");
    }
  }
  return shards;
}

int stitch_path(const StitchOptions& o, std::ostream& out) {
  std::vector<PathShard> shards = read_path_records(o.inputs);
  const PathShard& first = shards.front();
  std::map<int, const PathShard*> by_index;
  for (const PathShard& s : shards) {
    if (s.shard.count != first.shard.count || s.frames != first.frames) {
      throw ShardError("shard " + shard_name(s.shard) + " in " + brief_text(s.dir.string()) +
                       " is not of the path of shard " + shard_name(first.shard) + " in " +
                       brief_text(first.dir.string()) + " (its shard or frame count differs)");
    }
    if (const auto [at, added] = by_index.emplace(s.shard.index, &s); !added) {
      throw ShardError("shard " + shard_name(s.shard) + " is in both " +
                       brief_text(at->second->dir.string()) + " and " + brief_text(s.dir.string()));
    }
  }
  for (int i = 0; i < first.shard.count; ++i) {
    if (!by_index.count(i)) {
      const ShardSpan f = shard_frames(first.frames, {i, first.shard.count});
      throw ShardError("shard " + shard_name({i, first.shard.count}) + " (frames " +
                       std::to_string(f.begin) + " to " + std::to_string(f.end - 1) +
                       ") is missing: no record relief-shard-" + std::to_string(i) + "-of-" +
                       std::to_string(first.shard.count) + ".json in the directories given");
    }
  }
  // Every frame of every shard, checked before one is copied.
  std::vector<std::filesystem::path> sources(std::size_t(first.frames));
  for (const auto& [index, s] : by_index) {
    const ShardSpan f = shard_frames(first.frames, s->shard);
    for (int k = f.begin; k < f.end; ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04d.png", k);
      sources[std::size_t(k)] = s->dir / name;
      std::error_code error;
      if (!std::filesystem::is_regular_file(sources[std::size_t(k)], error)) {
        throw ShardError("frame " + std::to_string(k) + " of shard " + shard_name(s->shard) +
                         " is missing: no " + brief_text(sources[std::size_t(k)].string()));
      }
    }
  }
  std::error_code error;
  if (std::filesystem::is_directory(o.out_dir, error)) {
    for (const auto& entry : std::filesystem::directory_iterator(o.out_dir, error)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("frame_") && name.ends_with(".png")) {
        throw ShardError("--out " + brief_text(o.out_dir) + " already holds " + name +
                         "; allowed: a new directory, or one without frame_*.png");
      }
    }
  }
  OutputDirectory directory(o.out_dir);
  for (std::size_t k = 0; k < sources.size(); ++k) {
    const std::vector<unsigned char> png = read_whole(sources[k].string(), "frame");
    if (!parse_png_header(png.data(), png.size())) {
      throw ShardError("frame " + brief_text(sources[k].string()) + " is not a PNG image");
    }
    write_file_atomically(std::filesystem::path(o.out_dir) / sources[k].filename(), png);
    directory.keep();
  }
  out << "stitched " << first.shard.count << " shards into " << o.out_dir << " (" << first.frames
      << " frames)\n";
  return kExitOk;
}

}  // namespace

CLI::App* add_stitch_command(CLI::App& app, StitchOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "stitch",
      "Assemble what --shard I/N rendered: -o IMAGE.png from the shards of relief render (the "
      "bytes of one render), or --out DIR from the directories of relief path's shards");
  cmd->add_option("SHARD", options.inputs,
                  "The shards: PNG files of relief render --shard, or directories of relief "
                  "path --shard")
      ->required();
  cmd->add_option("-o,--output", options.output, "The image to write (from image shards)");
  cmd->add_option("--out", options.out_dir, "The directory to write the frames to (path shards)");
  return cmd;
}

int run_stitch_command(const StitchOptions& o, std::ostream& out, std::ostream&) {
  if (o.output.empty() == o.out_dir.empty()) {
    throw ShardError(
        "give -o IMAGE.png to stitch an image's shards, or --out DIR to stitch a "
        "path's, not both or neither");
  }
  return o.output.empty() ? stitch_path(o, out) : stitch_image(o, out);
}

}  // namespace relief
