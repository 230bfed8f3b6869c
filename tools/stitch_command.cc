#include "tools/stitch_command.h"

#include <algorithm>
#include <climits>
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
#include "image/png_layout.h"
#include "image/png_text.h"
#include "pipeline/png_checks.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/distinct_paths.h"
#include "tools/float_image_file.h"
#include "tools/shard.h"
#include "tools/stitch_files.h"

namespace relief {

namespace {

// A shard's PNG whole: its chunks and their CRCs checked (a damaged file is refused, not
// decoded into wrong pixels).
std::vector<unsigned char> read_shard_png(const std::string& file) {
  std::vector<unsigned char> png = read_shard_file(file, "shard");
  const std::string source = "shard " + brief_text(file);
  if (!parse_png_header(png.data(), png.size())) {
    throw ShardError(source + " is not a PNG image");
  }
  if (const PngLayout layout = png_layout(png.data(), png.size(), true); !layout.problem.empty()) {
    throw ShardError(source + ": " + layout.problem);
  }
  return png;
}

ImageShard read_image_shard(const std::string& file) {
  const std::vector<unsigned char> png = read_shard_png(file);
  const std::optional<PngHeader> header = parse_png_header(png.data(), png.size());
  const std::string source = "shard " + brief_text(file);
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

// Every shard of one image once, each holding the rows shard_rows gives it (exit 2 otherwise).
// Each shard has a companion of every kind asked for in `extras` (StitchOptions::extras).
std::vector<ImageShard> complete_image_set(std::vector<ImageShard> shards,
                                           const StitchExtras& extras) {
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
    if (r.backend != r0.backend) {
      differs("backend (" + brief_text(r.backend) + " against " + brief_text(r0.backend) + ")");
    }
    if (r.unit != r0.unit) {
      differs("step of rows (" + std::to_string(r.unit) + " against " + std::to_string(r0.unit) +
              ": shards of relief render and relief reference, or other samples a pixel)");
    }
    if (s.text.size() != first.text.size() ||
        !std::equal(s.text.begin(), s.text.end(), first.text.begin(),
                    [](const ImageText& a, const ImageText& b) {
                      return a.keyword == b.keyword && a.text == b.text;
                    })) {
      differs("scene or software (its PNG text)");
    }
    const ShardSpan rows = shard_rows(r.height, r.shard, r.unit);
    if (r.top != r.height - rows.end || r.rows != rows.end - rows.begin) {
      differs("row band (rows " + std::to_string(r.top) + " + " + std::to_string(r.rows) +
              ", where shard " + shard_name(r.shard) + " holds rows " +
              std::to_string(r.height - rows.end) + " + " + std::to_string(rows.end - rows.begin) +
              ")");
    }
    for (std::size_t k = 0; k < std::size(kShardOutputKinds); ++k) {
      const std::string_view kind = kShardOutputKinds[k].kind;
      if (!extras[k].empty() && !find_companion(r, kind)) {
        throw ShardError("shard " + brief_text(s.file) + " has no " + std::string(kind) +
                         " output to stitch into " + std::string(kShardOutputKinds[k].option) +
                         " " + brief_text(extras[k]) + " (rendered without " +
                         std::string(kShardOutputKinds[k].option) + ")");
      }
    }
    if (const auto [at, added] = by_index.emplace(r.shard.index, &s); !added) {
      throw ShardError("shards " + brief_text(at->second->file) + " and " + brief_text(s.file) +
                       " are both shard " + shard_name(r.shard));
    }
  }
  for (int i = 0; i < r0.shard.count; ++i) {
    if (!by_index.count(i)) {
      const ShardSpan rows = shard_rows(r0.height, {i, r0.shard.count}, r0.unit);
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

// The image's pixels from its shards' PNGs, encoded once with the shards' text.
std::vector<unsigned char> stitch_png(const std::vector<ImageShard>& shards,
                                      const std::string& output) {
  const int width = shards.front().record.width;
  const int height = shards.front().record.height;
  const std::size_t row_bytes = 3 * std::size_t(width);
  std::vector<std::uint8_t> rgb(row_bytes * std::size_t(height));  // bottom row first
  for (const ImageShard& s : shards) {
    const std::vector<unsigned char> png = read_shard_png(s.file);
    const std::string field = "shard " + brief_text(s.file);
    if (png.size() > std::size_t(INT_MAX)) {  // stb takes an int size
      throw ShardError(field + " is larger than " + std::to_string(INT_MAX) + " bytes");
    }
    try {
      check_png_image_data(png, field, "");
    } catch (const SceneError& e) {  // "scene: FIELD ...": the field is the shard here
      const std::string what = e.what();
      throw ShardError(what.starts_with("scene: ") ? what.substr(7) : what);
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
  std::vector<unsigned char> png = encode_png_rgb(width, height, rgb, shards.front().text);
  if (png.empty()) {
    throw OutputError("-o " + output + ": the PNG could not be encoded (out of memory)");
  }
  return png;
}

int stitch_image(const StitchOptions& o, std::ostream& out) {
  if (!has_extension(o.output, ".png")) {
    throw ShardError("-o " + brief_text(o.output) + ": give a file name ending in .png");
  }
  std::vector<CommandPath> paths{{"-o", o.output, true}};
  for (std::size_t k = 0; k < std::size(kShardOutputKinds); ++k) {
    const ShardOutputKind& kind = kShardOutputKinds[k];
    if (!o.extras[k].empty()) {
      if (kind.channels != 0 && !float_format_of(o.extras[k])) {
        throw ShardError(std::string(kind.option) + " " + brief_text(o.extras[k]) +
                         ": give a file name ending in .pfm or .exr");
      }
      if (kind.channels == 0 && !has_extension(o.extras[k], ".bin")) {
        throw ShardError(std::string(kind.option) + " " + brief_text(o.extras[k]) +
                         ": the ids are written raw; give a file name ending in .bin");
      }
      paths.push_back({std::string(kind.option), o.extras[k], true});
    }
  }
  for (const std::string& file : o.inputs) {
    paths.push_back({"SHARD", file, false});
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    throw ShardError(*conflict);
  }
  // Each file is read whole: the largest must fit before the first is read (a shard padded
  // with a large private chunk is input like any other).
  std::uintmax_t largest_file = 0;
  for (const std::string& file : o.inputs) {
    largest_file = std::max(largest_file, shard_file_size(file));
  }
  MemoryEstimate reading;
  reading.add("the largest shard file", largest_file);
  check_memory(reading, o.budget, "reading these shards", "Give the shards of relief render");
  std::vector<ImageShard> shards;
  for (const std::string& file : o.inputs) {
    shards.push_back(read_image_shard(file));
  }
  shards = complete_image_set(std::move(shards), o.extras);
  for (const ImageShard& s : shards) {  // no output may replace a shard's companion
    for (const ShardCompanion& c : s.record.companions) {
      paths.push_back({"shard " + brief_text(s.file) + "'s " + c.kind + " output",
                       companion_path(s, c), false});
    }
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    throw ShardError(*conflict);
  }
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
  estimate.add("one shard's file and pixels", largest_file + row_bytes * std::uintmax_t(tallest));
  for (std::size_t k = 0; k < std::size(kShardOutputKinds); ++k) {
    if (!o.extras[k].empty()) {
      add_extra_memory(estimate, kShardOutputKinds[k], shards);
    }
  }
  check_memory(estimate, o.budget, "stitching this image",
               "Stitch the extra outputs one at a time");

  OutputSet files;  // the image and every extra output, or nothing
  files.add(o.output, stitch_png(shards, o.output));
  std::string also;
  for (std::size_t k = 0; k < std::size(kShardOutputKinds); ++k) {
    if (!o.extras[k].empty()) {
      files.add(o.extras[k], stitch_extra(kShardOutputKinds[k], o.extras[k], shards));
      also += ", " + o.extras[k];
    }
  }
  files.commit();
  out << "stitched " << shards.size() << " shards into " << o.output << also << " (" << width << "x"
      << height << ")\n";
  // Outputs the shards hold that were not asked for: said, so that none is lost unnoticed.
  for (const ShardCompanion& c : shards.front().record.companions) {
    for (std::size_t k = 0; k < std::size(kShardOutputKinds); ++k) {
      if (kShardOutputKinds[k].kind == c.kind && o.extras[k].empty()) {
        out << "  the shards also hold " << c.kind << " outputs; give "
            << kShardOutputKinds[k].option << " FILE to stitch them\n";
      }
    }
  }
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
  for (std::size_t k = 0; k < std::size(kShardOutputKinds); ++k) {
    const ShardOutputKind& kind = kShardOutputKinds[k];
    cmd->add_option(std::string(kind.option), options.extras[k],
                    "With -o: the shards' " + std::string(kind.kind) + " outputs stitched into " +
                        (kind.channels == 0 ? std::string("this file (raw 32-bit ids)")
                                            : std::string("this PFM or EXR file")));
  }
  return cmd;
}

int run_stitch_command(const StitchOptions& o, std::ostream& out, std::ostream&) {
  if (o.output.empty() == o.out_dir.empty()) {
    throw ShardError(
        "give -o IMAGE.png to stitch an image's shards, or --out DIR to stitch a "
        "path's, not both or neither");
  }
  for (std::size_t k = 0; k < std::size(kShardOutputKinds); ++k) {
    if (!o.out_dir.empty() && !o.extras[k].empty()) {
      throw ShardError(std::string(kShardOutputKinds[k].option) +
                       " stitches an image's shards (with -o); a path's shards hold frames alone");
    }
  }
  return o.output.empty() ? stitch_path(o, out) : stitch_image(o, out);
}

}  // namespace relief
