// Debian's gnuplot (package gnuplot-nox) run as an external program to draw a PNG: the script
// is written to a private temporary directory and run as `gnuplot -c SCRIPT OUTPUT.png` with
// a fixed argument vector (posix_spawnp, no shell), so no path is ever interpolated into a
// command line or into the script; the script reads its output's name from ARG1.
#pragma once

#include <string>
#include <vector>

namespace relief {

struct GnuplotResult {
  enum class Status {
    kDrawn,    // png holds the image
    kMissing,  // no gnuplot on PATH
    kFailed,   // gnuplot ran and failed, or wrote nothing: message says how
  };
  Status status = Status::kFailed;
  std::vector<unsigned char> png;
  std::string message;
};

// Runs `script` (which must `set output ARG1`). Never throws for gnuplot's own failures.
GnuplotResult run_gnuplot(const std::string& script);

}  // namespace relief
