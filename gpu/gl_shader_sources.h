// The GLSL sources of gpu/shaders/ (or generated from their templates there), compiled into
// the library (gpu/CMakeLists.txt embeds each file into gl_shader_sources.cc at build time with
// relief_embed_files, as core/ does with the scene presets), so a program built with them needs
// no file beside it.
#pragma once

#include <span>
#include <string_view>

namespace relief::gpu {

struct ShaderFile {
  std::string_view name;  // file name under gpu/shaders/, e.g. "fbm.comp"
  std::string_view text;
};

std::span<const ShaderFile> shader_files();

// The text of gpu/shaders/<name>; throws GlError if the library has no such file.
std::string_view shader_file(std::string_view name);

}  // namespace relief::gpu
