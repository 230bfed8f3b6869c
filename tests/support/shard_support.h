// relief render whole and in shards, then relief stitch: the test the shard tests and the GL
// shard test share (tests/cli/shard_test.cc, tests/gl/gl_shard_test.cc).
#pragma once

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief::test {

inline std::vector<std::string> size_sets(int width, int height) {
  return {"--set", "viewport.width=" + std::to_string(width),
          "--set", "viewport.height=" + std::to_string(height),
          "--set", "grid.width=96",
          "--set", "grid.height=96"};
}

// relief render SCENE at width x height, whole and in `count` shards, then stitched (the
// shards given in reverse order): the same bytes.
inline void require_stitched_equal(const std::string& scene, int width, int height, int count,
                                   const std::vector<std::string>& extra = {}) {
  INFO(scene << " " << width << "x" << height << " in " << count << " shards");
  TempDir dir("shard");
  const auto args = [&](std::vector<std::string> head) {
    const std::vector<std::string> sizes = size_sets(width, height);
    head.insert(head.end(), sizes.begin(), sizes.end());
    head.insert(head.end(), extra.begin(), extra.end());
    return head;
  };
  const std::string whole = (dir.path() / "whole.png").string();
  REQUIRE(run(args({"render", scene, "-o", whole})).code == 0);
  std::vector<std::string> stitch = {"stitch", "-o", (dir.path() / "stitched.png").string()};
  for (int i = count - 1; i >= 0; --i) {
    const std::string part = (dir.path() / ("part" + std::to_string(i) + ".png")).string();
    const std::string shard = std::to_string(i) + "/" + std::to_string(count);
    const CliResult r = run(args({"render", scene, "--shard", shard, "-o", part}));
    INFO(r.err);
    REQUIRE(r.code == 0);
    stitch.push_back(part);
  }
  const CliResult r = run(stitch);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(read_bytes(dir.path() / "stitched.png") == read_bytes(whole));
}

}  // namespace relief::test
