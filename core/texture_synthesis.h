// Built-in proto-textures (§4.2's "set of textures that serve as prototypes for ... grass,
// sand, rock, snow"), synthesised deterministically at start-up: seamlessly tiling value-noise
// fBm (lattices from counter_hash, so the bytes are the same everywhere) mapped through a
// per-material palette of linear-RGB albedos.
#pragma once

#include <string_view>

#include "core/proto_texture.h"

namespace relief {

// Names: sand, grass, rock, snow, bed (the water bed), basalt, dune. Precondition: a known
// name (scene validation checks it) and size a power of two >= 16.
RgbImage synthesize_texture(std::string_view name, int size);

}  // namespace relief
