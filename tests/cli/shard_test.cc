// --shard I/N and relief stitch (tools/shard.h, tools/stitch_command.h): the parts are a
// partition of the job, and the stitched image or path is byte for byte the one-process
// render, for every preset, odd sizes and N = 1, 7 and 64; every incomplete, mixed or damaged
// set is refused naming what is wrong, with nothing written.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/scene/scene_json.h"
#include "tests/support/cli_support.h"
#include "tests/support/shard_support.h"
#include "tests/support/test_support.h"
#include "tools/shard.h"

namespace relief {
namespace {

using Catch::Matchers::Contains;
using test::read_bytes;
using test::require_stitched_equal;
using test::run;
using test::size_sets;

TEST_CASE("shardsOfEveryPresetStitchToTheBytesOfOneRender", "[shard]") {
  for (const std::string& preset : preset_names()) {
    require_stitched_equal(preset, 203, 131, 3);  // odd sizes: the top band is 3 rows high
    require_stitched_equal(preset, 203, 131, 1);
  }
}

TEST_CASE("sevenAndSixtyFourShardsStitchToTheBytesOfOneRender", "[shard]") {
  require_stitched_equal("default", 157, 455, 7);  // 8 tile rows in 7 bands
  require_stitched_equal("lava", 80, 4096, 64);    // one tile row each
  require_stitched_equal("default", 157, 455, 7, {"--backend", "reference-double"});
  require_stitched_equal("default", 157, 455, 7, {"--simd", "SCALAR"});
}

TEST_CASE("shardsPartitionTheRowsAndFramesInWholeTiles", "[shard]") {
  for (int height = 1; height <= 700; height += 7) {
    const int tile_rows = (height + 63) / 64;
    for (const int count : {1, 2, 3, 5, 7, 11}) {
      if (count > tile_rows) {
        CHECK_THROWS_AS(shard_rows(height, {0, count}), ShardError);
        continue;
      }
      int next = 0;
      for (int i = 0; i < count; ++i) {
        const ShardSpan rows = shard_rows(height, {i, count});
        CHECK(rows.begin == next);
        CHECK(rows.begin % 64 == 0);
        CHECK(rows.end > rows.begin);
        CHECK((rows.end % 64 == 0 || rows.end == height));
        next = rows.end;
      }
      CHECK(next == height);
    }
  }
  for (int frames = 1; frames <= 40; ++frames) {
    for (int count = 1; count <= frames; ++count) {
      int next = 0;
      for (int i = 0; i < count; ++i) {
        const ShardSpan f = shard_frames(frames, {i, count});
        CHECK(f.begin == next);
        CHECK(f.end > f.begin);
        next = f.end;
      }
      CHECK(next == frames);
    }
    CHECK_THROWS_AS(shard_frames(frames, {0, frames + 1}), ShardError);
  }
}

TEST_CASE("shardIndicesComeFromTheOptionOrFromSlurmOrKubernetes", "[shard]") {
  std::map<std::string, std::string> env;
  const auto environment = [&](const char* name) -> const char* {
    const auto at = env.find(name);
    return at == env.end() ? nullptr : at->second.c_str();
  };
  CHECK(parse_shard("3/7", environment).index == 3);
  CHECK(parse_shard("3/7", environment).count == 7);
  CHECK(parse_shard("0/1", environment).count == 1);
  CHECK(parse_shard("4095/4096", environment).index == 4095);
  for (const char* bad : {"", "3", "/7", "3/", "7/7", "-1/4", "1/0", "1/4097", "01/4", "1/04",
                          "a/b", "1.0/4", "1/4/5", "auto/4", " 1/4", "1/4 ", "99999999999/4"}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_shard(bad, environment), ShardError);
  }
  env["JOB_COMPLETION_INDEX"] = "2";
  CHECK(parse_shard("auto/4", environment).index == 2);
  env["SLURM_ARRAY_TASK_ID"] = "1";  // Slurm first
  CHECK(parse_shard("auto/4", environment).index == 1);
  env["SLURM_ARRAY_TASK_ID"] = "4";
  CHECK_THROWS_WITH(parse_shard("auto/4", environment), Contains("from SLURM_ARRAY_TASK_ID"));
  env["SLURM_ARRAY_TASK_ID"] = "x";
  CHECK_THROWS_AS(parse_shard("auto/4", environment), ShardError);
}

TEST_CASE("incompleteMixedOrDamagedImageShardsAreRefused", "[shard]") {
  test::TempDir dir("shard-refused");
  const auto part = [&](const std::string& name, const std::string& shard, int height,
                        const std::vector<std::string>& extra = {}) {
    std::vector<std::string> a = {"render", "--shard", shard, "-o", (dir.path() / name).string()};
    const std::vector<std::string> sizes = size_sets(120, height);
    a.insert(a.end(), sizes.begin(), sizes.end());
    a.insert(a.end(), extra.begin(), extra.end());
    const test::CliResult r = run(a);
    INFO(r.err);
    REQUIRE(r.code == 0);
    return (dir.path() / name).string();
  };
  const std::string a0 = part("a0.png", "0/3", 200), a1 = part("a1.png", "1/3", 200),
                    a2 = part("a2.png", "2/3", 200);
  const std::string out = (dir.path() / "out.png").string();
  const auto refused = [&](std::vector<std::string> inputs, const std::string& message) {
    std::vector<std::string> a = {"stitch", "-o", out};
    a.insert(a.end(), inputs.begin(), inputs.end());
    test::require_refused(run(a), message, out);
  };
  refused({a0, a2}, "shard 1/3 (image rows 72 to 135) is missing; 2 of 3 given");
  refused({a0, a1, a1, a2}, "are both shard 1/3");
  refused({a0, a1, part("b2.png", "2/3", 200, {"--set", "terrain.seed=2"})},
          "scene or software (its PNG text) differs");
  refused({a0, a1, part("c2.png", "1/3", 250)}, "image size differs");
  refused({a0, a1, part("d2.png", "2/4", 300)}, "shard count (4 against 3) differs");
  refused({a0, a1, a2, (dir.path() / "missing.png").string()}, "missing.png");
  // Not a shard: a whole render, a text file, a truncated shard.
  REQUIRE(run({"render", "-o", (dir.path() / "whole.png").string(), "--set", "viewport.width=120",
               "--set", "viewport.height=200"})
              .code == 0);
  refused({a0, a1, (dir.path() / "whole.png").string()}, "has no relief:shard record");
  refused({a0, a1, test::write_file(dir.path() / "text.png", "not a png")}, "is not a PNG image");
  const std::vector<unsigned char> bytes = read_bytes(a2);
  const std::string cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(bytes.size() * 3 / 4));
  refused({a0, a1, test::write_file(dir.path() / "cut.png", cut)}, "cut.png");
  // The output naming an input, and -o with --out, are refused before anything is read.
  test::require_refused(run({"stitch", "-o", a0, a0, a1, a2}), "SHARD", out);
  test::require_refused(run({"stitch", "-o", out, "--out", dir.path().string(), a0}),
                        "not both or neither", out);
}

TEST_CASE("renderShardOptionsOutsideTheirRangeAreRefused", "[shard]") {
  test::TempDir dir("shard-options");
  const std::string out = (dir.path() / "x.png").string();
  const auto refused = [&](std::vector<std::string> extra, const std::string& message) {
    std::vector<std::string> a = {"render", "-o", out};
    a.insert(a.end(), extra.begin(), extra.end());
    test::require_refused(run(a), message, out);
  };
  refused({"--shard", "0/17", "--set", "viewport.height=1024"},
          "has 16 rows of 64-pixel tiles, so at most 16 shards");
  refused({"--shard", "2/2", "--set", "viewport.height=200"}, "is not a whole number below N");
}

TEST_CASE("pathShardsStitchToTheFramesOfOnePath", "[shard]") {
  test::TempDir dir("shard-path");
  const std::vector<std::string> path = {"path",
                                         "planet",
                                         "--frames",
                                         "5",
                                         "--from-altitude",
                                         "2e5",
                                         "--to-altitude",
                                         "500",
                                         "--set",
                                         "viewport.width=64",
                                         "--set",
                                         "viewport.height=48",
                                         "--set",
                                         "grid.width=48",
                                         "--set",
                                         "grid.height=48"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = path;
    a.insert(a.end(), extra.begin(), extra.end());
    return run(a);
  };
  REQUIRE(with({"--out", (dir.path() / "whole").string()}).code == 0);
  // Shards 0 and 2 share a directory; shard 1 has its own.
  const std::string shared = (dir.path() / "shared").string();
  const std::string own = (dir.path() / "own").string();
  REQUIRE(with({"--out", shared, "--shard", "0/3"}).code == 0);
  REQUIRE(with({"--out", own, "--shard", "1/3"}).code == 0);
  // The same shard again into the same directory is refused (its frames are there).
  test::require_refused(with({"--out", shared, "--shard", "0/3"}), "already holds", "");
  REQUIRE(with({"--out", shared, "--shard", "2/3"}).code == 0);
  const std::string joined = (dir.path() / "joined").string();
  test::require_refused(run({"stitch", "--out", joined, shared}),
                        "shard 1/3 (frames 1 to 2) is missing", joined);
  const test::CliResult r = run({"stitch", "--out", joined, shared, own});
  INFO(r.err);
  REQUIRE(r.code == 0);
  for (int k = 0; k < 5; ++k) {
    const std::string name = "frame_000" + std::to_string(k) + ".png";
    CHECK(read_bytes(std::filesystem::path(joined) / name) ==
          read_bytes(dir.path() / "whole" / name));
  }
  // A frame gone from a shard's directory, or a record of another path, is named.
  std::filesystem::remove(std::filesystem::path(own) / "frame_0002.png");
  test::require_refused(run({"stitch", "--out", joined + "2", shared, own}),
                        "frame 2 of shard 1/3 is missing", joined + "2");
  test::write_file(std::filesystem::path(own) / "relief-shard-1-of-3.json",
                   R"({"command": "path", "index": 1, "count": 3, "frames": 9})");
  test::require_refused(run({"stitch", "--out", joined + "3", shared, own}),
                        "its shard or frame count differs", joined + "3");
  test::require_refused(run({"stitch", "--out", joined + "4", dir.path().string()}),
                        "holds no relief-shard-I-of-N.json record", joined + "4");
  // A record is input: frame and shard counts past relief path's limits are refused before
  // anything is sized by them (2^30 frames would have been gigabytes of file names).
  const std::filesystem::path forged = dir.path() / "forged";
  std::filesystem::create_directories(forged);
  test::write_file(forged / "relief-shard-0-of-1.json",
                   R"({"command": "path", "index": 0, "count": 1, "frames": 1073741824})");
  test::require_refused(run({"stitch", "--out", joined + "5", forged.string()}),
                        "names 1073741824 frames; allowed 1 to 10000", joined + "5");
  test::write_file(forged / "relief-shard-0-of-1.json",
                   R"({"command": "path", "index": 0, "count": 1, "frames": 0})");
  test::require_refused(run({"stitch", "--out", joined + "6", forged.string()}), "names 0 frames",
                        joined + "6");
  std::filesystem::remove(forged / "relief-shard-0-of-1.json");
  test::write_file(forged / "relief-shard-0-of-9.json",
                   R"({"command": "path", "index": 0, "count": 9, "frames": 5})");
  test::require_refused(run({"stitch", "--out", joined + "7", forged.string()}), "names shard 0/9",
                        joined + "7");
}

}  // namespace
}  // namespace relief
