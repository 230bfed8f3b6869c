// The options several commands share (tools/cli.cc): the scene and its overrides, the memory
// limit, the backend, the thread count, and checks of file names.
#pragma once

#include "core/input_file.h"  // has_extension

#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "tools/float_image_file.h"

namespace relief {

// SCENE and --set, shared by every command that renders a scene.
struct SceneArgs {
  std::string scene;
  std::vector<std::string> overrides;
};

void add_scene_args(CLI::App* command, SceneArgs& args);

// Memory limit of a job (memory_budget.h): "2G", "512M", bytes.
void add_max_memory(CLI::App* command, std::string& max_memory);

// A finite coordinate within +-1e6 (CLI::Range lets NaN through: every comparison with it is
// false).
extern const CLI::Validator kFiniteViewportValue;

// A whole number written in digits (an optional sign) from lo to hi; the message names the
// value and the range. CLI::Range let "1e3" and "1.5" through to a message about the range,
// and a value CLI11 could not convert reached the user as "Could not convert".
// Give it with ->transform (->check hands a validator a copy): the text is then rewritten in
// canonical decimal, so that CLI11's conversion reads it as this check did (CLI11 reads "010"
// as octal 8).
CLI::Validator integer_in(long long lo, long long hi);

// A number is given: CLI11 turns an empty value into 0 ("--amplitude ''" was a flat map).
extern const CLI::Validator kNonEmptyNumber;

// An option given with an empty value (-o ""): never silently the default.
bool given_empty(const CLI::Option* option, const std::string& value);

// --backend NAME (pipeline/frame.h): which implementation runs the frame's stages; --simd
// TARGET forces one Highway target (implies --backend simd).
void add_backend(CLI::App* command, std::string& backend, std::string& simd_target);

void add_threads(CLI::App* command, int& threads);

// --float-format pfm|exr (any letter case): the format of relief stages' float files.
void add_float_format(CLI::App* command, FloatFormat& format);

}  // namespace relief
