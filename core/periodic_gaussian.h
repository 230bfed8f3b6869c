// The Gaussian filter of a periodic square grid, for §3's basis-image filters (low-pass,
// high-pass: core/basis_images.h). A basis image tiles the plane, so its filters wrap around
// too: the blur is defined in the frequency domain, each discrete Fourier coefficient
// (kx, ky) of an N x N grid multiplied by the continuous Gaussian's response
//   G(kx, ky) = exp(-2 pi^2 sigma^2 ((kx' / N)^2 + (ky' / N)^2)),
// k' the frequency k wrapped to [-N/2, N/2] (sigma in texels). G(0, 0) = 1: the mean is kept
// exactly; G is even in each k, so a real grid stays real; it commutes with every periodic
// shift of the grid. Computed once per scene by a radix-2 FFT in double whose twiddle factors
// come from square roots of exact values (half-angle recursion) and whose response comes from
// exp2_det: no library sin, cos or exp, so the bits are the same on every machine.
#pragma once

#include <span>

namespace relief {

// values (side x side, row-major) replaced by their periodic Gaussian blur. Preconditions:
// side a power of two >= 1, values.size() == side^2, sigma >= 0 finite (0: unchanged).
void periodic_gaussian_blur(std::span<double> values, int side, double sigma);

}  // namespace relief
