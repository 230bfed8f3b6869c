// Colour maps for the diagnostic images. Inputs and outputs are display values (sRGB bytes);
// these pictures are for people to read, not radiometry.
#pragma once

#include <array>
#include <cstdint>

namespace relief {

using Rgb8 = std::array<std::uint8_t, 3>;

// A perceptually ordered heat map (dark blue - cyan - green - yellow - red) for t in [0, 1];
// t outside is clamped (a display mapping, not input handling); NaN maps to magenta.
Rgb8 heat_color(double t);

Rgb8 gray_color(double t);

// A magma-like map (black - purple - orange - pale yellow), the colours FLIP's error maps use:
// matplotlib's magma at nine evenly spaced points, linear between (in sRGB); t clamped; NaN
// maps to pure white, which magma never reaches.
Rgb8 magma_color(double t);

}  // namespace relief
