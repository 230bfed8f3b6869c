// `relief generate METHOD --size N -o FILE` (docs/heightfields.md): a height map by one of the
// seeds' generators (core/heightfield/): triangle-edge, diamond-square and square-square
// subdivision (Miller 1986), or Perlin noise (Mekala), optionally smoothed, written as a 16-bit
// grey PNG, a float PFM or EXR, or RAW16; with its creasing measured (a figure and a heat map).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "pipeline/memory_budget.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace relief {

inline constexpr int kMaxGeneratedSize = 16385;  // 2^14 + 1

struct GenerateOptions {
  std::string method;
  int size = 513;
  std::uint64_t seed = 1;
  double roughness = 0.8;
  double amplitude = 1000.0;
  int smooth = 0;
  int cells = 4;  // Perlin: the first octave's cells across the map
  std::string output;
  std::string creases;  // heat map PNG of the second differences (empty: none)
  std::string json;     // the figures (empty: none)
  MemoryBudget budget;
  const CLI::Option* output_option = nullptr;  // to tell an empty name given from none
  const CLI::Option* creases_option = nullptr;
  const CLI::Option* json_option = nullptr;
};

CLI::App* add_generate_command(CLI::App& app, GenerateOptions& options);

// Returns an exit code; bad options are reported on `err` (2, nothing written). Throws
// MemoryLimitError when the map does not fit options.budget, OutputError when a file cannot be
// written.
int run_generate_command(const GenerateOptions& options, std::ostream& out, std::ostream& err);

}  // namespace relief
