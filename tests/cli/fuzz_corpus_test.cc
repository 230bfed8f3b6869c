// The fuzzers' seed corpora (fuzz/corpus/TARGET/) and regression inputs (fuzz/regressions/)
// replayed through the fuzzers' own per-input functions (fuzz/fuzz_inputs.h) in the ordinary
// build, without libFuzzer: every file is either accepted with its properties intact or refused
// with the exit-2 error, and each corpus holds inputs that are accepted (so that a change that
// refuses them all shows here, not as a fuzzer that quietly explores nothing).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "fuzz/fuzz_inputs.h"
#include "tests/support/cli_support.h"

namespace relief {
namespace {

const std::filesystem::path kFuzzDir = std::filesystem::path(RELIEF_SOURCE_DIR) / "fuzz";

// Replays every file of `folder` whose name starts with `prefix`; returns how many were
// accepted.
int replay(const std::filesystem::path& folder, const std::string& prefix,
           const std::function<bool(std::string_view)>& input) {
  REQUIRE(std::filesystem::is_directory(folder));
  int accepted = 0, files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().filename().string().rfind(prefix, 0) != 0) {
      continue;
    }
    INFO(entry.path().string());
    const std::vector<unsigned char> file = test::read_bytes(entry.path());
    const std::string bytes(file.begin(), file.end());
    bool ok = false;
    CHECK_NOTHROW(ok = input(bytes));
    accepted += ok;
    ++files;
  }
  CHECK(files > 0);
  return accepted;
}

TEST_CASE("fuzzSeedCorporaReplayCleanly", "[fuzz]") {
  const std::vector<std::pair<std::string, std::function<bool(std::string_view)>>> targets = {
      {"scene", fuzz::scene_input},
      {"override", fuzz::override_input},
      {"soup", fuzz::soup_input},
      {"texture", fuzz::texture_input}};
  for (const auto& [target, input] : targets) {
    INFO("fuzz/corpus/" << target);
    CHECK(replay(kFuzzDir / "corpus" / target, "", input) > 0);
  }
}

TEST_CASE("fuzzRegressionInputsAreRefusedCleanly", "[fuzz]") {
  CHECK(replay(kFuzzDir / "regressions", "texture_", fuzz::texture_input) == 0);
}

}  // namespace
}  // namespace relief
