// Running Debian's idiff (openimageio-tools, OpenImageIO 2.4) beside relief compare, and reading
// the report both print (tools/compare_report.h prints idiff's lines).
#pragma once

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "tests/support/cli_support.h"
#include "tools/image_compare.h"

#ifndef RELIEF_IDIFF
#error "RELIEF_IDIFF (the idiff program) is set by tests/CMakeLists.txt"
#endif

namespace relief::test {

struct ToolRun {
  int code = -1;
  std::string out;
};

// The figures of a report, as printed.
struct PrintedFigures {
  std::string mean, rms, psnr, max;
  std::string max_at;                // "(x, y, C)", empty when the largest difference is 0
  std::string warn_line, fail_line;  // "N pixels (P%) over T"
  std::string verdict;               // the last line
};

// `threshold` as idiff's float option reads it back exactly.
inline std::string option_value(float threshold) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(threshold));
  return text;
}

// idiff -v (figures printed whatever the verdict) with the same thresholds. The test fails,
// not skips, without idiff: `make test` installs openimageio-tools.
inline ToolRun run_idiff(const std::filesystem::path& a, const std::filesystem::path& b,
                         const CompareThresholds& t) {
  const std::filesystem::path idiff = RELIEF_IDIFF;
  if (!std::filesystem::exists(idiff)) {
    FAIL("idiff is missing (" << idiff.string()
                              << "): install Debian's openimageio-tools (make deps does)");
  }
  std::string command = concat({"'", idiff.string(), "' -v"});
  const std::vector<std::pair<const char*, float>> options = {
      {"-fail", t.fail}, {"-failpercent", t.fail_percent}, {"-hardfail", t.hard_fail},
      {"-warn", t.warn}, {"-warnpercent", t.warn_percent}, {"-hardwarn", t.hard_warn}};
  for (const auto& [name, value] : options) {
    if (std::isfinite(value)) {
      command += concat({" ", name, " ", option_value(value)});
    }
  }
  command += concat({" '", a.string(), "' '", b.string(), "' 2>/dev/null"});
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  ToolRun run;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) {
    run.out.append(buffer, n);
  }
  const int status = ::pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

inline std::optional<std::string> after(const std::string& line, const std::string& prefix) {
  return line.rfind(prefix, 0) == 0 ? std::optional(line.substr(prefix.size())) : std::nullopt;
}

inline PrintedFigures parse_report(const std::string& out) {
  PrintedFigures f;
  std::istringstream lines(out);
  std::vector<std::string> over;
  const auto take = [](const std::string& line, const std::string& prefix, std::string& field) {
    const std::optional<std::string> value = after(line, prefix);
    if (value) {
      field = *value;
    }
    return value.has_value();
  };
  for (std::string line; std::getline(lines, line);) {
    std::string max;
    if (take(line, "  Mean error = ", f.mean) || take(line, "  RMS error = ", f.rms) ||
        take(line, "  Peak SNR = ", f.psnr)) {
      continue;
    }
    if (take(line, "  Max error  = ", max)) {
      const std::size_t at = max.find(" @ ");
      f.max = max.substr(0, at);
      if (at != std::string::npos) {
        f.max_at = max.substr(at + 3, max.find(')', at) - at - 2);
      }
    } else if (line.find(" pixels (") != std::string::npos &&
               line.find("%) over ") != std::string::npos) {
      over.push_back(line);
    } else if (line == "PASS" || line == "WARNING" || line == "FAILURE" ||
               line == "SIZE MISMATCH") {
      f.verdict = line;
    }
  }
  if (over.size() == 2) {
    f.warn_line = over[0];
    f.fail_line = over[1];
  }
  return f;
}

// `value` equals `printed` (%g, six significant digits) to the printed precision: within half
// a unit of its last digit.
inline bool agrees_to_printed_precision(double value, const std::string& printed) {
  if (printed == "inf") {
    return std::isinf(value) && value > 0;
  }
  if (printed == "nan") {
    return std::isnan(value);
  }
  const double shown = std::stod(printed);
  if (shown == 0) {
    return value == 0;
  }
  const double unit = std::pow(10.0, std::floor(std::log10(std::abs(shown))) - 5);
  return std::abs(value - shown) <= 0.5 * unit * (1 + 1e-9);
}

}  // namespace relief::test
