#include "tools/cli.h"

#include <algorithm>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "core/scene_json.h"
#include "tools/atomic_file.h"
#include "tools/commands.h"

namespace relief {

namespace {

std::string preset_list() {
  std::string out;
  for (const std::string& name : preset_names()) {
    out += (out.empty() ? "" : ", ") + name;
  }
  return out;
}

// SCENE and --set, shared by every command that renders a scene.
struct SceneArgs {
  std::string scene;
  std::vector<std::string> overrides;
};

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
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

void add_threads(CLI::App* command, int& threads) {
  command
      ->add_option("--threads", threads,
                   "Worker threads (default: all cores). Results are bit-identical for any count.")
      ->check(CLI::Range(1, 1024));
}

}  // namespace

int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "Relief renders procedural fractal landscapes (Schneider, Boldte & Westermann, VMV 2006) "
      "with a deterministic CPU pipeline.\n"
      "Scenes are JSON files or built-in presets; every field can be overridden with --set.\n"
      "The scene reference and the stage-by-stage map to the paper are in README.md.",
      "relief"};
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 2 bad input (nothing written), 1 output not written.\n"
      "Run 'relief COMMAND --help' for the options of one command.");

  SceneArgs scene_args;
  int threads = 0;

  CLI::App* scene_cmd =
      app.add_subcommand("scene",
                         "Print the effective scene (defaults, preset or file, then "
                         "--set overrides) as JSON.");
  add_scene_args(scene_cmd, scene_args);

  StagesOptions stages;
  CLI::App* stages_cmd = app.add_subcommand(
      "stages",
      "Run stages 1-4 (screen grid, projected domain, fractal, surface) and write "
      "each stage's buffers as PNG pictures and PFM floats, with stages.json.");
  add_scene_args(stages_cmd, scene_args);
  stages_cmd->add_option("--out", stages.out_dir,
                         "Output directory (created if missing). Default: the scene's "
                         "output.stages_dir");
  stages_cmd
      ->add_option("--repeat", stages.repeat,
                   "Run the stages this many times and report the median stage times")
      ->check(CLI::Range(1, 1000));
  add_threads(stages_cmd, threads);

  std::vector<const char*> argv;
  for (const std::string& a : args) {
    argv.push_back(a.c_str());
  }
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    err << "relief: error: " << e.what() << "\nRun 'relief --help' for usage.\n";
    return kExitBadInput;
  }

  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0) {
    thread_limit = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  }
  try {
    // The scene is validated completely before any work starts.
    const Scene scene = resolve_scene(scene_args.scene, scene_args.overrides);
    if (scene_cmd->parsed()) {
      out << scene_to_json(scene).dump(2) << "\n";
      return kExitOk;
    }
    if (stages_cmd->parsed()) {
      return run_stages_command(scene, stages, out);
    }
  } catch (const SceneError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const OutputError& e) {
    err << "relief: error: " << e.what() << "\n";
    return kExitOutputError;
  }
  return kExitOk;
}

}  // namespace relief
