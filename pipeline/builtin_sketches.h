// Height sketches shipped inside the binary (terrain.sketch.image = "builtin:NAME"), so that a
// preset using one renders from any directory: the PNG files of scenes/sketches/, compiled in
// byte for byte by pipeline/CMakeLists.txt (tools/make_island_sketch.py made them).
#pragma once

#include <span>
#include <string_view>

namespace relief {

// The PNG file's bytes; empty for an unknown name.
std::span<const unsigned char> builtin_sketch_png(std::string_view name);

}  // namespace relief
