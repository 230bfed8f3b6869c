// Driving the command line in-process: run relief with arguments and collect its exit code and
// output, write input files, and check what every refused command must do.
#pragma once

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <catch2/catch.hpp>

#include "tools/cli.h"

namespace relief::test {

struct CliResult {
  int code;
  std::string out;
  std::string err;
};

inline CliResult run(std::vector<std::string> args) {
  args.insert(args.begin(), "relief");
  std::ostringstream out, err;
  const int code = run_cli(args, out, err);
  return {code, out.str(), err.str()};
}

inline std::string write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

inline std::vector<unsigned char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// a + b + ... (GCC 12 warns falsely about operator+ on a literal and a string: bug 105651).
inline std::string concat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (std::string_view part : parts) {
    out.append(part);
  }
  return out;
}

// `relief render PRESET --set S ... -o OUT` with the given leading arguments (a smaller size,
// say) before the scene's overrides.
inline CliResult render_preset(const std::string& preset, const std::vector<std::string>& sets,
                               const std::filesystem::path& out,
                               const std::vector<std::string>& leading = {}) {
  std::vector<std::string> args = {"render", preset};
  args.insert(args.end(), leading.begin(), leading.end());
  for (const std::string& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  args.push_back("-o");
  args.push_back(out.string());
  return run(args);
}

// A command that must succeed: its error output shown if it did not.
inline void require_ok(const CliResult& r) {
  INFO(r.err);
  REQUIRE(r.code == 0);
}

// The checks every refused command must pass: exit 2, an error message naming the problem,
// and `out` not written.
inline void require_refused(const CliResult& r, const std::string& message,
                            const std::filesystem::path& out) {
  INFO(r.err);
  CHECK(r.code == kExitBadInput);
  CHECK_THAT(r.err, Catch::Matchers::Contains("relief: error:"));
  CHECK_THAT(r.err, Catch::Matchers::Contains(message));
  CHECK_FALSE(std::filesystem::exists(out));
}

}  // namespace relief::test
