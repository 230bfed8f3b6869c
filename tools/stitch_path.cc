// relief stitch --out DIR SHARD_DIR... (stitch_command.h): a camera path's frames from the
// directories of its shards (relief path --shard), each shard's record checked, every frame
// present, then copied into DIR.
#include <cstdio>
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene/json_input.h"
#include "image/png_header.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/stitch_command.h"
#include "tools/stitch_files.h"

namespace relief {

namespace {

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
      const std::vector<unsigned char> bytes = read_shard_file(entry.path().string(), "record");
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

}  // namespace

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
    const std::vector<unsigned char> png = read_shard_file(sources[k].string(), "frame");
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

}  // namespace relief
