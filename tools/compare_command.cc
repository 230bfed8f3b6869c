// `relief compare A B`: two image files compared as OpenImageIO's idiff compares them, with
// idiff's thresholds, figures and exit codes (image_compare.h), a heat map of the differences
// and the report as JSON.
#include <cmath>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <system_error>

#include <CLI/CLI.hpp>

#include "core/scene/json_input.h"
#include "pipeline/memory_budget.h"
#include "tools/atomic_file.h"
#include "tools/commands.h"
#include "tools/compare_report.h"
#include "tools/distinct_paths.h"
#include "tools/image_file.h"

namespace relief {

namespace {

constexpr int kFileError = exit_code(CompareVerdict::kFileError);

// A threshold: a non-negative number, infinity allowed (idiff's hard thresholds default to it).
const CLI::Validator kThreshold(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || std::isnan(v) || v < 0) {
        return "'" + brief_text(text) + "' is not a number >= 0 (inf allowed)";
      }
      return "";
    },
    "NUMBER >= 0");

// A file name given empty ("") is an error, never "no file".
const CLI::Validator kFileName(
    [](std::string& text) -> std::string { return text.empty() ? "empty; give a file name" : ""; },
    "FILE");

const CLI::Validator kPngName(
    [](std::string& text) -> std::string {
      const bool png =
          text.size() >= 4 && CLI::detail::to_lower(text.substr(text.size() - 4)) == ".png";
      return png ? ""
                 : "'" + brief_text(text) +
                       "': the heat map is written as PNG; give a name ending in .png";
    },
    "FILE.png");

std::span<const unsigned char> bytes_of(const std::string& text) {
  return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

// The memory the comparison holds at its peak: both images as floats, and for the heat map
// their absolute difference, its largest channel (twice: OpenImageIO's and the copy), the
// colours (3 bytes a pixel) and their PNG (at most 13, pipeline/job_memory.cc).
MemoryEstimate compare_memory(const ImageFile& a, const ImageFile& b, bool heat_map) {
  MemoryEstimate estimate;
  estimate.add("image A as floats", a.float_bytes());
  estimate.add("image B as floats", b.float_bytes());
  if (heat_map) {
    const std::uintmax_t pixels = std::uintmax_t(a.width()) * std::uintmax_t(a.height());
    estimate.add("difference heat map", a.float_bytes() + pixels * (2 * 4 + 3 + 13));
  }
  return estimate;
}

int compare(const CompareOptions& options, std::ostream& out) {
  ImageFile a_file(options.a);
  ImageFile b_file(options.b);
  CompareReport report{options.a, options.b, nullptr, nullptr, options.thresholds, {}, {}, {}};
  FloatImage a, b;
  // Sizes first: different sizes are a verdict of their own (3), nothing is read.
  if (a_file.width() != b_file.width() || a_file.height() != b_file.height()) {
    report.result = compare_images(FloatImage{a_file.width(), a_file.height(), 0, {}, {}},
                                   FloatImage{b_file.width(), b_file.height(), 0, {}, {}}, {});
  } else if (a_file.channels() != b_file.channels()) {
    throw ImageFileError("cannot compare " + brief_text(options.a) + " (" +
                         std::to_string(a_file.channels()) + " channels) with " +
                         brief_text(options.b) + " (" + std::to_string(b_file.channels()) +
                         " channels): the images differ in their number of channels");
  } else {
    check_memory(compare_memory(a_file, b_file, !options.diff.empty()),
                 memory_budget(std::nullopt, ""), "comparing these images",
                 "Compare smaller images");
    a = a_file.read();
    b = b_file.read();
    report.a = &a;
    report.b = &b;
    report.a_non_finite = count_non_finite(a);
    report.b_non_finite = count_non_finite(b);
    report.result = compare_images(a, b, options.thresholds);
    if (report.result.verdict == CompareVerdict::kFileError) {
      throw ImageFileError(report.result.problem);
    }
  }
  OutputSet files;  // the heat map and the JSON appear together or not at all
  const bool compared = report.result.verdict != CompareVerdict::kSizeMismatch;
  if (!options.diff.empty() && compared) {
    files.add(options.diff,
              difference_heat_map_png(largest_channel_difference(a, b), a.width, a.height));
  }
  if (!options.json.empty()) {
    files.add(options.json, bytes_of(compare_report_json(report).dump(
                                         2, ' ', false, nlohmann::json::error_handler_t::replace) +
                                     "\n"));
  }
  files.commit();
  print_compare_report(out, report);
  if (!options.diff.empty() && compared) {
    out << "wrote " << options.diff << ": per pixel the largest channel difference, red at "
        << report.result.max_error << ", dark blue " << kHeatDecades
        << " decades below or less (logarithmic), black where equal\n";
  }
  return exit_code(report.result.verdict);
}

}  // namespace

void add_compare_thresholds(CLI::App* command, CompareThresholds& t) {
  const auto threshold = [&](const char* name, float& value, const char* what) {
    command->add_option(name, value, what)->check(kThreshold)->capture_default_str();
  };
  threshold("--fail", t.fail, "A channel differing by more than this makes its pixel fail");
  threshold("--failpercent", t.fail_percent, "Allow this percentage of the pixels to fail");
  threshold("--hardfail", t.hard_fail, "Fail if any one difference exceeds this");
  threshold("--warn", t.warn, "A channel differing by more than this makes its pixel warn");
  threshold("--warnpercent", t.warn_percent, "Allow this percentage of the pixels to warn");
  threshold("--hardwarn", t.hard_warn, "Warn if any one difference exceeds this");
}

CLI::App* add_compare_command(CLI::App& app, CompareOptions& options) {
  CLI::App* command = app.add_subcommand(
      "compare",
      "Compare two images (PNG, EXR, PFM, any format OpenImageIO reads) as OpenImageIO's idiff "
      "does: mean, RMS and largest difference, PSNR, pixels over the thresholds. Exit code "
      "as idiff's: 0 pass, 1 warning, 2 failure, 3 different sizes, 4 an image or option that "
      "cannot be used.");
  command->add_option("A", options.a, "First image file")->required()->check(kFileName);
  command->add_option("B", options.b, "Second image file")->required()->check(kFileName);
  add_compare_thresholds(command, options.thresholds);
  command
      ->add_option("--diff", options.diff,
                   "Write a heat map of the differences as a PNG file (logarithmic: red at "
                   "the largest difference, black where equal)")
      ->check(kFileName & kPngName);
  command->add_option("--json", options.json, "Write the report as a JSON file")->check(kFileName);
  return command;
}

int run_compare_command(const CompareOptions& options, std::ostream& out, std::ostream& err) {
  if (const std::optional<std::string> conflict =
          same_file_conflict({{"A", options.a, false},
                              {"B", options.b, false},
                              {"--diff", options.diff, true},
                              {"--json", options.json, true}})) {
    err << "relief: error: " << *conflict << "\n";
    return kFileError;
  }
  try {
    return compare(options, out);
  } catch (const ImageFileError& e) {
    err << "relief: error: " << e.what() << "\n";
  } catch (const MemoryLimitError& e) {
    err << "relief: error: " << e.what() << "\n";
  } catch (const OutputError& e) {
    err << "relief: error: " << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    err << "relief: error: out of memory comparing the images; nothing was written\n";
  } catch (const std::system_error& e) {
    // OpenImageIO's threads could not start (an address-space or process limit).
    err << "relief: error: cannot run the comparison: " << brief_text(e.what())
        << "; nothing was written\n";
  }
  return kFileError;
}

}  // namespace relief
