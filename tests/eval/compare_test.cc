// relief compare against Debian's idiff (OpenImageIO 2.4.7): the same pairs of images with the
// same thresholds must give the same verdict (exit code) and the same figures to the precision
// idiff prints them (%g, six digits). Both call ImageBufAlgo::compare, so any difference is in
// how relief reads the files or decides the verdict. Where relief deliberately differs (sizes,
// channel counts: docs/using-relief.md, "Comparing images") the test says so and checks idiff's
// side too, so that a changed idiff is noticed.
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <stb_image.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "tests/support/cli_support.h"
#include "tests/support/idiff_support.h"
#include "tests/support/test_support.h"
#include "tools/colormap.h"
#include "tools/float_image_file.h"
#include "tools/image_compare.h"

namespace relief {
namespace {

using test::CliResult;
using test::PrintedFigures;

constexpr int kW = 40, kH = 30;
constexpr float kInf = std::numeric_limits<float>::infinity();

std::vector<float> random_floats(unsigned seed, int channels) {
  test::TestRandom random(seed);
  std::vector<float> v(std::size_t(kW) * kH * std::size_t(channels));
  for (float& x : v) {
    x = static_cast<float>(random.uniform(0, 1));
  }
  return v;
}

std::string write_floats(const std::filesystem::path& path, const std::vector<float>& v,
                         int channels) {
  const std::vector<unsigned char> bytes =
      encode_float_image(*float_format_of(path.string()), kW, kH, channels, v,
                         std::size_t(kW) * std::size_t(channels), {});
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  return path.string();
}

std::string write_png(const std::filesystem::path& path, const std::vector<std::uint8_t>& rgb,
                      int width = kW, int height = kH) {
  const std::vector<unsigned char> bytes = encode_png_rgb(width, height, rgb);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  return path.string();
}

std::vector<std::string> compare_args(const std::string& a, const std::string& b,
                                      const CompareThresholds& t, const std::string& json) {
  std::vector<std::string> args = {"compare", a, b, "--json", json};
  const std::vector<std::pair<const char*, float>> options = {
      {"--fail", t.fail}, {"--failpercent", t.fail_percent}, {"--hardfail", t.hard_fail},
      {"--warn", t.warn}, {"--warnpercent", t.warn_percent}, {"--hardwarn", t.hard_warn}};
  for (const auto& [name, value] : options) {
    args.insert(args.end(), {name, std::isinf(value) ? "inf" : test::option_value(value)});
  }
  return args;
}

struct Pair {
  std::string name;
  std::string a, b;
  CompareThresholds thresholds;
  int expected;  // the exit code both give
};

// relief compare and idiff agree on the verdict and on every figure idiff prints.
void check_agreement(const Pair& pair, const std::filesystem::path& dir) {
  INFO(pair.name);
  const std::string json_path = (dir / "report.json").string();
  const CliResult relief = test::run(compare_args(pair.a, pair.b, pair.thresholds, json_path));
  const test::ToolRun idiff = test::run_idiff(pair.a, pair.b, pair.thresholds);
  INFO("relief:\n" << relief.out << relief.err << "idiff:\n" << idiff.out);
  CHECK(relief.code == pair.expected);
  CHECK(idiff.code == pair.expected);
  const PrintedFigures theirs = test::parse_report(idiff.out);
  const PrintedFigures ours = test::parse_report(relief.out);
  // The lines relief prints are idiff's, character for character.
  CHECK(ours.mean == theirs.mean);
  CHECK(ours.rms == theirs.rms);
  CHECK(ours.psnr == theirs.psnr);
  CHECK(ours.max == theirs.max);
  CHECK(ours.max_at == theirs.max_at);
  CHECK(ours.warn_line == theirs.warn_line);
  CHECK(ours.fail_line == theirs.fail_line);
  CHECK(ours.verdict == theirs.verdict);
  // The JSON's figures, at full precision, round to what idiff printed.
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(json_path));
  CHECK(j["exit_code"] == pair.expected);
  const auto figure = [&](const char* key) {
    return j[key].is_null() ? std::numeric_limits<double>::infinity() : j[key].get<double>();
  };
  CHECK(test::agrees_to_printed_precision(figure("mean_error"), theirs.mean));
  CHECK(test::agrees_to_printed_precision(figure("rms_error"), theirs.rms));
  CHECK(test::agrees_to_printed_precision(figure("psnr_db"), theirs.psnr));
  CHECK(test::agrees_to_printed_precision(figure("max_error"), theirs.max));
  const std::string warned = std::to_string(j["warn_pixels"].get<long long>());
  const std::string failed = std::to_string(j["fail_pixels"].get<long long>());
  CHECK(theirs.warn_line.rfind(test::concat({"  ", warned, " pixels"}), 0) == 0);
  CHECK(theirs.fail_line.rfind(test::concat({"  ", failed, " pixels"}), 0) == 0);
  if (j.contains("max_error_at")) {
    const nlohmann::json& at = j["max_error_at"];
    const std::string x = std::to_string(at["x"].get<int>());
    const std::string y = std::to_string(at["y"].get<int>());
    CHECK(theirs.max_at ==
          test::concat({"(", x, ", ", y, ", ", at["channel"].get<std::string>(), ")"}));
  }
}

TEST_CASE("compareAgreesWithIdiffOnVerdictsAndFigures", "[compare]") {
  test::TempDir dir("compare-idiff");
  const auto path = [&](const char* name) { return (dir.path() / name).string(); };

  // An 8-bit picture, twice; and the same values as floats (v / 255, as OpenImageIO reads
  // 8-bit channels), in another format.
  std::vector<std::uint8_t> rgb(std::size_t(kW) * kH * 3);
  std::vector<float> as_floats(rgb.size());
  for (std::size_t k = 0; k < rgb.size(); ++k) {
    rgb[k] = static_cast<std::uint8_t>((k * 97 + k / 11) & 0xff);
    as_floats[k] = float(rgb[k]) / 255.0f;
  }
  const std::string png = write_png(path("a.png"), rgb);
  const std::string png_copy = write_png(path("a-copy.png"), rgb);
  const std::string png_floats = write_floats(path("a-floats.exr"), as_floats, 3);

  // Small noise: |d| <= 1e-3 on every channel.
  const std::vector<float> base = random_floats(1, 3);
  std::vector<float> noisy = base;
  test::TestRandom random(2);
  for (float& v : noisy) {
    v += static_cast<float>(random.uniform(-1e-3, 1e-3));
  }
  const std::string base_exr = write_floats(path("base.exr"), base, 3);
  const std::string noisy_exr = write_floats(path("noisy.exr"), noisy, 3);

  // Three hard outliers of different sizes beside noise of 1e-5.
  std::vector<float> outliers = base;
  for (float& v : outliers) {
    v += static_cast<float>(random.uniform(-1e-5, 1e-5));
  }
  outliers[(5 * kW + 7) * 3 + 1] += 0.5f;
  outliers[(20 * kW + 33) * 3 + 2] -= 0.45f;
  outliers[(29 * kW + 0) * 3 + 0] += 0.4f;
  const std::string base_pfm = write_floats(path("base.pfm"), base, 3);
  const std::string outliers_pfm = write_floats(path("outliers.pfm"), outliers, 3);

  const CompareThresholds defaults;
  CompareThresholds loose;  // no pixel fails, many warn: idiff passes (image_compare.cc)
  loose.fail = 0.01f;
  loose.warn = 1e-4f;
  CompareThresholds mostly_failing = loose;  // 87.5% of the pixels fail, 95% may
  mostly_failing.fail = 5e-4f;
  mostly_failing.fail_percent = 95;
  CompareThresholds outlier_warn;  // 3 of 1200 pixels fail, 1% may; all warn
  outlier_warn.fail = 0.1f;
  outlier_warn.fail_percent = 1;
  CompareThresholds outlier_hardfail = outlier_warn;
  outlier_hardfail.hard_fail = 0.3f;
  CompareThresholds outlier_pass = outlier_warn;  // 3 warn too, and 1% may
  outlier_pass.warn = 0.1f;
  outlier_pass.warn_percent = 1;
  CompareThresholds outlier_hardwarn = outlier_pass;
  outlier_hardwarn.hard_warn = 0.3f;

  const std::vector<Pair> pairs = {
      {"identical PNG files", png, png_copy, defaults, 0},
      {"PNG against the same values in EXR", png, png_floats, defaults, 0},
      {"small noise, default thresholds", base_exr, noisy_exr, defaults, 2},
      {"small noise, no pixel over fail", base_exr, noisy_exr, loose, 0},
      {"small noise, fewer failures than allowed", base_exr, noisy_exr, mostly_failing, 1},
      {"outliers, fewer failures than allowed", base_pfm, outliers_pfm, outlier_warn, 1},
      {"outliers over hardfail", base_pfm, outliers_pfm, outlier_hardfail, 2},
      {"outliers within every percentage", base_pfm, outliers_pfm, outlier_pass, 0},
      {"outliers over hardwarn", base_pfm, outliers_pfm, outlier_hardwarn, 1},
      {"outliers, default thresholds", base_pfm, outliers_pfm, defaults, 2},
  };
  for (const Pair& pair : pairs) {
    check_agreement(pair, dir.path());
  }
}

// The cases where relief compare answers differently from Debian's idiff, on purpose.
TEST_CASE("compareRefusesWhatIdiffComparesAnyway", "[compare]") {
  test::TempDir dir("compare-refused");
  const std::vector<std::uint8_t> rgb(std::size_t(kW) * kH * 3, 128);
  const std::string a = write_png(dir.path() / "a.png", rgb);
  const std::string shorter = write_png(dir.path() / "short.png", rgb, kW, kH - 2);
  const std::string one_channel =
      write_floats(dir.path() / "one.pfm", std::vector<float>(std::size_t(kW) * kH, 0.5f), 1);
  const std::filesystem::path json = dir.path() / "report.json";

  // Different sizes: relief 3 (idiff's ErrDifferentSize) with the JSON written; idiff 2.4
  // compares the union of the two windows, the missing pixels as 0, and reports a failure.
  const CliResult sizes = test::run({"compare", a, shorter, "--json", json.string()});
  CHECK(sizes.code == 3);
  CHECK_THAT(sizes.out, Catch::Matchers::Contains("differ in size: 40 x 30 and 40 x 28"));
  CHECK(nlohmann::json::parse(std::ifstream(json))["verdict"] == "SIZE MISMATCH");
  CHECK(test::run_idiff(a, shorter, {}).code == 2);

  // Different channel counts: relief 4 (not comparable), nothing written; idiff reads the
  // missing channels as 0 and reports a failure.
  std::filesystem::remove(json);
  const CliResult channels = test::run({"compare", a, one_channel, "--json", json.string()});
  CHECK(channels.code == 4);
  CHECK_THAT(channels.err, Catch::Matchers::Contains("differ in their number of channels"));
  CHECK_FALSE(std::filesystem::exists(json));
  CHECK(test::run_idiff(a, one_channel, {}).code == 2);
}

TEST_CASE("unreadableImagesAreFileErrorsForBoth", "[compare]") {
  test::TempDir dir("compare-unreadable");
  const std::vector<std::uint8_t> rgb(std::size_t(kW) * kH * 3, 7);
  const std::string a = write_png(dir.path() / "a.png", rgb);
  const std::vector<unsigned char> whole = encode_png_rgb(kW, kH, rgb);
  const auto cut = [&](const char* name, std::size_t bytes) {
    return test::write_file(dir.path() / name, std::string(whole.begin(), whole.begin() + bytes));
  };
  const std::string no_header = cut("no-header.png", 20);  // within IHDR
  const std::string text = test::write_file(dir.path() / "text.png", "not an image at all");
  for (const std::string& bad : {no_header, text, (dir.path() / "missing.png").string()}) {
    INFO(bad);
    const CliResult r = test::run({"compare", a, bad});
    CHECK(r.code == 4);
    CHECK_THAT(r.err, Catch::Matchers::Contains("relief: error:"));
    CHECK(test::run_idiff(a, bad, {}).code == 4);
  }
  // Pixel data cut short: relief refuses the file. (Debian's idiff reads it through its image
  // cache, which ignores the failed read and compares uninitialised memory: a FAILURE with
  // figures such as 1e+27, different from run to run, so it is not compared here.)
  const std::string short_pixels = cut("short-pixels.png", whole.size() - 20);
  const CliResult cut_short = test::run({"compare", a, short_pixels});
  CHECK(cut_short.code == 4);
  CHECK_THAT(cut_short.err, Catch::Matchers::Contains("short-pixels.png cannot be read"));
  // Special files are refused before OpenImageIO opens them: idiff waits for ever on a FIFO
  // with no writer, and takes a directory B as B/A's file name.
  const std::filesystem::path fifo = dir.path() / "fifo.png";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const auto& [bad, reason] :
       std::vector<std::pair<std::string, std::string>>{{fifo.string(), "is a FIFO"},
                                                        {dir.path().string(), "is a directory"},
                                                        {"/dev/zero", "is a character device"}}) {
    INFO(bad);
    const CliResult r = test::run({"compare", a, bad, "--json", (dir.path() / "j").string()});
    CHECK(r.code == 4);
    CHECK_THAT(r.err, Catch::Matchers::Contains(reason));
    CHECK_FALSE(std::filesystem::exists(dir.path() / "j"));
  }
}

// The figures of a difference small enough to work out by hand: 4 x 3 pixels of 2 channels,
// all 0, against the same with 0.25 at pixel (2, 1), channel 1.
TEST_CASE("compareImagesGivesTheClosedFormFigures", "[compare]") {
  FloatImage a{4, 3, 2, {"X", "Y"}, std::vector<float>(24, 0.0f)};
  FloatImage b = a;
  b.pixels[(1 * 4 + 2) * 2 + 1] = 0.25f;
  const CompareResult r = compare_images(a, b, {});
  CHECK(r.verdict == CompareVerdict::kFailure);
  CHECK(r.pixels == 12);
  CHECK(r.mean_error == Approx(0.25 / 24).epsilon(1e-15));
  CHECK(r.rms_error == Approx(std::sqrt(0.0625 / 24)).epsilon(1e-15));
  // The peak is 1: no value exceeds it.
  CHECK(r.psnr == Approx(20 * std::log10(1 / std::sqrt(0.0625 / 24))).epsilon(1e-12));
  CHECK(r.max_error == 0.25);
  CHECK((r.max_x == 2 && r.max_y == 1 && r.max_channel == 1));
  CHECK((r.warn_pixels == 1 && r.fail_pixels == 1));
  // One pixel in 12 (8.3%) may fail under 10%: then it only warns.
  CompareThresholds allowed;
  allowed.fail_percent = 10;
  CHECK(compare_images(a, b, allowed).verdict == CompareVerdict::kWarning);
  CHECK(compare_images(a, a, {}).verdict == CompareVerdict::kPass);
  CHECK(std::isinf(compare_images(a, a, {}).psnr));

  FloatImage narrow = a;
  narrow.width = 3;
  narrow.pixels.resize(18);
  CHECK(compare_images(a, narrow, {}).verdict == CompareVerdict::kSizeMismatch);
  FloatImage one_channel{4, 3, 1, {}, std::vector<float>(12, 0.0f)};
  CHECK(compare_images(a, one_channel, {}).verdict == CompareVerdict::kFileError);
}

// The heat map: black where equal, red at the largest difference, dark blue four decades
// below it (compare_report.h), rows top first as the report's (x, y).
TEST_CASE("compareWritesAHeatMapOfTheDifferences", "[compare]") {
  test::TempDir dir("compare-heat");
  std::vector<float> a(std::size_t(kW) * kH, 0.0f), b = a;
  b[3 * kW + 4] += 0.25f;      // the largest: red
  b[10 * kW + 20] += 2.5e-5f;  // four decades below: dark blue
  const std::string pa = write_floats(dir.path() / "a.pfm", a, 1);
  const std::string pb = write_floats(dir.path() / "b.pfm", b, 1);
  const std::filesystem::path heat = dir.path() / "heat.png";
  const CliResult r = test::run({"compare", pa, pb, "--diff", heat.string()});
  INFO(r.out << r.err);
  REQUIRE(r.code == 2);
  const std::vector<unsigned char> png = test::read_bytes(heat);
  int w = 0, h = 0, n = 0;
  unsigned char* pixels = stbi_load_from_memory(png.data(), int(png.size()), &w, &h, &n, 3);
  REQUIRE(pixels != nullptr);
  const auto rgb = [&](int x, int y) {
    const unsigned char* p = pixels + (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3;
    return Rgb8{p[0], p[1], p[2]};
  };
  // The PFM's row 0 is the bottom row; OpenImageIO (and idiff) count rows from the top.
  const Rgb8 red = heat_color(1.0), blue = heat_color(0.0);
  CHECK(rgb(4, kH - 1 - 3) == red);
  CHECK(rgb(20, kH - 1 - 10) == blue);
  CHECK(rgb(0, 0) == (Rgb8{0, 0, 0}));
  CHECK_THAT(r.out, Catch::Matchers::Contains("Max error  = 0.25 @ (4, 26, Y)"));
  stbi_image_free(pixels);
}

}  // namespace
}  // namespace relief
