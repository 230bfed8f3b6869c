// relief generate (tools/generate_command.h): every format holds the same map (the PNG's and
// RAW16's levels are the float heights mapped from the recorded low and high), the map tiles
// (its last row and column repeat the first), the figures are those of the generators, a
// generated map renders as a terrain sketch, and every bad option is refused with nothing
// written.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "image/png_text.h"
#include "pipeline/png_checks.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

using test::read_bytes;
using test::run;

using test::require_ok;

// A PFM of one channel as relief writes it: rows bottom to top.
std::vector<float> pfm_values(const std::vector<unsigned char>& bytes, int n) {
  const std::string header = "Pf\n" + std::to_string(n) + " " + std::to_string(n) + "\n-1.0\n";
  REQUIRE(bytes.size() == header.size() + std::size_t(n) * std::size_t(n) * 4);
  REQUIRE(std::equal(header.begin(), header.end(), bytes.begin()));
  std::vector<float> values(std::size_t(n) * std::size_t(n));
  std::memcpy(values.data(), bytes.data() + header.size(), values.size() * 4);
  return values;
}

TEST_CASE("generatedMapsAreTheSameInEveryFormatAndTile", "[cli]") {
  test::TempDir dir("generate");
  const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
  for (const std::string method : {"triangle-edge", "diamond-square", "square-square", "perlin"}) {
    INFO(method);
    const int n = 65;
    const auto generate = [&](const std::string& out, std::vector<std::string> extra = {}) {
      std::vector<std::string> a = {"generate", method, "--size", "65", "--seed", "9", "-o", out};
      a.insert(a.end(), extra.begin(), extra.end());
      require_ok(run(a));
    };
    generate(file(method + ".pfm"), {"--json", file(method + ".json")});
    generate(file(method + ".png"), {"--creases", file(method + "-creases.png")});
    generate(file(method + ".r16"));
    const std::vector<float> heights = pfm_values(read_bytes(file(method + ".pfm")), n);
    const std::vector<unsigned char> json_bytes = read_bytes(file(method + ".json"));
    const nlohmann::json figures = nlohmann::json::parse(json_bytes.begin(), json_bytes.end());
    const double low = figures["low"], high = figures["high"];
    CHECK(low == *std::min_element(heights.begin(), heights.end()));
    CHECK(high == *std::max_element(heights.begin(), heights.end()));
    // The file repeats its first row and column last (rows bottom to top in the PFM).
    const auto h = [&](int x, int z) {
      return double(heights[std::size_t(z) * n + std::size_t(x)]);
    };
    for (int k = 0; k < n; ++k) {
      CHECK(h(k, 0) == h(k, n - 1));
      CHECK(h(0, k) == h(n - 1, k));
    }
    // And the map tiles without a seam: across the wrap (the first column's neighbours the
    // second and the second to last) the second differences are like those inside. A map made
    // without wrapping would break its slope there, far above the inside's mean.
    double seam = 0, inside = 0;
    for (int k = 0; k < n - 1; ++k) {
      seam += std::abs(h(n - 2, k) - 2 * h(0, k) + h(1, k)) +
              std::abs(h(k, n - 2) - 2 * h(k, 0) + h(k, 1));
      for (int x = 1; x < n - 1; ++x) {
        inside += std::abs(h(x - 1, k) - 2 * h(x, k) + h(x + 1, k));
      }
    }
    const double ratio = (seam / (2.0 * (n - 1))) / (inside / (double(n - 1) * (n - 2)));
    CHECK(ratio > 0.3);
    CHECK(ratio < 3.0);
    // The PNG: 16-bit levels round((h - low) / (high - low) * 65535), top row = z0, and its
    // text records the range.
    const std::vector<unsigned char> png = read_bytes(file(method + ".png"));
    const Grey16Image levels = decode_grey16_png(png, "map", "");
    REQUIRE((levels.width == n && levels.height == n));
    const std::vector<unsigned char> raw = read_bytes(file(method + ".r16"));
    REQUIRE(raw.size() == 2 * std::size_t(n) * std::size_t(n));
    for (int z = 0; z < n; ++z) {
      for (int x = 0; x < n; ++x) {
        const double height = heights[std::size_t(n - 1 - z) * n + std::size_t(x)];
        const long expected = std::lround((height - low) / (high - low) * 65535.0);
        const std::size_t k = std::size_t(z) * n + std::size_t(x);
        CHECK(std::abs(long(levels.levels[k]) - expected) <= 1);
        CHECK(raw[2 * k] + 256 * raw[2 * k + 1] == levels.levels[k]);
      }
    }
    bool recorded = false;
    for (const ImageText& t : read_png_text(png)) {
      if (t.keyword == "relief:heights") {
        const nlohmann::json record = nlohmann::json::parse(t.text);
        recorded = record["low"] == low && record["high"] == high;
      }
    }
    CHECK(recorded);
  }
}

// Whole numbers are decimal whatever their leading zeros (CLI11 alone read "011" as octal 9);
// --cells binds Perlin alone.
TEST_CASE("generateReadsNumbersInDecimalAndCellsForPerlinAlone", "[cli]") {
  test::TempDir dir("generate-numbers");
  const auto figures = [&](std::vector<std::string> args) {
    const std::string json = (dir.path() / "f.json").string();
    args.insert(args.begin(), "generate");
    args.insert(args.end(), {"-o", (dir.path() / "m.pfm").string(), "--json", json});
    require_ok(run(args));
    const std::vector<unsigned char> bytes = read_bytes(json);
    return nlohmann::json::parse(bytes.begin(), bytes.end());
  };
  const nlohmann::json f =
      figures({"perlin", "--size", "017", "--seed", "017", "--smooth", "010", "--cells", "04"});
  CHECK(f["size"] == 17);
  CHECK(f["seed"] == 17);
  CHECK(f["smooth"] == 10);
  CHECK(f["cells"] == 4);
  CHECK(figures({"triangle-edge", "--size", "3"})["size"] == 3);  // --cells 4 > 1: not Perlin's
  CHECK(figures({"square-square", "--size", "5", "--amplitude", "-0"})["amplitude"].dump() ==
        "0.0");
}

TEST_CASE("aGeneratedMapRendersAsATerrainSketch", "[cli]") {
  test::TempDir dir("generate-render");
  const std::string map = (dir.path() / "hills.png").string();
  require_ok(run({"generate", "square-square", "--size", "257", "--seed", "3", "-o", map}));
  require_ok(run({"render", "default", "--set", "terrain.sketch={\"image\": \"" + map + "\"}",
                  "--set", "viewport.width=160", "--set", "viewport.height=100", "-o",
                  (dir.path() / "hills-render.png").string()}));
}

TEST_CASE("generateRefusesBadOptionsWithNothingWritten", "[cli]") {
  test::TempDir dir("generate-refused");
  const std::string out = (dir.path() / "map.png").string();
  const auto refused = [&](std::vector<std::string> args, const std::string& message) {
    std::vector<std::string> a = {"generate"};
    a.insert(a.end(), args.begin(), args.end());
    if (std::find(a.begin(), a.end(), "-o") == a.end()) {
      a.insert(a.end(), {"-o", out});
    }
    test::require_refused(run(a), message, out);
  };
  refused({"midpoint"}, "METHOD midpoint is not a generator");
  refused({"perlin", "--seed", "-1"}, "--seed");
  refused({"perlin", "--seed", "18446744073709551616"}, "--seed");
  refused({"perlin", "--seed", "1.5"}, "--seed");
  refused({"perlin", "--size", "1000"}, "--size 1000 is out of range");
  refused({"perlin", "--size", "16387"}, "--size 16387 is out of range");
  refused({"perlin", "--size", "2"}, "--size 2 is out of range");
  refused({"square-square", "--roughness", "nan"}, "--roughness");
  refused({"square-square", "--roughness", "2.5"}, "--roughness");
  refused({"square-square", "--amplitude", "-1"}, "--amplitude");
  refused({"square-square", "--amplitude", "inf"}, "--amplitude");
  refused({"square-square", "--smooth", "65"}, "--smooth 65 is out of range");
  refused({"perlin", "--size", "65", "--cells", "3"}, "--cells 3 is out of range");
  refused({"perlin", "--size", "65", "--cells", "64"}, "--cells 64 is out of range");
  refused({"perlin", "-o", (dir.path() / "map.txt").string()}, "give a file name ending in");
  refused({"perlin", "--creases", out}, "same file");
  // Empty values are refused, not read as 0 or as no output.
  refused({"square-square", "--amplitude", ""}, "--amplitude");
  refused({"square-square", "--roughness", ""}, "--roughness");
  refused({"square-square", "--creases", ""}, "--creases is empty");
  refused({"square-square", "--json", ""}, "--json is empty");
  // Outputs that cannot be written are found before the work, and none is written.
  refused({"square-square", "--json", (dir.path() / "missing" / "f.json").string()},
          "does not exist");
  refused({"square-square", "--json", (dir.path() / (std::string(300, 'j') + ".json")).string()},
          "the file system allows at most 255");
  refused({"square-square", "-o", dir.path().string() + "/"}, "give a file name ending in");
  refused({"square-square", "--size", "16385", "--max-memory", "64M"}, "Lower --size");
}

}  // namespace
}  // namespace relief
