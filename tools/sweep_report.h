// What relief sweep writes and prints (docs/sweep.md): the CSV, the gnuplot script of the
// time-against-error plot, the table on the terminal, and whether the scene's defaults are on
// the Pareto front (and if not, what dominates them and by how much).
#pragma once

#include <iosfwd>
#include <span>
#include <string>

#include "eval/sweep.h"

namespace relief {

// One row per configuration: name, knob, value, backend, supersample, median_ms, psnr_db,
// rmse, max_error, mean_flip, height_max, height_rms, on_pareto_front (0/1), is_default (0/1);
// text fields quoted as RFC 4180 asks when they hold a comma or a quote.
std::string sweep_csv(std::span<const SweepRow> rows);

// A self-contained gnuplot script (the data inline as datablocks): x the median frame time
// (log scale), y the mean FLIP; every point labelled, the Pareto front as a step line, the
// default ringed. Run as `gnuplot -c sweep.gp OUTPUT.png` (sweep.png without an argument).
// `subtitle`: plain text (quotes and backslashes are escaped).
std::string sweep_gnuplot_script(std::span<const SweepRow> rows, const std::string& subtitle);

// The rows as an aligned table, front and default marked.
void print_sweep_table(std::ostream& out, std::span<const SweepRow> rows);

// "the default is on the Pareto front", or the rows that dominate it with their time and FLIP
// against the default's.
void print_default_verdict(std::ostream& out, std::span<const SweepRow> rows);

}  // namespace relief
