#include "tools/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <vector>

#include "eval/pareto.h"

namespace relief {

namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) {
    return text;
  }
  std::string out = "\"";
  for (char c : text) {
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return out + "\"";
}

// Shortest text that reads back to the same double ("inf" for an infinite PSNR).
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// A gnuplot double-quoted string: backslash and quote escaped, control characters dropped.
std::string gnuplot_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) >= 0x20) {
      out += c;
    }
  }
  return out + "\"";
}

const SweepRow* default_row(std::span<const SweepRow> rows) {
  for (const SweepRow& row : rows) {
    if (row.configuration.is_default) {
      return &row;
    }
  }
  return nullptr;
}

}  // namespace

std::string sweep_csv(std::span<const SweepRow> rows) {
  std::ostringstream csv;
  csv << "name,knob,value,backend,supersample,median_ms,psnr_db,rmse,max_error,mean_flip,"
         "height_max,height_rms,on_pareto_front,is_default\n";
  for (const SweepRow& row : rows) {
    const SweepConfiguration& c = row.configuration;
    csv << csv_field(c.name) << ',' << csv_field(c.knob) << ',' << csv_field(c.value) << ','
        << backend_name(c.backend) << ',' << c.supersample << ',' << number(row.median_ms) << ','
        << number(row.psnr_db) << ',' << number(row.rmse) << ',' << number(row.max_error) << ','
        << number(row.mean_flip) << ',' << number(row.height_max) << ',' << number(row.height_rms)
        << ',' << (row.on_pareto_front ? 1 : 0) << ',' << (c.is_default ? 1 : 0) << '\n';
  }
  return csv.str();
}

std::string sweep_gnuplot_script(std::span<const SweepRow> rows, const std::string& subtitle) {
  std::ostringstream gp;
  gp << "# relief sweep: median frame time against mean LDR-FLIP (docs/sweep.md).\n"
        "# Run: gnuplot -c sweep.gp [OUTPUT.png]   (default sweep.png)\n"
        "output_file = (ARGC >= 1) ? ARG1 : \"sweep.png\"\n"
        "set terminal pngcairo noenhanced size 1600,1000 font \"sans,11\"\n"
        "set output output_file\n"
        "set title \"relief sweep: frame time against perceptual error\\n\" . "
     << gnuplot_string(subtitle)
     << "\n"
        "set logscale x\n"
        "set xlabel \"median frame time, ms (log scale)\"\n"
        "set ylabel \"mean LDR-FLIP against the ground truth (lower is better)\"\n"
        "set grid xtics ytics mxtics\n"
        "set key top right box opaque\n"
        "set autoscale fix\n"
        "set offsets graph 0.03, graph 0.15, graph 0.06, graph 0.06\n";
  // Rows: name, time, FLIP (names are quoted: one column each).
  // Rows: name, time, FLIP, and 0 or 1 for the side of the label (alternating, so that
  // neighbours at one height do not write over each other).
  gp << "$rows << EOD\n";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    gp << gnuplot_string(rows[k].configuration.name) << ' ' << number(rows[k].median_ms) << ' '
       << number(rows[k].mean_flip) << ' ' << k % 2 << '\n';
  }
  gp << "EOD\n$front << EOD\n";
  std::vector<const SweepRow*> front;
  for (const SweepRow& row : rows) {
    if (row.on_pareto_front) {
      front.push_back(&row);
    }
  }
  std::sort(front.begin(), front.end(), [](const SweepRow* a, const SweepRow* b) {
    return a->median_ms < b->median_ms ||
           (a->median_ms == b->median_ms && a->mean_flip > b->mean_flip);
  });
  for (const SweepRow* row : front) {
    gp << number(row->median_ms) << ' ' << number(row->mean_flip) << '\n';
  }
  gp << "EOD\n$default << EOD\n";
  if (const SweepRow* row = default_row(rows)) {
    gp << number(row->median_ms) << ' ' << number(row->mean_flip) << '\n';
  }
  // The step line: from each front point, level to the next point's time, then down to its
  // error (the best error attainable within a time budget).
  gp << "EOD\n"
        "plot $front using 1:2 with steps lw 2 lc rgb \"#d62728\" title \"Pareto front\", \\\n"
        "     $front using 1:2 with points pt 7 ps 1.6 lc rgb \"#d62728\" notitle, \\\n"
        "     $rows using 2:3 with points pt 7 ps 1.0 lc rgb \"#1f77b4\" title "
        "\"configurations\", \\\n"
        "     $default using 1:2 with points pt 6 ps 3.5 lw 3 lc rgb \"#2ca02c\" title "
        "\"the scene's settings (default)\", \\\n"
        "     $rows using 2:($4 == 0 ? $3 : NaN):1 with labels left offset char 0.8,0.4 "
        "font \"sans,9\" notitle, \\\n"
        "     $rows using 2:($4 == 1 ? $3 : NaN):1 with labels right offset char -0.8,-0.4 "
        "font \"sans,9\" notitle\n";
  return gp.str();
}

void print_sweep_table(std::ostream& out, std::span<const SweepRow> rows) {
  std::size_t name_width = 4;
  for (const SweepRow& row : rows) {
    name_width = std::max(name_width, row.configuration.name.size());
  }
  const int w = int(name_width);
  out << std::left << std::setw(w) << "name" << std::right << std::setw(11) << "median ms"
      << std::setw(9) << "PSNR dB" << std::setw(9) << "RMSE" << std::setw(8) << "max"
      << std::setw(10) << "mean FLIP" << std::setw(11) << "height max" << std::setw(11)
      << "height rms"
      << "  front\n";
  for (const SweepRow& row : rows) {
    out << std::left << std::setw(w) << row.configuration.name << std::right << std::fixed
        << std::setprecision(1) << std::setw(11) << row.median_ms << std::setprecision(2)
        << std::setw(9) << row.psnr_db << std::setprecision(4) << std::setw(9) << row.rmse
        << std::setprecision(3) << std::setw(8) << row.max_error << std::setprecision(4)
        << std::setw(10) << row.mean_flip << std::scientific << std::setprecision(2)
        << std::setw(11) << row.height_max << std::setw(11) << row.height_rms << std::fixed << "  "
        << (row.on_pareto_front ? "*" : " ") << (row.configuration.is_default ? " (default)" : "")
        << "\n";
  }
}

void print_default_verdict(std::ostream& out, std::span<const SweepRow> rows) {
  const SweepRow* base = default_row(rows);
  if (base == nullptr) {
    return;
  }
  if (base->on_pareto_front) {
    out << "The scene's settings are on the Pareto front of time against mean FLIP.\n";
    return;
  }
  // Medians of a few rounds on a shared machine resolve about 3 % of a frame's time; mean FLIP
  // differences below 0.5 % are invisible.
  constexpr double kTimeTolerance = 0.03, kErrorTolerance = 0.005;
  const ParetoPoint base_point{base->median_ms, base->mean_flip};
  bool clearly = false;
  for (const SweepRow& row : rows) {
    clearly = clearly || dominates_beyond({row.median_ms, row.mean_flip}, base_point,
                                          kTimeTolerance, kErrorTolerance);
  }
  out << (clearly ? "The scene's settings are NOT on the Pareto front; dominated by:\n"
                  : "The scene's settings are on the Pareto front within what the measurement "
                    "resolves (3 % of the time, 0.5 % of the mean FLIP); dominated, by less, "
                    "by:\n");
  for (const SweepRow& row : rows) {
    if (dominates({row.median_ms, row.mean_flip}, {base->median_ms, base->mean_flip})) {
      out << std::fixed << std::setprecision(1) << "  " << row.configuration.name << ": "
          << row.median_ms << " ms against " << base->median_ms << " (" << std::setprecision(0)
          << 100.0 * (row.median_ms / base->median_ms - 1.0) << " %), mean FLIP "
          << std::setprecision(4) << row.mean_flip << " against " << base->mean_flip;
      if (base->mean_flip > 0) {  // the ratio's domain
        out << " (" << std::setprecision(1) << 100.0 * (row.mean_flip / base->mean_flip - 1.0)
            << " %)";
      }
      out << (row.on_pareto_front ? ", on the front" : "") << "\n";
    }
  }
}

}  // namespace relief
