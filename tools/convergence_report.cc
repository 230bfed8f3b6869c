#include "tools/convergence_report.h"

#include <cmath>
#include <iomanip>
#include <ostream>

namespace relief {

namespace {

nlohmann::ordered_json settings_json(const GroundTruthSettings& s) {
  return {{"supersample", s.supersample},
          {"grid_scale", s.grid_scale},
          {"octave_epsilon", s.octave_epsilon}};
}

nlohmann::ordered_json band_json(const BandError& b) {
  return {{"band", b.band},
          {"pixels", b.pixels},
          {"max_distance", b.max_distance},
          // A band without pixels has no error to give: null, not a perfect 0.
          {"mean_flip", b.pixels > 0 ? nlohmann::ordered_json(b.mean_flip) : nullptr},
          {"psnr_db",
           b.pixels > 0 && std::isfinite(b.psnr_db) ? nlohmann::ordered_json(b.psnr_db) : nullptr}};
}

}  // namespace

void print_convergence(std::ostream& out, const ConvergenceReport& r) {
  out << "  convergence: against the same frame at twice the settings (supersample "
      << r.doubled.supersample << ", grid scale " << r.doubled.grid_scale << ", octave epsilon "
      << std::defaultfloat << r.doubled.octave_epsilon << "):\n"
      << "    band            pixels   farthest   mean FLIP    PSNR\n";
  const auto row = [&](const BandError& b) {
    out << "    " << std::left << std::setw(14) << b.band << std::right << std::setw(8) << b.pixels
        << std::setw(11) << std::setprecision(0) << std::fixed << b.max_distance;
    if (b.pixels == 0) {
      out << std::setw(12) << "-" << std::setw(8) << "-"
          << "\n";
      return;
    }
    out << std::setw(12) << std::setprecision(4) << b.mean_flip << std::setw(8)
        << std::setprecision(1);
    if (std::isfinite(b.psnr_db)) {
      out << b.psnr_db << " dB\n";
    } else {
      out << "inf"
          << " dB\n";
    }
  };
  for (const BandError& b : r.bands) {
    row(b);
  }
  row(r.all);
}

nlohmann::ordered_json convergence_json(const ConvergenceReport& r) {
  nlohmann::ordered_json bands = nlohmann::ordered_json::array();
  for (const BandError& b : r.bands) {
    bands.push_back(band_json(b));
  }
  return {{"settings", settings_json(r.settings)},
          {"doubled", settings_json(r.doubled)},
          {"all", band_json(r.all)},
          {"bands", bands}};
}

}  // namespace relief
