#include "tools/shard.h"

#include <charconv>
#include <filesystem>
#include <functional>
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
  command
      ->add_option("--shard", text,
                   "Render shard I of N (0 <= I < N <= " + std::to_string(kMaxShards) +
                       ") of the " + std::string(unit) +
                       ", for relief stitch; auto/N takes I from SLURM_ARRAY_TASK_ID or "
                       "JOB_COMPLETION_INDEX")
      // Given empty (a job script's unset variable) it would render the whole image in
      // every task: refused like any other bad value.
      ->check(CLI::Validator(
          [](const std::string& value) {
            return value.empty() ? std::string("is empty; allowed I/N or auto/N") : "";
          },
          "I/N"));
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

ShardSpan shard_rows(int height, const Shard& s, int unit) {
  if (unit < 1 || unit > kImageShardUnit) {
    throw ShardError("a shard's step of " + std::to_string(unit) + " rows is out of range 1 to " +
                     std::to_string(kImageShardUnit));
  }
  const int steps = (height + unit - 1) / unit;
  if (s.count > steps) {
    throw ShardError("--shard " + std::to_string(s.index) + "/" + std::to_string(s.count) +
                     ": an image " + std::to_string(height) + " rows high has " +
                     std::to_string(steps) +
                     (unit == kImageShardUnit ? std::string(" rows of 64-pixel tiles")
                                              : " bands of " + std::to_string(unit) + " rows") +
                     ", so at most " + std::to_string(steps) + " shards");
  }
  const auto at = [&](long long i) {
    return std::min(height, static_cast<int>(i * steps / s.count) * unit);
  };
  return {at(s.index), at(s.index + 1)};
}

std::string shard_record_text(const ImageShardRecord& r) {
  nlohmann::ordered_json outputs = nlohmann::ordered_json::object();
  for (const ShardCompanion& c : r.companions) {
    outputs[c.kind] = {{"file", c.file}, {"bytes", c.bytes}, {"crc32", c.crc}};
  }
  const nlohmann::ordered_json record = {
      {"index", r.shard.index}, {"count", r.shard.count}, {"backend", r.backend},
      {"width", r.width},       {"height", r.height},     {"top", r.top},
      {"rows", r.rows},         {"unit", r.unit},         {"outputs", outputs}};
  return record.dump();
}

namespace {

// The "outputs" object of a record: known kinds, each once, each a file name, a size and a CRC.
std::vector<ShardCompanion> parse_companions(
    const nlohmann::json& outputs, const std::function<void(const std::string&)>& refuse) {
  if (!outputs.is_object()) {
    refuse("has no object \"outputs\"");
  }
  std::vector<ShardCompanion> companions;
  for (const ShardOutputKind& kind : kShardOutputKinds) {
    const std::string key(kind.kind);
    if (!outputs.contains(key)) {
      continue;
    }
    const nlohmann::json& entry = outputs[key];
    const auto whole = [&](const char* name, std::uint64_t max) {
      return entry.contains(name) && entry[name].is_number_unsigned() &&
             entry[name].get<std::uint64_t>() <= max;
    };
    if (!entry.is_object() || entry.size() != 3 || !entry.contains("file") ||
        !entry["file"].is_string() || entry["file"].get<std::string>().empty() ||
        !whole("bytes", std::uint64_t(1) << 62) || !whole("crc32", 0xFFFFFFFFu)) {
      refuse("has an output \"" + key + "\" that is not {\"file\", \"bytes\", \"crc32\"}");
    }
    companions.push_back({key, entry["file"].get<std::string>(),
                          entry["bytes"].get<std::uint64_t>(),
                          entry["crc32"].get<std::uint32_t>()});
  }
  if (companions.size() != outputs.size()) {
    refuse("names an output other than float, depth, normal, height, octaves and primitive");
  }
  return companions;
}

}  // namespace

ImageShardRecord parse_shard_record(std::string_view text, const std::string& source) {
  const auto refuse = [&](const std::string& why) {
    throw ShardError(source + ": its " + std::string(kShardKey) + " record " + why);
  };
  const nlohmann::json record = nlohmann::json::parse(text, nullptr, false);
  const char* keys[] = {"index", "count", "width", "height", "top", "rows", "unit"};
  int values[std::size(keys)] = {};
  if (!record.is_object() || record.size() != std::size(keys) + 2) {
    refuse("is not an object of " + std::to_string(std::size(keys)) +
           " numbers, the backend and the outputs");
  }
  // A backend's name (frame.h): a short word; which one, the set's agreement decides.
  if (!record.contains("backend") || !record["backend"].is_string() ||
      record["backend"].get<std::string>().empty() ||
      record["backend"].get<std::string>().size() > 32) {
    refuse("has no backend name");
  }
  for (std::size_t k = 0; k < std::size(keys); ++k) {
    if (!record.contains(keys[k]) || !record[keys[k]].is_number_integer() ||
        record[keys[k]].get<long long>() < 0 || record[keys[k]].get<long long>() > 1 << 30) {
      refuse(std::string("has no whole number \"") + keys[k] + "\"");
    }
    values[k] = record[keys[k]].get<int>();
  }
  ImageShardRecord r{{values[0], values[1]},
                     record["backend"].get<std::string>(),
                     values[2],
                     values[3],
                     values[4],
                     values[5],
                     values[6],
                     {}};
  if (r.shard.count < 1 || r.shard.count > kMaxShards || r.shard.index >= r.shard.count) {
    refuse("names shard " + std::to_string(r.shard.index) + " of " + std::to_string(r.shard.count));
  }
  if (r.unit < 1 || r.unit > kImageShardUnit) {
    refuse("has a step of " + std::to_string(r.unit) + " rows; allowed 1 to " +
           std::to_string(kImageShardUnit));
  }
  r.companions =
      parse_companions(record.contains("outputs") ? record["outputs"] : nlohmann::json(), refuse);
  return r;
}

const ShardCompanion* find_companion(const ImageShardRecord& record, std::string_view kind) {
  for (const ShardCompanion& c : record.companions) {
    if (c.kind == kind) {
      return &c;
    }
  }
  return nullptr;
}

std::string companion_file_name(const std::string& png, const std::string& file) {
  namespace fs = std::filesystem;
  // Resolved directories (links followed, as the kernel will when the name is opened from the
  // PNG's directory): a lexical "../x" from a linked directory would lead elsewhere.
  std::error_code error;
  const fs::path base =
      fs::weakly_canonical(fs::absolute(fs::path(png), error), error).parent_path();
  const fs::path target = fs::weakly_canonical(fs::absolute(fs::path(file), error), error);
  if (error) {
    return fs::absolute(fs::path(file), error).lexically_normal().string();
  }
  const fs::path relative = target.lexically_relative(base);
  return relative.empty() ? target.string() : relative.string();
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
