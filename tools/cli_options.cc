#include "tools/cli_options.h"

#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>

#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "pipeline/frame.h"
#include "pipeline/memory_budget.h"

namespace relief {

namespace {

std::string preset_list() {
  std::string out;
  for (const std::string& name : preset_names()) {
    out += (out.empty() ? "" : ", ") + name;
  }
  return out;
}

}  // namespace

void add_scene_args(CLI::App* command, SceneArgs& args) {
  command->add_option("SCENE", args.scene,
                      "Scene: a JSON file, or a preset name (" + preset_list() +
                          "). Default: the built-in default scene.");
  command
      ->add_option("--set", args.overrides,
                   "Override one scene field, validated like the scene file; repeatable, "
                   "applied in order. Example: --set terrain.H=0.85 --set grid.width=256")
      ->type_name("KEY=VALUE")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      // One value per --set: "--set a=b lava" leaves lava to SCENE.
      ->allow_extra_args(false);
}

void add_max_memory(CLI::App* command, std::string& max_memory) {
  command
      ->add_option("--max-memory", max_memory,
                   "Refuse the job (exit 2) if its estimated memory exceeds SIZE (for example "
                   "512M, 2G). Default: the memory available on this machine.")
      ->type_name("SIZE")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return parse_memory_size(text)
                       ? ""
                       : "'" + brief_text(text) +
                             "' is not a size from 1M to 1E: a number with an optional unit K, "
                             "M, G, T, P or E (powers of 1024)";
          },
          "SIZE"));
}

const CLI::Validator kFiniteViewportValue = CLI::Validator(
    [](std::string& text) -> std::string {
      double v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v) ||
          std::abs(v) > 1e6) {
        return "'" + brief_text(text) + "' is not a finite number in [-1e6, 1e6]";
      }
      return "";
    },
    "NUMBER in [-1e6, 1e6]");

CLI::Validator integer_in(long long lo, long long hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        long long v = 0;
        const char* first = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
        const auto [end, ec] = std::from_chars(first, text.data() + text.size(), v);
        if (text.empty() || ec != std::errc() || end != text.data() + text.size() || v < lo ||
            v > hi) {
          // A command that checks the range itself (with the option's own advice) asks for any
          // int: the message then speaks of the form alone.
          const bool any_int = lo <= INT_MIN && hi >= INT_MAX;
          return "'" + brief_text(text) + "' is not a whole number" +
                 (any_int ? std::string()
                          : " from " + std::to_string(lo) + " to " + std::to_string(hi));
        }
        // Decimal, as read here: CLI11 would take a leading 0 for octal ("010" as 8).
        text = std::to_string(v);
        return "";
      },
      "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

const CLI::Validator kNonEmptyNumber(
    [](std::string& text) -> std::string {
      return text.empty() ? std::string("is empty; give a number") : std::string();
    },
    "NUMBER");

bool given_empty(const CLI::Option* option, const std::string& value) {
  return option->count() > 0 && value.empty();
}

void add_backend(CLI::App* command, std::string& backend, std::string& simd_target) {
  command
      ->add_option("--simd", simd_target,
                   "Run the simd backend on this Highway target (AVX3, AVX2, SSE4, SSSE3, "
                   "SCALAR: relief info lists those compiled in and those this CPU runs); "
                   "every target gives the same bytes")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return text.empty() ? "empty; give a target (relief info lists them)" : "";
          },
          "TARGET"));
  std::string names;
  for (std::string_view name : backend_names()) {
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  command
      ->add_option("--backend", backend,
                   "Implementation of the stages: simd (the default: Highway kernels), "
                   "reference (the scalar float stages; simd gives their bytes exactly), "
                   "reference-double (every stage in double, for accuracy comparisons) or gl "
                   "(the GLSL twins on OpenGL 4.5: a GPU, or Mesa's llvmpipe)")
      ->check(CLI::Validator(
          [names](std::string& text) -> std::string {
            return backend_from_name(text)
                       ? ""
                       : "'" + brief_text(text) + "' is not a backend; allowed: " + names;
          },
          "NAME"));
}

void add_threads(CLI::App* command, int& threads) {
  command
      ->add_option("--threads", threads,
                   "Worker threads (default: all cores). Results are bit-identical for any count.")
      ->transform(integer_in(1, 1024));
}

void add_float_format(CLI::App* command, FloatFormat& format) {
  command
      ->add_option("--float-format", format,
                   "Format of the float files: pfm (the default) or exr (OpenEXR, 32-bit float)")
      ->transform(CLI::Validator(
          [](std::string& text) -> std::string {
            // The name to the enum's value, which CLI11 then converts; the message names the
            // option's own values (CLI11's own transformer printed its internal table).
            const std::string name = CLI::detail::to_lower(text);
            if (name != "pfm" && name != "exr") {
              return "'" + brief_text(text) + "' is not a float format; allowed: pfm, exr";
            }
            text = std::to_string(int(name == "pfm" ? FloatFormat::kPfm : FloatFormat::kExr));
            return "";
          },
          "pfm|exr"));
}

}  // namespace relief
