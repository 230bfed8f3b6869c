#include "tools/generate_command.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <optional>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/heightfield/creases.h"
#include "core/heightfield/perlin_field.h"
#include "core/heightfield/smoothing.h"
#include "core/heightfield/subdivision.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "image/image_io.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/colormap.h"
#include "tools/distinct_paths.h"
#include "tools/float_image_file.h"
#include "tools/height_file.h"
#include "tools/terminal_progress.h"

namespace relief {

namespace {

// A figure to read: six significant digits.
std::string six_digits(double value) {
  std::ostringstream text;
  text << std::setprecision(6) << value;
  return text.str();
}

// The lines of the first levels, where subdivision creases lie (creases.h).
constexpr int kCreaseLevels = 3;

// The map's N x N heights (N = side + 1, the first row and column repeated last so that the
// file tiles), row 0 = z0.
std::vector<float> tiled_heights(const PeriodicGrid& g) {
  const int n = g.side + 1;
  std::vector<float> out(std::size_t(n) * std::size_t(n));
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {
      out[std::size_t(z) * std::size_t(n) + std::size_t(x)] = g.at(x, z);
    }
  }
  return out;
}

// The crease map as a magma heat map, scaled to its 99th percentile (a few extreme points would
// otherwise leave the rest black).
std::vector<unsigned char> crease_picture(const PeriodicGrid& g) {
  const std::vector<float> map = crease_map(g);
  std::vector<float> sorted = map;
  const std::size_t rank = sorted.size() * 99 / 100;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(rank), sorted.end());
  const double top = sorted[rank];
  const int n = g.side;
  std::vector<std::uint8_t> rgb(3 * map.size());
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {  // rgb row 0 = the bottom row: z = n - 1
      const double t = top > 0 ? map[g.index(x, z)] / top : 0.0;
      const Rgb8 c = magma_color(t);
      std::memcpy(&rgb[3 * (std::size_t(n - 1 - z) * std::size_t(n) + std::size_t(x))], c.data(),
                  3);
    }
  }
  return encode_png_rgb(n, n, rgb);
}

}  // namespace

CLI::App* add_generate_command(CLI::App& app, GenerateOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Generate a height map: triangle-edge, diamond-square or square-square subdivision "
      "(Miller 1986) or Perlin noise, deterministic from the seed, tileable; written as a 16-bit "
      "PNG (the range in its text), PFM, EXR or RAW16 (.r16), with its creasing measured");
  cmd->add_option("METHOD", o.method, "triangle-edge, diamond-square, square-square or perlin")
      ->required();
  cmd->add_option("--size", o.size,
                  "Samples a side, 2^k + 1 from 3 to " + std::to_string(kMaxGeneratedSize) +
                      " (the last row and column repeat the first: the map tiles)")
      ->transform(integer_in(INT_MIN, INT_MAX))
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Seed of the random displacements (0 to 2^64 - 1)")
      // In digits and within 64 bits: CLI11 wrapped -1 and 2^64 around without a word.
      ->transform(CLI::Validator(
          [](std::string& text) {
            std::uint64_t value = 0;
            const auto [end, error] =
                std::from_chars(text.data(), text.data() + text.size(), value);
            if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
              return "'" + brief_text(text, 40) +
                     "' is not a whole number from 0 to 18446744073709551615";
            }
            text = std::to_string(value);  // decimal as read here: CLI11 reads "017" as octal
            return std::string();
          },
          "SEED"))
      ->capture_default_str();
  cmd->add_option("--roughness", o.roughness,
                  "H, 0 to 2: the displacement at spacing d is amplitude d^H (d in units of the "
                  "map's side); lower is rougher")
      ->check(kNonEmptyNumber)
      ->capture_default_str();
  cmd->add_option("--amplitude", o.amplitude,
                  "Standard deviation of the coarsest displacement (Perlin: the first octave's "
                  "amplitude), in height units, 0 to 1e7")
      ->check(kNonEmptyNumber)
      ->capture_default_str();
  cmd->add_option("--smooth", o.smooth, "Smoothing passes of [1 2 1] / 4 along x and z, 0 to 64")
      ->transform(integer_in(INT_MIN, INT_MAX))
      ->capture_default_str();
  cmd->add_option("--cells", o.cells,
                  "perlin: the first octave's cells across the map, a power of two up to "
                  "(size - 1) / 2")
      ->transform(integer_in(INT_MIN, INT_MAX))
      ->capture_default_str();
  o.output_option = cmd->add_option("-o,--output", o.output,
                                    "The map: .png (16-bit grey), .pfm, .exr or .r16 (RAW16)")
                        ->required();
  o.creases_option =
      cmd->add_option("--creases", o.creases,
                      "Also write the second differences (Miller's creases) as a heat map PNG");
  o.json_option =
      cmd->add_option("--json", o.json, "Also write the figures (range, creasing) as JSON");
  return cmd;
}

int run_generate_command(const GenerateOptions& o, std::ostream& out, std::ostream& err) {
  const auto refuse = [&](const std::string& message) {
    err << "relief: error: " << message << "\n";
    return kExitBadInput;
  };
  for (const auto& [option, value] :
       {std::pair{o.output_option, &o.output}, std::pair{o.creases_option, &o.creases},
        std::pair{o.json_option, &o.json}}) {
    if (given_empty(option, *value)) {
      return refuse(option->get_name() + " is empty; give a file name");
    }
  }
  std::optional<Subdivision> method;
  for (const Subdivision m :
       {Subdivision::kTriangleEdge, Subdivision::kDiamondSquare, Subdivision::kSquareSquare}) {
    if (o.method == subdivision_name(m)) {
      method = m;
    }
  }
  if (!method && o.method != "perlin") {
    return refuse("METHOD " + brief_text(o.method) +
                  " is not a generator; allowed triangle-edge, diamond-square, square-square, "
                  "perlin");
  }
  const int side = o.size - 1;
  if (o.size < 3 || o.size > kMaxGeneratedSize || !std::has_single_bit(unsigned(side))) {
    return refuse("--size " + std::to_string(o.size) +
                  " is out of range; allowed 2^k + 1 from 3 to " +
                  std::to_string(kMaxGeneratedSize) + " (3, 5, 9, 17, ..., 8193, 16385)");
  }
  if (!(o.roughness >= 0.0 && o.roughness <= 2.0)) {
    return refuse("--roughness " + format_number(o.roughness) + " is out of range; allowed 0 to 2");
  }
  if (!(o.amplitude >= 0.0 && o.amplitude <= 1e7)) {
    return refuse("--amplitude " + format_number(o.amplitude) +
                  " is out of range; allowed 0 to 1e7");
  }
  if (o.smooth < 0 || o.smooth > 64) {
    return refuse("--smooth " + std::to_string(o.smooth) + " is out of range; allowed 0 to 64");
  }
  if (!method &&  // Perlin's alone
      (o.cells < 1 || o.cells > side / 2 || !std::has_single_bit(unsigned(o.cells)))) {
    return refuse("--cells " + std::to_string(o.cells) +
                  " is out of range; allowed a power of two from 1 to " + std::to_string(side / 2) +
                  " for --size " + std::to_string(o.size));
  }
  const std::optional<HeightFormat> format = height_format(o.output);
  if (!format || *format == HeightFormat::kGeoTiff) {  // a generated map has no place
    return refuse("-o " + brief_text(o.output) +
                  ": give a file name ending in .png (16-bit grey), .pfm, .exr or .r16");
  }
  if (!o.creases.empty() && !has_extension(o.creases, ".png")) {
    return refuse("--creases " + brief_text(o.creases) + ": give a file name ending in .png");
  }
  std::vector<CommandPath> paths{{"-o", o.output}};
  if (!o.creases.empty()) {
    paths.push_back({"--creases", o.creases});
  }
  if (!o.json.empty()) {
    paths.push_back({"--json", o.json});
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    return refuse(*conflict);
  }
  for (const CommandPath& path : paths) {  // before the work, not after it
    if (const std::optional<std::string> problem = output_path_problem(path.path)) {
      return refuse(path.option + " " + *problem);
    }
  }
  // The grid (square-square keeps the level before too), the file's encoding (at most 2 x 4
  // bytes a sample with a float format's buffers), the crease map and its picture.
  const double amplitude = o.amplitude + 0.0;  // -0 as 0: the figures say 0
  const std::uintmax_t samples = std::uintmax_t(o.size) * std::uintmax_t(o.size);
  MemoryEstimate estimate;
  estimate.add("the height map",
               4 * samples + (method == Subdivision::kSquareSquare ? samples : 0));
  estimate.add("its file's encoding", 12 * samples);
  if (!o.creases.empty()) {
    estimate.add("the crease map and its picture", (4 + 4 + 3 + 4) * samples);
  }
  check_memory(estimate, o.budget, "generating this height map", "Lower --size");

  TerminalProgress progress("relief generate", method ? "levels" : "octaves");
  const auto report = [&](int done, int total) { progress.update(done, total); };
  const int levels = std::countr_zero(unsigned(side));
  // The map, and its interpolant: the same first kCreaseLevels random levels, then
  // subdivision alone, whose creases are the method's own (Miller's test).
  const auto make = [&](int random_levels, bool progress_shown) {
    PeriodicGrid g;
    std::function<void(int, int)> shown;
    if (progress_shown) {
      shown = report;
    }
    if (method) {
      PeriodicGrid coarse(1);  // one control point at height 0
      g = subdivide(coarse, {*method, levels, amplitude, o.roughness, o.seed, random_levels},
                    shown);
    } else {
      g = perlin_field({side, o.cells, amplitude, o.roughness, o.seed, random_levels}, shown);
    }
    if (progress_shown && o.smooth > 0) {
      progress.finish();
      TerminalProgress smoothing("relief generate: smoothing", "passes");
      smooth_height_map(g, o.smooth, [&](int done, int total) { smoothing.update(done, total); });
      smoothing.finish();
    } else {
      smooth_height_map(g, o.smooth);
    }
    return g;
  };
  const PeriodicGrid grid = make(1 << 30, true);
  progress.finish();
  // Subdivision alone has an interpolant to judge (Perlin's octaves are not subdivision).
  const PeriodicGrid interpolant = method ? make(kCreaseLevels, false) : PeriodicGrid();

  const auto [low_it, high_it] = std::minmax_element(grid.heights.begin(), grid.heights.end());
  const double low = *low_it, high = *high_it;
  const double ratio = crease_ratio(grid, kCreaseLevels);
  const double largest = largest_second_difference(grid);
  const double interpolant_ratio = method ? crease_ratio(interpolant, kCreaseLevels) : 0.0;
  nlohmann::ordered_json figures = {
      {"method", o.method},
      {"size", o.size},
      {"seed", o.seed},
      {"roughness", o.roughness},
      {"amplitude", amplitude},
      {"smooth", o.smooth},
      {"low", low},
      {"high", high},
      {"crease_ratio", ratio},
      {"largest_second_difference", largest},
      {"interpolant_crease_ratio", method ? nlohmann::ordered_json(interpolant_ratio) : nullptr}};
  if (!method) {
    figures["cells"] = o.cells;
  }
  // The PNG and RAW16 hold levels: the text says which heights 0 and 65535 stand for (the
  // numbers for terrain.sketch.height).
  const std::vector<ImageText> text = {{"relief:heights", figures.dump()}};
  // An encoder returns nothing only when it ran out of memory: no empty file written for it.
  const auto encoded = [](const std::string& file, std::vector<unsigned char> bytes) {
    if (bytes.empty()) {
      throw OutputError(file + ": the file could not be encoded (out of memory)");
    }
    return bytes;
  };
  OutputSet files;
  files.add(o.output, encoded(o.output, encode_heights(*format, grid.side + 1, grid.side + 1,
                                                       tiled_heights(grid), low, high, text)));
  if (!o.creases.empty()) {
    files.add(o.creases, encoded(o.creases, crease_picture(method ? interpolant : grid)));
  }
  std::string json_text;
  if (!o.json.empty()) {
    json_text = figures.dump(2) + "\n";
    files.add(o.json,
              std::span<const unsigned char>(
                  reinterpret_cast<const unsigned char*>(json_text.data()), json_text.size()));
  }
  files.commit();
  out << std::setprecision(6) << "generated " << o.method << " " << o.size << "x" << o.size << " ("
      << (method ? std::to_string(levels) + " levels" : "Perlin") << ", seed " << o.seed
      << ", roughness " << o.roughness << ", smoothing " << o.smooth << "): heights " << low
      << " to " << high << "\n"
      << "  creasing: mean second difference across the first " << kCreaseLevels
      << " levels' lines " << ratio << " x the mean everywhere; largest second difference "
      << largest << "\n"
      << (method ? "  the interpolant of the first " + std::to_string(kCreaseLevels) +
                       " random levels: " + six_digits(interpolant_ratio) + " x"
                 : std::string("  (Perlin noise is not subdivision: no interpolant)"))
      << (o.creases.empty() ? ""
                            : std::string(" (") + (method ? "its" : "the map's") +
                                  " second differences: " + o.creases + ")")
      << "\n"
      << "wrote " << o.output << (o.creases.empty() ? "" : " and " + o.creases) << "\n";
  return kExitOk;
}

}  // namespace relief
