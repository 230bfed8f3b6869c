// terrain.basis's images (§3 Eq. 2, core/basis_images.h): read, checked, filtered and composed
// once per scene into stage 3's grid.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/lattice.h"
#include "core/scene/scene.h"

namespace relief {

// The composed grid (nullopt when the scene has no terrain.basis). Every image and weight image
// must be a regular file (or "builtin:basis/NAME"), a grey PNG of 8 or 16 bits, square with a
// power-of-two side from kMinLatticeSize to kMaxLatticeSize (doubled by wrap "mirror": at most
// kMaxLatticeSize / 2 then), all of one size; its header is checked before the rest is read,
// its chunks and inflated size before it is decoded (png_checks.h). Filter sigmas at most half
// the grid's side. Throws SceneError naming the field (terrain.basis.images[1].weight, ...).
// `notes` receives what the user should know but that is no error: an image that does not tile
// under wrap "repeat" (seam measure above kMaxBasisSeam, with the remedy), and a
// terrain.horizontal_scale other than the default, which basis mode does not use.
std::optional<NoiseLattice> load_basis_grid(const Scene& scene,
                                            std::vector<std::string>* notes = nullptr);

// Each image's seam measure (core/basis_images.h) as decoded, before any wrap or filter.
std::vector<double> basis_seam_measures(const Scene& scene);

// The peak memory of load_basis_grid from the images' headers alone (0 without terrain.basis,
// or when a header cannot be read: loading then says why).
std::uintmax_t basis_memory_bytes(const Scene& scene);

}  // namespace relief
