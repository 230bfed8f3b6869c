// Outputs that cannot be written, outputs that name an input or each other, images
// holding NaN or infinities, --max-memory's largest units, an address-space limit on the real
// binary, and crosscheck's exit codes. Each case failed (an abort, a destroyed input, a silent
// NaN) before its fix.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/idiff_support.h"
#include "tests/support/limited_run.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using test::CliResult;
using test::run;

const std::vector<std::string> kSmallLimitsFrame = {
    "--set", "viewport.width=64", "--set", "viewport.height=48",
    "--set", "grid.width=48",     "--set", "grid.height=48"};

CliResult render_small(std::vector<std::string> args) {
  args.insert(args.begin(), "render");
  args.insert(args.end(), kSmallLimitsFrame.begin(), kSmallLimitsFrame.end());
  return run(args);
}

// a.png and ref.pfm (64 x 48, a second view) in `dir`.
void write_inputs(const fs::path& dir) {
  REQUIRE(render_small({"-o", (dir / "a.png").string()}).code == 0);
  REQUIRE(render_small({"--set", "camera.yaw_deg=10", "-o", (dir / "b.png").string(), "--float",
                        (dir / "ref.pfm").string()})
              .code == 0);
}

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// A 64 x 48 RGB PFM written by hand (little-endian, scale -1), so that any value can be put in.
std::string write_pfm(const fs::path& path, const std::vector<float>& values) {
  std::string bytes = "PF\n64 48\n-1.0\n";
  for (const float v : values) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 4; ++i) {
      bytes.push_back(static_cast<char>(bits >> (8 * i)));
    }
  }
  return test::write_file(path, bytes);
}
constexpr std::size_t kPfmValues = 64 * 48 * 3;

TEST_CASE("outputsThatCannotBeWrittenExit1WithAMessage", "[cli]") {
  // Each of these aborted on an uncaught exception (exit 134) instead of exiting 1.
  test::TempDir dir("cli-unwritable");
  write_inputs(dir.path());
  const std::string a = (dir.path() / "a.png").string(), ref = (dir.path() / "ref.pfm").string();
  fs::create_directories(dir.path() / "d");
  const fs::path fifo = dir.path() / "f.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::vector<std::string> before = listing(dir.path());
  std::vector<std::vector<std::string>> outputs = {
      {"--json", (dir.path() / "nodir" / "j.json").string()},
      {"--map", (dir.path() / "nodir" / "m.png").string()},
      {"--json", (dir.path() / "d").string() + "/"},
      {"--json", fifo.string()}};
  if (fs::exists("/dev/full")) {
    outputs.push_back({"--json", "/dev/full"});
  }
  for (const std::vector<std::string>& output : outputs) {
    std::vector<std::string> args = {"error", a, ref};
    args.insert(args.end(), output.begin(), output.end());
    const CliResult r = run(args);
    INFO(output.back() << ": " << r.err);
    CHECK(r.code == kExitOutputError);
    CHECK_THAT(r.err, Contains("relief: error: cannot write"));
    CHECK(r.out.empty());
    CHECK(listing(dir.path()) == before);
    CHECK(fs::is_empty(dir.path() / "d"));
    CHECK(fs::is_fifo(fifo));
  }
}

// `args` is refused with `code` and the aliasing message; `kept` is byte-identical afterwards
// and none of `absent` exists.
void require_alias_refused(const std::vector<std::string>& args, int code, const fs::path& kept,
                           const std::vector<fs::path>& absent = {}) {
  const std::vector<unsigned char> bytes = test::read_bytes(kept);
  REQUIRE_FALSE(bytes.empty());
  const CliResult r = run(args);
  INFO(args[0] << " ... " << args.back() << ": " << r.err);
  CHECK(r.code == code);
  CHECK_THAT(r.err, Contains("relief: error:") && Contains("name the same file"));
  const bool kept_intact = test::read_bytes(kept) == bytes;  // (no dump of the bytes)
  CHECK(kept_intact);
  for (const fs::path& path : absent) {
    CHECK_FALSE(fs::exists(path));
  }
}

TEST_CASE("anOutputNamingAnInputIsRefusedAndTheInputKept", "[cli]") {
  // An output naming an input destroyed it with exit 0 (or, for error, exit 0 with the input
  // image replaced by its own error map).
  test::TempDir dir("cli-input-alias");
  write_inputs(dir.path());
  const fs::path keep = dir.path() / "keep.png", a = dir.path() / "a.png";
  fs::copy_file(a, keep);
  const std::string ref = (dir.path() / "ref.pfm").string();
  require_alias_refused({"error", keep.string(), ref, "--map", keep.string()}, kExitBadInput, keep);
  require_alias_refused({"compare", a.string(), ref, "--json", a.string()}, 4, a);
  // Another spelling of the same file: a symbolic link (which the rename into place replaced
  // with a regular file) and a hard link.
  const fs::path symlink = dir.path() / "link.png", hardlink = dir.path() / "hard.png";
  fs::create_symlink(keep.filename(), symlink);
  fs::create_hard_link(keep, hardlink);
  require_alias_refused({"error", keep.string(), ref, "--map", symlink.string()}, kExitBadInput,
                        keep);
  CHECK(fs::is_symlink(symlink));
  require_alias_refused({"error", keep.string(), ref, "--map", hardlink.string()}, kExitBadInput,
                        keep);
  const bool keep_intact = test::read_bytes(keep) == test::read_bytes(a);
  CHECK(keep_intact);
  // The scene file itself as the statistics output.
  const CliResult scene = run({"scene"});
  REQUIRE(scene.code == 0);
  const fs::path scene_file = test::write_file(dir.path() / "s.json", scene.out);
  std::vector<std::string> render = {"render",       scene_file.string(),
                                     "--stats-json", scene_file.string(),
                                     "-o",           (dir.path() / "o.png").string()};
  render.insert(render.end(), kSmallLimitsFrame.begin(), kSmallLimitsFrame.end());
  require_alias_refused(render, kExitBadInput, scene_file, {dir.path() / "o.png"});
}

TEST_CASE("twoOutputsNamingOneFileAreRefused", "[cli]") {
  // Two outputs of one name: one silently overwrote the other.
  test::TempDir dir("cli-output-alias");
  write_inputs(dir.path());
  const fs::path a = dir.path() / "a.png", x = dir.path() / "x.png";
  require_alias_refused({"compare", a.string(), (dir.path() / "b.png").string(), "--json",
                         x.string(), "--diff", x.string()},
                        4, a, {x});
  const fs::path r = dir.path() / "r.png", pfm = dir.path() / "x.pfm";
  std::vector<std::string> stats = {"render", "-o", r.string(), "--stats-json", r.string()};
  stats.insert(stats.end(), kSmallLimitsFrame.begin(), kSmallLimitsFrame.end());
  require_alias_refused(stats, kExitBadInput, a, {r});
  std::vector<std::string> floats = {"render",     "-o",      r.string(),  "--float",
                                     pfm.string(), "--depth", pfm.string()};
  floats.insert(floats.end(), kSmallLimitsFrame.begin(), kSmallLimitsFrame.end());
  require_alias_refused(floats, kExitBadInput, a, {r, pfm});
}

TEST_CASE("inputsMayNameTheSameFile", "[cli]") {
  // Only outputs are checked for aliasing: an image compared with itself is still measured.
  test::TempDir dir("cli-self");
  write_inputs(dir.path());
  const std::string a = (dir.path() / "a.png").string();
  const CliResult error = run({"error", a, a});
  INFO(error.err);
  CHECK(error.code == 0);
  CHECK_THAT(error.out, Contains("PSNR") && Contains("inf dB"));
  const CliResult compare = run({"compare", a, a});
  INFO(compare.err);
  CHECK(compare.code == 0);
  CHECK_THAT(compare.out, Contains("PASS"));
}

TEST_CASE("errorRefusesNaNAndInfiniteImages", "[cli]") {
  // An image of NaN was measured (a finite PSNR) with exit 0; relief error measures finite
  // radiance only.
  test::TempDir dir("cli-nan-error");
  write_inputs(dir.path());
  const std::string ref = (dir.path() / "ref.pfm").string();
  const fs::path json = dir.path() / "out.json";
  const std::string all_nan =
      write_pfm(dir.path() / "allnan.pfm", std::vector<float>(kPfmValues, std::nanf("")));
  const CliResult nan = run({"error", all_nan, ref, "--json", json.string()});
  INFO(nan.err);
  CHECK(nan.code == kExitBadInput);
  CHECK_THAT(nan.err, Contains("relief: error:") && Contains("holds 9216 NaN"));
  CHECK_FALSE(fs::exists(json));
  std::vector<float> values(kPfmValues, 0.5f);
  values[100] = std::numeric_limits<float>::infinity();
  const std::string inf = write_pfm(dir.path() / "inf.pfm", values);
  const CliResult r = run({"error", inf, ref, "--json", json.string()});
  INFO(r.err);
  CHECK(r.code == kExitBadInput);
  CHECK_THAT(r.err, Contains("0 NaN and 1 infinite"));
  CHECK_FALSE(fs::exists(json));
}

TEST_CASE("compareKeepsIdiffsVerdictButReportsNaN", "[cli]") {
  // idiff passes an image of NaN (a NaN difference is over no threshold); compare keeps that
  // verdict but no longer hides the NaN.
  test::TempDir dir("cli-nan-compare");
  std::vector<float> values(kPfmValues, 0.5f);
  const std::string half = write_pfm(dir.path() / "half.pfm", values);
  int nans = 0;
  for (std::size_t i = 0; i < values.size(); i += 97) {
    values[i] = std::nanf("");
    ++nans;
  }
  const std::string nan = write_pfm(dir.path() / "nan.pfm", values);
  const fs::path json = dir.path() / "c.json";
  const CliResult r =
      run({"compare", nan, half, "--fail", "0", "--warn", "0", "--json", json.string()});
  CompareThresholds thresholds;
  thresholds.fail = 0;
  thresholds.warn = 0;
  const test::ToolRun idiff = test::run_idiff(nan, half, thresholds);
  INFO(r.out << r.err);
  CHECK(r.code == idiff.code);
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains(test::concat({"holds ", std::to_string(nans), " NaN"})));
  REQUIRE(fs::exists(json));
  const nlohmann::json report = nlohmann::json::parse(test::read_bytes(json));
  CHECK(report["non_finite"]["a"]["nan"] == nans);
  CHECK(report["non_finite"]["a"]["infinite"] == 0);
  CHECK(report["non_finite"]["b"]["nan"] == 0);
}

TEST_CASE("maxMemoryAcceptsUpToOneExbibyte", "[cli]") {
  // The range ends at 1E, but the parser knew units up to T: 1P and 1E were refused.
  test::TempDir dir("cli-max-memory");
  for (const char* size : {"1P", "1E"}) {
    const fs::path out = dir.path() / (std::string(size) + ".png");
    const CliResult r = render_small({"--max-memory", size, "-o", out.string()});
    INFO(size << ": " << r.err);
    CHECK(r.code == 0);
    CHECK(fs::exists(out));
  }
  const fs::path out = dir.path() / "2E.png";
  const CliResult r = render_small({"--max-memory", "2E", "-o", out.string()});
  INFO(r.err);
  CHECK(r.code == kExitBadInput);
  CHECK_THAT(r.err, Contains("--max-memory: '2E' is not a size from 1M to 1E"));
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("anAddressSpaceLimitEndsInAMessageNotASignal", "[cli]") {
  // Under ulimit -v 900000, error aborted on std::bad_alloc: its estimate did not read the
  // limit. compare must keep exiting 4 with a message under a limit too.
  const fs::path binary = test::relief_binary();
  if (binary.empty() || test::kSanitized) {
    // AddressSanitizer reserves terabytes of address space, so its build cannot run this.
    WARN("skipped: " << (test::kSanitized ? "a sanitizer build"
                                          : "no relief binary beside the tests"));
    return;
  }
  test::TempDir dir("cli-ulimit");
  const std::string big = (dir.path() / "big.png").string();
  REQUIRE(run({"render", "--set", "viewport.width=2048", "--set", "viewport.height=2048", "--set",
               "grid.width=64", "--set", "grid.height=64", "-o", big})
              .code == 0);
  const std::string pair = test::concat({"'", big, "' '", big, "'"});
  const test::Exit error = test::run_limited(binary, 900000, "error " + pair, dir.path());
  INFO(error.err);
  CHECK_FALSE(error.signalled);
  CHECK(error.code < 128);
  const bool refused =
      error.code == kExitBadInput && error.err.find("needs about") != std::string::npos;
  const bool out_of_memory =
      error.code == kExitOutputError && error.err.find("out of memory") != std::string::npos;
  CHECK((refused || out_of_memory));
  // OpenImageIO's libraries died of a signal before main under 387,000 to 449,000 KiB (their
  // static initialisers: log4cplus starting a thread). They are loaded only when a command needs
  // them now (tools/image_library.h), after a check of the address space left: every limit
  // from 20,000 KiB up ends in a message or a result.
  for (const long kib : {400000L, 500000L}) {
    const test::Exit compare = test::run_limited(binary, kib, "compare " + pair, dir.path());
    INFO(kib << " KiB: " << compare.err);
    CHECK_FALSE(compare.signalled);
    CHECK(compare.code == 4);
    CHECK_THAT(compare.err, Contains("relief: error"));
  }
  const test::Exit limited = test::run_limited(binary, 400000, "compare " + pair, dir.path());
  CHECK_THAT(limited.err, Contains("loading OpenImageIO needs about"));
  for (const char* command : {"--help", "info", "scene"}) {
    const test::Exit r = test::run_limited(binary, 400000, command, dir.path());
    INFO(command << ": " << r.err);
    CHECK_FALSE(r.signalled);
    CHECK(r.code == 0);
  }
}

TEST_CASE("crosscheckBadInputExits4", "[cli]") {
  // crosscheck exits as idiff does, where 2 means the images differ: bad input exited 2 and
  // read as a failed comparison. (An unwritable --out, exit 5, needs GL: the [gl] tests.)
  test::TempDir dir("cli-crosscheck");
  const fs::path out = dir.path() / "out";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"crosscheck", "--out", out.string(), "--repeat", "0"},
        std::vector<std::string>{"crosscheck", "no-such-preset", "--out", out.string()}}) {
    const CliResult r = run(args);
    INFO(args[1] << ": " << r.err);
    CHECK(r.code == 4);
    CHECK_THAT(r.err, Contains("relief: error:"));
    CHECK_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace relief

namespace relief {

TEST_CASE("aReportLostOnStandardOutputIsAnOutputThatCannotBeWritten", "[cli]") {
  const std::filesystem::path binary = test::relief_binary();
  if (binary.empty()) {
    WARN("skipped: no relief binary in this build");
    return;
  }
  test::TempDir dir("cli-stdout-full");
  // relief info said nothing and relief error exited 0 with its whole report lost.
  const test::Exit info = test::run_binary(binary, ":", "info >/dev/full", dir.path());
  CHECK(info.code == 1);
  CHECK_THAT(info.err, Catch::Contains("cannot write to standard output"));
  const test::Exit scene = test::run_binary(binary, ":", "scene >/dev/full", dir.path());
  CHECK(scene.code == 1);
  // compare's own code for what is not a comparison.
  const std::string png = (dir.path() / "a.png").string();
  REQUIRE(run({"render", "--set", "viewport.width=16", "--set", "viewport.height=16", "--set",
               "grid.width=8", "--set", "grid.height=8", "-o", png})
              .code == 0);
  const test::Exit compare =
      test::run_binary(binary, ":", "compare '" + png + "' '" + png + "' >/dev/full", dir.path());
  CHECK(compare.code == 4);
  CHECK_THAT(compare.err, Catch::Contains("cannot write to standard output"));
  // Also when the verdict was not a pass (3: the sizes differ): the report was lost all the
  // same.
  const std::string other = (dir.path() / "b.png").string();
  REQUIRE(run({"render", "--set", "viewport.width=16", "--set", "viewport.height=8", "--set",
               "grid.width=8", "--set", "grid.height=8", "-o", other})
              .code == 0);
  CHECK(test::run_binary(binary, ":", "compare '" + png + "' '" + other + "'", dir.path()).code ==
        3);
  const test::Exit differ =
      test::run_binary(binary, ":", "compare '" + png + "' '" + other + "' >/dev/full", dir.path());
  CHECK(differ.code == 4);
}

}  // namespace relief
