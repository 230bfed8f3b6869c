// relief reference --converge's figures (eval/convergence.h) as a table and as JSON.
#pragma once

#include <iosfwd>

#include <nlohmann/json.hpp>

#include "eval/convergence.h"

namespace relief {

// The table: each band's pixels, farthest distance, mean FLIP and PSNR.
void print_convergence(std::ostream& out, const ConvergenceReport& report);

// {"settings": {...}, "doubled": {...}, "all": BAND, "bands": [BAND...]}, BAND = {"band",
// "pixels", "max_distance", "mean_flip", "psnr_db" (null where the images agree)}.
nlohmann::ordered_json convergence_json(const ConvergenceReport& report);

}  // namespace relief
