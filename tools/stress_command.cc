// relief stress: the stability stress suite of eval/stress_run.h as a table, with progress
// on a terminal.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "eval/process_memory.h"
#include "eval/stress_run.h"
#include "pipeline/job_memory.h"
#include "pipeline/memory_budget.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/stress_sheet.h"

namespace relief {

namespace {

std::string mib(std::uintmax_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", double(bytes) / 1048576.0);
  return text;
}

// `value` with `digits` decimals, fixed or scientific.
std::string decimal(double value, int digits, bool scientific = false) {
  std::ostringstream text;
  text << (scientific ? std::scientific : std::fixed) << std::setprecision(digits) << value;
  return text.str();
}

// One line of the table; refusal and skip messages go to numbered notes below it.
void print_row(std::ostream& out, const StressRow& row, std::vector<std::string>& notes) {
  std::string status = "ok";
  if (row.status != StressStatus::kOk) {
    notes.push_back(row.message);
    status = std::string(row.status == StressStatus::kRefused ? "refused" : "skipped") + " [" +
             std::to_string(notes.size()) + "]";
  }
  const bool ran = row.status == StressStatus::kOk;
  const auto opt = [](const std::optional<double>& v, int digits, bool scientific = false) {
    return v ? decimal(*v, digits, scientific) : std::string("-");
  };
  char line[512];
  std::snprintf(
      line, sizeof line, "%-9s %-44.44s %-16s %-12s %9s %10s %7s %9s %9s %9s %7s %7s",
      row.axis.c_str(), row.name.c_str(), row.backend.c_str(), status.c_str(),
      ran ? decimal(row.frame_ms, 1).c_str() : "-", ran ? std::to_string(row.values).c_str() : "-",
      ran ? std::to_string(row.nonfinite).c_str() : "-",
      row.estimate_bytes ? mib(row.estimate_bytes).c_str() : "-",
      row.measured_bytes ? mib(*row.measured_bytes).c_str() : "-",
      opt(row.height_error, 2, true).c_str(),
      opt(row.srgb_share ? std::optional<double>(100 * *row.srgb_share) : std::nullopt, 2).c_str(),
      opt(row.psnr_db, 1).c_str());
  out << line;
  for (const std::string& failure : row.failures) {
    out << "  FAIL: " << failure;
  }
  out << "\n";
}

}  // namespace

CLI::App* add_stress_command(CLI::App& app, StressOptions& options) {
  CLI::App* command = app.add_subcommand(
      "stress",
      "Run the stability stress suite: the scene pushed to the ends of every axis the float "
      "pipeline is sensitive to (camera distance and altitude, pitch, camera inside the "
      "terrain or under water, warping, H, r, octaves, grid and viewport sizes), on every "
      "backend; prints a table of NaN/inf counts, memory (estimate and measured peak) and the "
      "float error against reference-double. Exit 0 when every check holds, 1 otherwise.");
  command
      ->add_option("--viewport", options.viewport,
                   "WIDTH HEIGHT of the base scene (default 640 512; the viewport axis sets its "
                   "own)")
      ->expected(2)
      ->transform(integer_in(1, 16384));
  command->add_option("--grid", options.grid_side, "Grid side of the base scene (default 256)")
      ->transform(integer_in(6, 8192));
  std::string names;
  for (std::string_view name : backend_names()) {
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  command
      ->add_option("--backend", options.backends,
                   "Run only this backend (repeatable): " + names + ". Default: every one")
      ->check(CLI::IsMember(backend_names()));
  const std::vector<std::string> axes = stress_axes();
  std::string axis_names;
  for (const std::string& axis : axes) {
    axis_names += (axis_names.empty() ? "" : ", ") + axis;
  }
  command->add_option("--axis", options.axes, "Run only this axis (repeatable): " + axis_names)
      ->check(CLI::IsMember(axes));
  command
      ->add_option("--max-memory", options.max_memory,
                   "Budget of the largest grid and viewport cases (default 1G, at most the "
                   "memory available); larger ones must be refused by the memory estimate")
      ->type_name("SIZE")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return parse_memory_size(text)
                       ? ""
                       : "'" + brief_text(text) +
                             "' is not a size from 1M to 1E, such as 512M or 2G";
          },
          "SIZE"));
  command
      ->add_option("--sheet", options.sheet,
                   "Also write a PNG with one thumbnail per case, in the table's order (8 a "
                   "row; the simd backend's image, dark red where the case is refused)")
      ->type_name("FILE.png")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            return has_extension(name, ".png") ? "" : "give a file name ending in .png";
          },
          "FILE.png"));
  return command;
}

int run_stress_command(const Scene& scene, const StressOptions& options, std::ostream& out,
                       std::ostream& err) {
  Scene base = scene;
  for (const std::string& assignment : {"viewport.width=" + std::to_string(options.viewport.at(0)),
                                        "viewport.height=" + std::to_string(options.viewport.at(1)),
                                        "grid.width=" + std::to_string(options.grid_side),
                                        "grid.height=" + std::to_string(options.grid_side)}) {
    apply_scene_layer(base, parse_override(assignment), "relief stress --viewport/--grid");
  }
  validate_scene(base);
  StressSettings settings;
  settings.budget = memory_budget(parse_memory_size(options.max_memory), options.max_memory);
  std::vector<Backend> all = stress_backends(settings.gl_unavailable);
  for (Backend backend : all) {
    const bool chosen =
        options.backends.empty() || std::find(options.backends.begin(), options.backends.end(),
                                              backend_name(backend)) != options.backends.end();
    if (chosen) {
      settings.backends.push_back(backend);
    }
  }
  // A backend asked for by name that cannot run here is bad input: a run in which it only
  // skipped would check nothing.
  if (!settings.gl_unavailable.empty() &&
      std::find(options.backends.begin(), options.backends.end(), "gl") != options.backends.end()) {
    err << "relief: error: --backend gl cannot run here: " << settings.gl_unavailable
        << "; nothing ran\n";
    return kExitBadInput;
  }
  // The budget must hold the base scene itself: below it every case would be refused one by one.
  for (Backend backend : settings.backends) {
    check_memory(
        estimate_render_memory(base, backend, {}), settings.budget,
        "the stress suite's base scene on the " + std::string(backend_name(backend)) + " backend",
        "Lower --viewport or --grid");
  }
  std::vector<StressCase> cases;
  for (StressCase& c : make_stress_cases(base, settings.budget.bytes, settings.backends)) {
    if (options.axes.empty() ||
        std::find(options.axes.begin(), options.axes.end(), c.axis) != options.axes.end()) {
      cases.push_back(std::move(c));
    }
  }
  // The distance axis's bounds compare each backend with reference-double: without it they
  // would go unchecked while the table said every check holds.
  const bool truth = std::find(settings.backends.begin(), settings.backends.end(),
                               Backend::kReferenceDouble) != settings.backends.end();
  for (const StressCase& c : cases) {
    if (c.error_bounded && !truth) {
      err << "relief: error: the " << c.axis << " axis checks its error bounds against "
          << "reference-double, which --backend leaves out; add --backend reference-double, or "
             "choose other axes with --axis\n";
      return kExitBadInput;
    }
  }
  settings.keep_images = !options.sheet.empty();
  StressSheet sheet;
  warm_up_stress_backends(base, settings);
  const bool progress = &err == &std::cerr && isatty(STDERR_FILENO);
  out << "relief stress: " << cases.size() << " cases of the base scene at " << base.viewport.width
      << "x" << base.viewport.height << ", grid " << base.grid.width << "x" << base.grid.height
      << "; budget " << mib(settings.budget.bytes) << " MiB (" << settings.budget.source
      << "); memory measured: "
      << (peak_memory_measurable() ? "peak resident set growth (VmHWM)" : "not here") << "\n"
      << "bounds on the distance axis: height error <= " << kStressHeightErrorBound
      << " x amplitude, sRGB bytes > 2 codes from reference-double <= "
      << 100 * kStressSrgbShareBound << "%\n";
  char header[512];
  std::snprintf(header, sizeof header, "%-9s %-44s %-16s %-12s %9s %10s %7s %9s %9s %9s %7s %7s",
                "axis", "case", "backend", "status", "frame ms", "values", "NaN/inf", "est MiB",
                "peak MiB", "h err/amp", "sRGB>2%", "PSNR dB");
  out << header << "\n";
  std::vector<std::string> notes;
  int failed = 0;
  std::size_t ran = 0;  // rows rendered and checked (not refused or skipped)
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (progress) {
      err << "\r[" << k + 1 << "/" << cases.size() << "] " << cases[k].axis << ": " << cases[k].name
          << "\x1b[K" << std::flush;
    }
    const std::vector<StressRow> rows = run_stress_case(base, cases[k], settings);
    for (const StressRow& row : rows) {
      print_row(out, row, notes);
      failed += !row.passed();
      ran += row.status == StressStatus::kOk;
    }
    if (settings.keep_images) {
      sheet.add_case(rows, "simd");
    }
    out.flush();
  }
  if (progress) {
    err << "\r\x1b[K" << std::flush;
  }
  for (std::size_t k = 0; k < notes.size(); ++k) {
    out << "[" << k + 1 << "] " << notes[k] << "\n";
  }
  if (settings.keep_images) {
    OutputSet files;
    files.add(options.sheet, sheet.encode_png("relief stress, " + std::to_string(cases.size()) +
                                              " cases in the table's order"));
    files.commit();
    out << "wrote " << options.sheet << "\n";
  }
  if (ran == 0) {
    out << "no case ran (every row was refused or skipped): nothing was checked\n";
    return 1;
  }
  out << (failed == 0 ? "every check holds" : std::to_string(failed) + " row(s) failed") << "\n";
  return failed == 0 ? kExitOk : 1;
}

}  // namespace relief
