// Height sketches shipped inside the binary (terrain.sketch.image = "builtin:NAME"), so that a
// preset using one renders from any directory: the PNG files of scenes/sketches/, compiled in
// byte for byte by pipeline/CMakeLists.txt (tools/make_island_sketch.py made them).
#pragma once

#include <span>
#include <string_view>
#include <vector>

namespace relief {

// The PNG file's bytes; empty for an unknown name. The table also holds §3 Eq. 2's basis images
// as "basis/NAME" (basis_resources.h); a sketch names none of those.
std::span<const unsigned char> builtin_sketch_png(std::string_view name);

// The height sketches' names (without "basis/..."), in the table's order: "island".
std::vector<std::string_view> builtin_sketch_names();

}  // namespace relief
