// One input of each fuzzer, through the entry point the command line uses for that input's
// bytes. The fuzzers (fuzz/*_fuzzer.cc) call these for every input libFuzzer makes, and
// tests/cli/fuzz_corpus_test.cc for every file of the seed corpora and of fuzz/regressions/, so
// that the corpora stay meaningful in the ordinary build.
//
// Each returns true when the input was accepted and false when it was refused with the error
// the command line turns into exit code 2 (SceneError, SoupError). An accepted input whose
// result breaks a documented property throws Finding; any other exception escapes. In a
// fuzzer both end the run as a crash, with the input saved.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace relief::fuzz {

class Finding : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// A scene file's bytes (resolve_scene_text). An accepted scene must print as a scene file that
// loads back to the same scene.
bool scene_input(std::string_view bytes);

// A preset and --set overrides (resolve_scene): byte 0 picks the base scene among
// preset_names() by its value modulo their count; the rest, if any, split at each '\n', are
// the KEY=VALUE arguments in order. Round trip as for scene_input.
bool override_input(std::string_view bytes);

// A triangle soup's bytes (parse_triangle_soup). An accepted soup must keep the format's
// ranges: framebuffer 1..16384, finite coordinates, window depths in [0, 1].
bool soup_input(std::string_view bytes);

// A texture PNG's bytes (decode_texture_png). An accepted texture must be square with a
// power-of-two side from 4 to 4096, with every linear colour in [0, 1].
bool texture_input(std::string_view bytes);

}  // namespace relief::fuzz
