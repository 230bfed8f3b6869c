// `relief error TEST REFERENCE [--map OUT.png] [--json FILE]`: the error of a render against a
// reference (eval/image_error.h): PSNR, RMSE and the largest difference of the display
// values, and LDR-FLIP's mean and heat map. This file reads the images and writes the outputs.
#include <cmath>
#include <iomanip>
#include <new>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/scene/json_input.h"
#include "core/srgb.h"
#include "eval/image_error.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/colormap.h"
#include "tools/distinct_paths.h"
#include "tools/image_file.h"
#include "tools/reference_command.h"

namespace relief {

namespace {

// An image as linear radiance RGB, top row first: PNG is sRGB-encoded (decoded here); EXR and
// PFM hold linear radiance (relief render --float, relief reference).
std::vector<float> linear_rgb(ImageFile& file, const std::string& path) {
  const std::string format = file.format();
  const bool png = format == "png";
  if (!png && format != "openexr" && !has_extension(path, ".pfm")) {
    throw ImageFileError(brief_text(path) + " is a " + format +
                         " image; relief error reads PNG (sRGB), EXR or PFM (linear radiance)");
  }
  if (file.channels() < 3) {
    throw ImageFileError(brief_text(path) + " has " + std::to_string(file.channels()) +
                         " channel(s); relief error compares RGB images (3 or 4 channels)");
  }
  const FloatImage image = file.read();
  // NaN or infinity is no radiance: clamped to the display's range it would pass as black or
  // white and hide the defect the comparison is for.
  if (const NonFiniteCount bad = count_non_finite(image); bad.total() > 0) {
    throw ImageFileError(brief_text(path) + " holds " + bad.describe() +
                         "; relief error measures finite radiance only");
  }
  const std::size_t pixels = std::size_t(image.width) * image.height;
  std::vector<float> rgb(3 * pixels);
  for (std::size_t k = 0; k < pixels; ++k) {
    for (int c = 0; c < 3; ++c) {
      const float v = image.pixels[k * image.channels + c];
      rgb[3 * k + c] = png ? static_cast<float>(srgb_decode(v)) : v;  // PNG: v in [0, 1]
    }
  }
  return rgb;
}

std::vector<unsigned char> flip_map_png(const std::vector<float>& map, int width, int height) {
  std::vector<std::uint8_t> rgb(3 * map.size());
  for (int y = 0; y < height; ++y) {
    const std::size_t source = std::size_t(y) * width;
    const std::size_t target = std::size_t(height - 1 - y) * width;  // the encoder's bottom-up
    for (int x = 0; x < width; ++x) {
      const Rgb8 c = magma_color(map[source + x]);
      for (int k = 0; k < 3; ++k) {
        rgb[3 * (target + x) + k] = c[k];
      }
    }
  }
  return encode_png_rgb(width, height, rgb, software_metadata());
}

nlohmann::json error_json(const ErrorOptions& o, const ImageError& e, int width) {
  return {{"test", o.test},
          {"reference", o.reference},
          {"values", "sRGB-encoded display values, each channel clamped to [0, 1]"},
          {"pixels_per_degree", o.pixels_per_degree},
          {"rmse", e.rmse},
          {"psnr_db", std::isinf(e.psnr_db) ? nlohmann::json(nullptr) : nlohmann::json(e.psnr_db)},
          {"max_error", e.max_error},
          {"max_pixel",
           {{"x", e.max_pixel % std::size_t(width)},
            {"y", e.max_pixel / std::size_t(width)},
            {"channel", e.max_channel}}},
          {"mean_flip", e.mean_flip}};
}

int error(const ErrorOptions& options, std::ostream& out) {
  ImageFile test_file(options.test);
  ImageFile reference_file(options.reference);
  const int width = test_file.width(), height = test_file.height();
  if (width != reference_file.width() || height != reference_file.height()) {
    throw ImageFileError("cannot compare " + brief_text(options.test) + " (" +
                         std::to_string(width) + "x" + std::to_string(height) + ") with " +
                         brief_text(options.reference) + " (" +
                         std::to_string(reference_file.width()) + "x" +
                         std::to_string(reference_file.height()) + "): the sizes differ");
  }
  MemoryEstimate estimate;
  const std::uintmax_t pixels = std::uintmax_t(width) * std::uintmax_t(height);
  estimate.add("images as floats", test_file.float_bytes() + reference_file.float_bytes());
  estimate.add("linear RGB copies", 2 * 12 * pixels);
  estimate.add("FLIP", image_error_bytes(width, height));
  estimate.add("heat map", options.map.empty() ? 0 : pixels * (3 + 13));
  check_memory(estimate, options.budget, "this comparison", "Compare smaller images");

  const std::vector<float> test = linear_rgb(test_file, options.test);
  const std::vector<float> reference = linear_rgb(reference_file, options.reference);
  const ImageError e = image_error(test, reference, width, height, options.pixels_per_degree);

  OutputSet files;  // the map and the JSON appear together or not at all
  if (!options.map.empty()) {
    files.add(options.map, flip_map_png(e.flip_map, width, height));
  }
  std::string json_text;
  if (!options.json.empty()) {
    json_text = error_json(options, e, width)
                    .dump(2, ' ', false, nlohmann::json::error_handler_t::replace) +
                "\n";
    files.add(options.json,
              std::span<const unsigned char>(
                  reinterpret_cast<const unsigned char*>(json_text.data()), json_text.size()));
  }
  files.commit();

  out << brief_text(options.test) << " against " << brief_text(options.reference) << ", " << width
      << "x" << height << " (sRGB display values in [0, 1]):\n"
      << std::setprecision(6) << "  PSNR      " << e.psnr_db << " dB\n"
      << "  RMSE      " << e.rmse << "\n"
      << "  max       " << e.max_error << " at (" << e.max_pixel % std::size_t(width) << ", "
      << e.max_pixel / std::size_t(width) << ") channel " << e.max_channel << "\n"
      << "  mean FLIP " << e.mean_flip << " (LDR-FLIP at " << options.pixels_per_degree
      << " pixels per degree)\n";
  if (!options.map.empty()) {
    out << "wrote " << options.map << ": FLIP per pixel, black 0 to pale yellow 1 (magma)\n";
  }
  return kExitOk;
}

// An output named empty (--map "") is an error, never "no file".
const CLI::Validator kNonEmpty(
    [](std::string& text) -> std::string { return text.empty() ? "empty; give a file name" : ""; },
    "FILE");

}  // namespace

CLI::App* add_error_command(CLI::App& app, ErrorOptions& options) {
  CLI::App* command = app.add_subcommand(
      "error",
      "The error of a render against a reference (relief reference): PSNR, RMSE and the "
      "largest difference of the sRGB display values, and the mean of NVIDIA's LDR-FLIP "
      "perceptual error, with its heat map. PNG is read as sRGB, EXR and PFM as linear "
      "radiance.");
  command->add_option("TEST", options.test, "The render to judge")->required();
  command->add_option("REFERENCE", options.reference, "The reference")->required();
  command->add_option("--map", options.map, "Write FLIP's per-pixel error as a PNG heat map")
      ->check(kNonEmpty);
  command->add_option("--json", options.json, "Write the figures as a JSON file")->check(kNonEmpty);
  command
      ->add_option("--ppd", options.pixels_per_degree,
                   "FLIP's pixels per degree of the viewing set-up (1-1000; default: a 0.7 m "
                   "wide 4K monitor seen from 0.7 m)")
      ->capture_default_str();
  return command;
}

int run_error_command(const ErrorOptions& options, std::ostream& out, std::ostream& err) {
  for (const auto& [name, value] :
       {std::pair{"TEST", &options.test}, std::pair{"REFERENCE", &options.reference}}) {
    if (value->empty()) {
      err << "relief: error: " << name << " is empty; give an image file\n";
      return kExitBadInput;
    }
  }
  if (!options.map.empty() && !has_extension(options.map, ".png")) {
    err << "relief: error: --map " << brief_text(options.map)
        << ": the heat map is written as PNG; give a file name ending in .png\n";
    return kExitBadInput;
  }
  if (const std::optional<std::string> conflict =
          same_file_conflict({{"TEST", options.test, false},
                              {"REFERENCE", options.reference, false},
                              {"--map", options.map, true},
                              {"--json", options.json, true}})) {
    err << "relief: error: " << *conflict << "\n";
    return kExitBadInput;
  }
  // NaN fails both comparisons.
  if (!(options.pixels_per_degree >= kMinPixelsPerDegree &&
        options.pixels_per_degree <= kMaxPixelsPerDegree)) {
    err << "relief: error: --ppd " << options.pixels_per_degree
        << " is out of range; allowed 1...1000 pixels per degree\n";
    return kExitBadInput;
  }
  try {
    return error(options, out);
  } catch (const ImageFileError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const MemoryLimitError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const OutputError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitOutputError;
  } catch (const std::bad_alloc&) {
    // The estimate missed (another process took the memory meanwhile).
    err << "relief: error: out of memory comparing the images; nothing was written\n";
    return kExitOutputError;
  } catch (const std::system_error& e) {
    // Threads that could not start (an address-space limit, a process limit).
    err << "relief: error: cannot run the comparison: " << brief_text(e.what())
        << "; nothing was written\n";
    return kExitOutputError;
  }
}

}  // namespace relief
