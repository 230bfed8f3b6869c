#include "tools/shard.h"

#include <charconv>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/json_input.h"
#include "raster/raster_types.h"

namespace relief {

namespace {

// A whole decimal number without sign or leading zeros, or nullopt.
std::optional<long long> whole_number(std::string_view text) {
  if (text.empty() || text.size() > 9 || (text.size() > 1 && text[0] == '0') ||
      text.find_first_not_of("0123456789") != std::string_view::npos) {
    return std::nullopt;
  }
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

}  // namespace

void add_shard_option(CLI::App* command, std::string& text, std::string_view unit) {
  command->add_option("--shard", text,
                      "Render shard I of N (0 <= I < N <= " + std::to_string(kMaxShards) +
                          ") of the " + std::string(unit) +
                          ", for relief stitch; auto/N takes I from SLURM_ARRAY_TASK_ID or "
                          "JOB_COMPLETION_INDEX");
}

Shard parse_shard(std::string_view text,
                  const std::function<const char*(const char*)>& environment) {
  const std::string allowed =
      "allowed I/N with 0 <= I < N <= " + std::to_string(kMaxShards) + ", or auto/N";
  const std::size_t slash = text.find('/');
  const auto refuse = [&](const std::string& why) -> Shard {
    throw ShardError("--shard " + brief_text(text) + ": " + why + "; " + allowed);
  };
  if (slash == std::string_view::npos) {
    return refuse("not of the form I/N");
  }
  const std::optional<long long> count = whole_number(text.substr(slash + 1));
  if (!count || *count < 1 || *count > kMaxShards) {
    return refuse("N is not a whole number from 1 to " + std::to_string(kMaxShards));
  }
  std::string_view index_text = text.substr(0, slash);
  std::string source;
  if (index_text == "auto") {
    for (const char* name : {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"}) {
      if (const char* value = environment(name)) {
        index_text = value;
        source = std::string(" (from ") + name + ")";
        break;
      }
    }
    if (source.empty()) {
      return refuse("neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set");
    }
  }
  const std::optional<long long> index = whole_number(index_text);
  if (!index || *index >= *count) {
    return refuse("I = " + brief_text(index_text) + source + " is not a whole number below N");
  }
  return Shard{static_cast<int>(*index), static_cast<int>(*count)};
}

ShardSpan shard_frames(int frames, const Shard& s) {
  if (s.count > frames) {
    throw ShardError("--shard " + std::to_string(s.index) + "/" + std::to_string(s.count) +
                     ": a path of " + std::to_string(frames) + " frames has at most " +
                     std::to_string(frames) + " shards");
  }
  const auto at = [&](long long i) { return static_cast<int>(i * frames / s.count); };
  return {at(s.index), at(s.index + 1)};
}

ShardSpan shard_rows(int height, const Shard& s) {
  const int tile = raster::kTileSize;
  const int tile_rows = (height + tile - 1) / tile;
  if (s.count > tile_rows) {
    throw ShardError("--shard " + std::to_string(s.index) + "/" + std::to_string(s.count) +
                     ": an image " + std::to_string(height) + " rows high has " +
                     std::to_string(tile_rows) + " rows of " + std::to_string(tile) + "-pixel " +
                     "tiles, so at most " + std::to_string(tile_rows) + " shards");
  }
  const auto at = [&](long long i) {
    return std::min(height, static_cast<int>(i * tile_rows / s.count) * tile);
  };
  return {at(s.index), at(s.index + 1)};
}

std::string shard_record_text(const ImageShardRecord& r) {
  const nlohmann::ordered_json record = {{"index", r.shard.index}, {"count", r.shard.count},
                                         {"width", r.width},       {"height", r.height},
                                         {"top", r.top},           {"rows", r.rows}};
  return record.dump();
}

ImageShardRecord parse_shard_record(std::string_view text, const std::string& source) {
  const auto refuse = [&](const std::string& why) -> ImageShardRecord {
    throw ShardError(source + ": its " + std::string(kShardKey) + " record " + why);
  };
  const nlohmann::json record = nlohmann::json::parse(text, nullptr, false);
  const char* keys[] = {"index", "count", "width", "height", "top", "rows"};
  int values[6] = {};
  if (!record.is_object() || record.size() != 6) {
    return refuse("is not an object of " + std::to_string(std::size(keys)) + " numbers");
  }
  for (std::size_t k = 0; k < std::size(keys); ++k) {
    if (!record.contains(keys[k]) || !record[keys[k]].is_number_integer() ||
        record[keys[k]].get<long long>() < 0 || record[keys[k]].get<long long>() > 1 << 30) {
      return refuse(std::string("has no whole number \"") + keys[k] + "\"");
    }
    values[k] = record[keys[k]].get<int>();
  }
  ImageShardRecord r{{values[0], values[1]}, values[2], values[3], values[4], values[5]};
  if (r.shard.count < 1 || r.shard.count > kMaxShards || r.shard.index >= r.shard.count) {
    return refuse("names shard " + std::to_string(r.shard.index) + " of " +
                  std::to_string(r.shard.count));
  }
  return r;
}

std::string path_shard_file_name(const Shard& s) {
  return "relief-shard-" + std::to_string(s.index) + "-of-" + std::to_string(s.count) + ".json";
}

std::string path_shard_record_text(const Shard& s, int frames) {
  const nlohmann::ordered_json record = {
      {"command", "path"}, {"index", s.index}, {"count", s.count}, {"frames", frames}};
  return record.dump() + "\n";
}

}  // namespace relief
