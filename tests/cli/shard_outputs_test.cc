// The extra outputs of image shards and the shards of relief reference (tools/shard.h,
// tools/stitch_files.h): each stitched file is byte for byte the one a single process writes
// (float, depth, normal, height and octave files in PFM and EXR, primitive ids, and the ground
// truth's PNG and float file for several sample counts and N), and a companion that is not the
// file its shard wrote, or one asked for that a shard lacks, is refused with nothing written.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "eval/ground_truth.h"
#include "image/crc32.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tools/shard.h"

namespace relief {
namespace {

using test::read_bytes;
using test::run;

// The parts joined (GCC 12's -Wrestrict misreads "literal" + std::string).
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (const std::string_view part : parts) {
    out.append(part);
  }
  return out;
}

std::vector<std::string> with_size(std::vector<std::string> head, int width, int height) {
  for (const std::string& set : {cat({"viewport.width=", std::to_string(width)}),
                                 cat({"viewport.height=", std::to_string(height)}),
                                 std::string("grid.width=64"), std::string("grid.height=64")}) {
    head.insert(head.end(), {"--set", set});
  }
  return head;
}

using test::require_ok;

// Every extra output of relief render, in the format `ext` gives the float files, sharded in
// `count` and stitched (shards given in reverse order) into `stitched_ext`.
void require_extras_stitched_equal(const std::string& scene, int count, const std::string& ext,
                                   const std::string& stitched_ext) {
  INFO(scene << " in " << count << " shards, " << ext << " stitched into " << stitched_ext);
  test::TempDir dir("shard-extras");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {"--float", ext},  {"--depth", ext},   {"--normal", ext},
      {"--height", ext}, {"--octaves", ext}, {"--primitive", ".bin"}};
  const auto outputs = [&](const std::string& stem, bool stitched) {
    std::vector<std::string> a;
    for (const auto& [option, e] : kinds) {
      a.insert(a.end(), {option, file(stem + option.substr(2) +
                                      (stitched && e != ".bin" ? stitched_ext : e))});
    }
    return a;
  };
  std::vector<std::string> whole = with_size({"render", scene, "-o", file("whole.png")}, 203, 131);
  for (const std::string& a : outputs("whole-", ext != stitched_ext)) {
    whole.push_back(a);
  }
  require_ok(run(whole));
  std::vector<std::string> stitch = {"stitch", "-o", file("stitched.png")};
  for (const std::string& a : outputs("stitched-", true)) {
    stitch.push_back(a);
  }
  for (int i = count - 1; i >= 0; --i) {
    const std::string part = cat({"part", std::to_string(i)});
    std::vector<std::string> a =
        with_size({"render", scene, "--shard", cat({std::to_string(i), "/", std::to_string(count)}),
                   "-o", file(part + ".png")},
                  203, 131);
    for (const std::string& o : outputs(part + "-", false)) {
      a.push_back(o);
    }
    require_ok(run(a));
    stitch.push_back(file(part + ".png"));
  }
  require_ok(run(stitch));
  CHECK(read_bytes(file("stitched.png")) == read_bytes(file("whole.png")));
  for (const auto& [option, e] : kinds) {
    const std::string name = option.substr(2) + (e == ".bin" ? e : stitched_ext);
    INFO(name);
    CHECK(read_bytes(file("stitched-" + name)) == read_bytes(file("whole-" + name)));
  }
}

TEST_CASE("extraOutputsOfRenderShardsStitchToTheBytesOfOneRender", "[shard]") {
  require_extras_stitched_equal("default", 3, ".pfm", ".pfm");
  require_extras_stitched_equal("lake", 2, ".exr", ".exr");
  require_extras_stitched_equal("planet", 1, ".pfm", ".exr");  // PFM shards into one EXR
}

// relief reference at `supersample` x its samples a pixel, whole and in `count` shards.
void require_reference_stitched_equal(int supersample, int count, const std::string& ext) {
  INFO(supersample << "x" << supersample << " samples in " << count << " shards, " << ext);
  test::TempDir dir("shard-reference");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const auto reference = [&](const std::string& stem, std::vector<std::string> extra) {
    std::vector<std::string> a =
        with_size({"reference", "default", "-o", file(stem + ".png"), "--float", file(stem + ext),
                   "--supersample", std::to_string(supersample), "--grid-scale", "2"},
                  101, 75);
    a.insert(a.end(), extra.begin(), extra.end());
    return run(a);
  };
  require_ok(reference("whole", {}));
  std::vector<std::string> stitch = {"stitch", "-o", file("stitched.png"), "--float",
                                     file("stitched" + ext)};
  for (int i = 0; i < count; ++i) {
    const std::string part = cat({"part", std::to_string(i)});
    require_ok(reference(part, {"--shard", cat({std::to_string(i), "/", std::to_string(count)})}));
    stitch.push_back(file(part + ".png"));
  }
  require_ok(run(stitch));
  CHECK(read_bytes(file("stitched.png")) == read_bytes(file("whole.png")));
  CHECK(read_bytes(file("stitched" + ext)) == read_bytes(file("whole" + ext)));
}

TEST_CASE("referenceShardsStitchToTheBytesOfOneReference", "[shard]") {
  // Steps of lcm(64, N) / N rows: 32 (N = 2), 64 (N = 3), 16 (N = 4); 75 rows.
  CHECK(ground_truth_shard_unit(1) == 64);
  CHECK(ground_truth_shard_unit(2) == 32);
  CHECK(ground_truth_shard_unit(3) == 64);
  CHECK(ground_truth_shard_unit(4) == 16);
  CHECK(ground_truth_shard_unit(16) == 4);
  require_reference_stitched_equal(2, 3, ".pfm");
  require_reference_stitched_equal(3, 2, ".exr");
  require_reference_stitched_equal(4, 5, ".pfm");
  require_reference_stitched_equal(4, 1, ".exr");
  test::TempDir dir("shard-reference-refused");
  const std::string out = (dir.path() / "r.png").string();
  test::require_refused(
      run(with_size({"reference", "default", "-o", out, "--supersample", "2", "--shard", "0/4"},
                    101, 75)),
      "has 3 bands of 32 rows, so at most 3 shards", out);
}

TEST_CASE("shardsPartitionTheRowsInStepsOfAnyUnit", "[shard]") {
  for (int unit = 1; unit <= 64; unit += 3) {
    for (int height = 1; height <= 300; height += 13) {
      const int steps = (height + unit - 1) / unit;
      for (const int count : {1, 2, 5, 9}) {
        if (count > steps) {
          CHECK_THROWS_AS(shard_rows(height, {0, count}, unit), ShardError);
          continue;
        }
        int next = 0;
        for (int i = 0; i < count; ++i) {
          const ShardSpan rows = shard_rows(height, {i, count}, unit);
          CHECK(rows.begin == next);
          CHECK(rows.begin % unit == 0);
          CHECK(rows.end > rows.begin);
          CHECK((rows.end % unit == 0 || rows.end == height));
          next = rows.end;
        }
        CHECK(next == height);
      }
    }
  }
  CHECK_THROWS_AS(shard_rows(100, {0, 1}, 0), ShardError);
  CHECK_THROWS_AS(shard_rows(100, {0, 1}, 65), ShardError);
}

TEST_CASE("companionsThatAreNotTheirShardsFilesAreRefused", "[shard]") {
  test::TempDir dir("shard-companions");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const auto part = [&](int i, std::vector<std::string> extra, const std::string& scene) {
    std::vector<std::string> a =
        with_size({"render", scene, "--shard", cat({std::to_string(i), "/2"}), "-o",
                   file(cat({"p", std::to_string(i), ".png"}))},
                  120, 100);
    a.insert(a.end(), extra.begin(), extra.end());
    require_ok(run(a));
    return file(cat({"p", std::to_string(i), ".png"}));
  };
  const std::string p0 = part(0, {"--float", file("f0.pfm"), "--depth", file("d0.pfm")}, "default");
  const std::string p1 = part(1, {"--float", file("f1.pfm")}, "default");
  const std::string out = file("out.png");
  const auto refused = [&](std::vector<std::string> extra, const std::string& message) {
    std::vector<std::string> a = {"stitch", "-o", out};
    a.insert(a.end(), extra.begin(), extra.end());
    test::require_refused(run(a), message, out);
    CHECK_FALSE(std::filesystem::exists(file("out.pfm")));
  };
  // Asked for an output a shard lacks; an output replacing a companion; a bad extension.
  refused({"--depth", file("out.pfm"), p0, p1}, "has no depth output to stitch into --depth");
  refused({"--float", file("f1.pfm"), p0, p1}, "name the same file");
  refused({"--float", file("out.txt"), p0, p1}, "give a file name ending in .pfm or .exr");
  refused({"--float", file("out.pfm"), "--out", dir.path().string(), p0}, "not both or neither");
  // A companion written again by another render (another scene: the same size, other bits).
  const auto text = [](const std::vector<unsigned char>& v) {
    return std::string(v.begin(), v.end());
  };
  const std::vector<unsigned char> p1_bytes = read_bytes(p1), f1 = read_bytes(file("f1.pfm"));
  part(1, {"--float", file("f1.pfm")}, "lake");
  test::write_file(file("lake-p1.png"), text(read_bytes(p1)));  // lake's shard kept aside
  test::write_file(p1, text(p1_bytes));
  refused({"--float", file("out.pfm"), p0, p1}, "is not the file that shard wrote");
  refused({"--float", file("out.pfm"), p0, file("lake-p1.png")}, "scene or software");
  test::write_file(file("f1.pfm"), text(f1));
  require_ok(run({"stitch", "-o", out, "--float", file("out.pfm"), p0, p1}));
  std::filesystem::remove(out);
  std::filesystem::remove(file("out.pfm"));
  std::vector<unsigned char> damaged = f1;
  damaged[damaged.size() / 2] ^= 1;
  test::write_file(file("f1.pfm"), text(damaged));
  refused({"--float", file("out.pfm"), p0, p1}, "is not the file that shard wrote");
  std::filesystem::remove(file("f1.pfm"));
  refused({"--float", file("out.pfm"), p0, p1}, "f1.pfm");
  // Without the extra outputs the PNGs still stitch, and the shards' other outputs are named.
  const test::CliResult r = run({"stitch", "-o", out, p0, p1});
  require_ok(r);
  CHECK(r.out.find("give --float FILE to stitch them") != std::string::npos);
}

TEST_CASE("forgedCompanionRecordsAreRefused", "[shard]") {
  const auto refused = [](const std::string& outputs) {
    INFO(outputs);
    const std::string text =
        R"({"index": 0, "count": 1, "backend": "simd", "width": 8, "height": 8, "top": 0, )"
        R"("rows": 8, "unit": 64, "outputs": )" +
        outputs + "}";
    CHECK_THROWS_AS(parse_shard_record(text, "shard"), ShardError);
  };
  refused("[]");
  refused(R"({"colour": {"file": "a.pfm", "bytes": 1, "crc32": 1}})");
  refused(R"({"float": {"file": "", "bytes": 1, "crc32": 1}})");
  refused(R"({"float": {"file": "a.pfm", "bytes": -1, "crc32": 1}})");
  refused(R"({"float": {"file": "a.pfm", "bytes": 1, "crc32": 4294967296}})");
  refused(R"({"float": {"file": "a.pfm", "bytes": 1}})");
  refused(R"({"float": {"file": "a.pfm", "bytes": 1, "crc32": 1, "x": 2}})");
  refused(R"({"float": "a.pfm"})");
  // No backend, or not a name.
  for (const char* backend : {"", R"("backend": "", )", R"("backend": 3, )"}) {
    CHECK_THROWS_AS(parse_shard_record(std::string(R"({"index": 0, "count": 1, )") + backend +
                                           R"("width": 8, "height": 8, "top": 0, "rows": 8, )"
                                           R"("unit": 64, "outputs": {}})",
                                       "shard"),
                    ShardError);
  }
  const ImageShardRecord r = parse_shard_record(
      R"({"index": 0, "count": 1, "backend": "simd", "width": 8, "height": 8, "top": 0, "rows": 8, "unit": 16, )"
      R"("outputs": {"depth": {"file": "d.pfm", "bytes": 300, "crc32": 7}}})",
      "shard");
  REQUIRE(r.companions.size() == 1);
  CHECK(r.unit == 16);
  CHECK(find_companion(r, "depth")->file == "d.pfm");
  CHECK(find_companion(r, "float") == nullptr);
  CHECK_THROWS_AS(
      parse_shard_record(
          R"({"index": 0, "count": 1, "backend": "simd", "width": 8, "height": 8, "top": 0, "rows": 8, "unit": 0, )"
          R"("outputs": {}})",
          "shard"),
      ShardError);
}

// The holes a hostile pass found: shards of different backends, a damaged PNG (a flipped bit
// in its image data: stb checks neither the chunk CRCs nor zlib's Adler-32), companions written
// from a linked directory, an empty --shard, a shard padded past --max-memory, raw ids under
// another extension.
TEST_CASE("damagedOrMixedShardsAndLinkedDirectoriesAreHandled", "[shard]") {
  test::TempDir dir("shard-hostile");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  const auto render = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = with_size({"render", "default"}, 120, 100);
    a.insert(a.end(), extra.begin(), extra.end());
    return run(a);
  };
  require_ok(render({"--shard", "0/2", "-o", file("a0.png")}));
  require_ok(render({"--shard", "1/2", "-o", file("a1.png")}));
  require_ok(render({"--shard", "1/2", "-o", file("d1.png"), "--backend", "reference-double"}));
  const std::string out = file("out.png");
  test::require_refused(run({"stitch", "-o", out, file("a0.png"), file("d1.png")}),
                        "backend (reference-double against simd) differs", out);
  // One bit of the image data flipped: the IDAT chunk's CRC no longer matches.
  std::vector<unsigned char> png = read_bytes(file("a1.png"));
  std::size_t idat = 0;
  for (std::size_t k = 8; k + 8 < png.size(); ++k) {
    if (std::string(png.begin() + std::ptrdiff_t(k), png.begin() + std::ptrdiff_t(k) + 4) ==
        "IDAT") {
      idat = k;
      break;
    }
  }
  REQUIRE(idat > 0);
  png[idat + 4 + 20] ^= 4;
  test::write_file(file("damaged.png"), std::string(png.begin(), png.end()));
  test::require_refused(run({"stitch", "-o", out, file("a0.png"), file("damaged.png")}),
                        "does not match its CRC-32", out);
  // The same shard with 3 MiB of private chunk: past --max-memory 2M before it is read.
  std::vector<unsigned char> padded = read_bytes(file("a1.png"));
  const std::vector<unsigned char> data(3 << 20, 7);
  std::vector<unsigned char> chunk = {0, 0x30, 0, 0, 'p', 'r', 'V', 't'};
  chunk.insert(chunk.end(), data.begin(), data.end());
  const std::uint32_t crc = crc32(std::span<const unsigned char>(chunk).subspan(4));
  for (const int shift : {24, 16, 8, 0}) {
    chunk.push_back(static_cast<unsigned char>(crc >> shift));
  }
  padded.insert(padded.begin() + 33, chunk.begin(), chunk.end());  // after IHDR
  test::write_file(file("padded.png"), std::string(padded.begin(), padded.end()));
  test::require_refused(
      run({"stitch", "--max-memory", "2M", "-o", out, file("a0.png"), file("padded.png")}),
      "reading these shards", out);
  require_ok(run({"stitch", "-o", out, file("a0.png"), file("padded.png")}));
  std::filesystem::remove(out);
  // Written from a linked directory: the record leads from the PNG's real directory.
  std::filesystem::create_directories(dir.path() / "real" / "deep");
  std::filesystem::create_directory_symlink(dir.path() / "real" / "deep", dir.path() / "link");
  for (const std::string i : {"0", "1"}) {
    require_ok(render({"--shard", i + "/2", "-o", file("link/l" + i + ".png"), "--float",
                       file("f" + i + ".pfm")}));
  }
  require_ok(run(
      {"stitch", "-o", out, "--float", file("out.pfm"), file("link/l0.png"), file("link/l1.png")}));
  require_ok(render({"-o", file("whole.png"), "--float", file("whole.pfm")}));
  CHECK(read_bytes(file("out.pfm")) == read_bytes(file("whole.pfm")));
  // An empty --shard (an unset variable in a job script) and raw ids named .exr.
  test::require_refused(render({"--shard", "", "-o", file("e.png")}), "--shard", file("e.png"));
  test::require_refused(run({"stitch", "-o", file("p.png"), "--primitive", file("p.exr"),
                             file("a0.png"), file("a1.png")}),
                        "give a file name ending in .bin", file("p.png"));
}

}  // namespace
}  // namespace relief
