// relief crosscheck: one scene rendered by a CPU backend and by the GL backend, compared stage
// by stage (tools/crosscheck.h), with heat maps, a table and its JSON, and idiff's verdict on
// the final images as the exit code.
#include <algorithm>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "pipeline/build_info.h"
#include "pipeline/frame.h"
#include "pipeline/frame_mesh.h"
#include "pipeline/gl_backend.h"
#include "pipeline/job_memory.h"
#include "pipeline/scene_resources.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/colormap.h"
#include "tools/commands.h"
#include "tools/compare_report.h"
#include "tools/crosscheck.h"
#include "tools/distinct_paths.h"

namespace relief {

namespace {

// The frame with every output, rendered `repeat` times; the median wall time in ms.
Frame timed_frame(const Scene& scene, const SceneResources& resources, Backend backend, int repeat,
                  double& median_ms) {
  FrameRequest request;
  request.backend = backend;
  request.outputs = {true, true, true, true, true, true};
  return render_frame_repeated(scene, resources, request, repeat, median_ms);
}

// A heat map of `values` (rows bottom to top), 0 black-blue to `scale` red; NaN magenta.
std::vector<std::uint8_t> heat_map(const std::vector<float>& values, double scale) {
  std::vector<std::uint8_t> rgb(3 * values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const Rgb8 c = heat_color(scale > 0 ? double(values[k]) / scale : 0.0);
    std::copy(c.begin(), c.end(), rgb.begin() + std::ptrdiff_t(3 * k));
  }
  return rgb;
}

// The CPU image in grey, red where the two frames' triangles differ.
std::vector<std::uint8_t> visibility_map(const FrameImage& cpu, const FrameImage& gl) {
  std::vector<std::uint8_t> rgb(cpu.srgb.size());
  for (std::size_t k = 0; k < cpu.primitive.size(); ++k) {
    const double grey = (cpu.srgb[3 * k] + cpu.srgb[3 * k + 1] + cpu.srgb[3 * k + 2]) / (3.0 * 255);
    const Rgb8 c = cpu.primitive[k] != gl.primitive[k] ? Rgb8{255, 0, 0} : gray_color(0.6 * grey);
    std::copy(c.begin(), c.end(), rgb.begin() + std::ptrdiff_t(3 * k));
  }
  return rgb;
}

double largest(const std::vector<float>& values) {
  double m = 0;
  for (float v : values) {
    if (std::isfinite(v)) {
      m = std::max(m, double(v));
    }
  }
  return m;
}

nlohmann::json figures_json(const CompareResult& r) {
  return {{"verdict", std::string(verdict_name(r.verdict))},
          {"mean_error", r.mean_error},
          {"rms_error", r.rms_error},
          // null when infinite (equal images), as relief compare and relief error write it
          {"psnr_db", std::isfinite(r.psnr) ? nlohmann::json(r.psnr) : nlohmann::json(nullptr)},
          {"max_error", r.max_error},
          {"max_at", {r.max_x, r.max_y, r.max_channel}},
          {"warn_pixels", r.warn_pixels},
          {"fail_pixels", r.fail_pixels}};
}

}  // namespace

CLI::App* add_crosscheck_command(CLI::App& app, CrosscheckOptions& options) {
  CLI::App* command = app.add_subcommand(
      "crosscheck",
      "Render the scene with a CPU backend and with the GL backend (a GPU, or Mesa's "
      "llvmpipe) and compare them stage by stage: heights, normals and octave counts at the "
      "grid's vertices, the triangle at each pixel, the per-pixel outputs, the final images. "
      "Writes both images, heat maps, a table and its JSON into --out; exits as idiff does on "
      "the final images over the pixels both draw with the same triangle (0 pass, 1 warning, 2 "
      "failure; 2 also for a pixel that changed triangle away from any triangle boundary), 4 "
      "for bad input or no GL, 5 when an output cannot be written.");
  options.out_option =
      command->add_option("--out", options.out_dir, "Output directory")->required();
  command
      ->add_option("--cpu-backend", options.cpu_backend_name,
                   "The CPU side: simd (the default) or reference")
      ->check(CLI::IsMember({"simd", "reference"}));
  command
      ->add_option("--repeat", options.repeat,
                   "Render each backend this many times for the frame times (median)")
      ->transform(integer_in(1, 100));
  add_compare_thresholds(command, options.thresholds);
  command->add_flag("--all-pixels", options.all_pixels,
                    "Judge every pixel, also where the two frames draw another triangle (as "
                    "idiff judges cpu.png and gl.png; may fail on a conforming GL)");
  return command;
}

int run_crosscheck_command(const Scene& scene, const CrosscheckOptions& options, std::ostream& out,
                           std::ostream& err) {
  std::vector<CommandPath> paths = scene_input_paths(options.scene_arg, scene);
  for (const char* name : {"cpu.png", "gl.png", "image_difference.png", "visibility_difference.png",
                           "height_difference.png", "crosscheck.txt", "crosscheck.json"}) {
    paths.push_back(
        {"--out's " + std::string(name), std::filesystem::path(options.out_dir) / name});
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    err << "relief: error: " << *conflict << "\n";
    return kCrosscheckBadInput;
  }
  // Two frames with every output, and two grids: twice a render's memory.
  MemoryEstimate estimate = estimate_render_memory(
      scene, options.cpu_backend, FrameOutputs{true, true, true, true, true, true});
  // The GL frame and the grids, and the CPU's trilinear frame of a bilinear scene.
  estimate.add("the GL frame, the grids and the trilinear frame", 2 * estimate.total());
  check_memory(estimate, options.budget, "relief crosscheck", "Lower the viewport or grid size");
  const SceneResources resources = load_scene_resources(scene);
  print_scene_notes(resources.notes, err);
  const std::string renderer = gl_renderer();  // GlBackendError (exit 2) when there is no GL
  double cpu_ms = 0, gl_ms = 0;
  const Frame cpu = timed_frame(scene, resources, options.cpu_backend, options.repeat, cpu_ms);
  const Frame gl = timed_frame(scene, resources, Backend::kGl, options.repeat, gl_ms);
  TerrainRun<float> cpu_terrain{{}, GridBuffers<float>(GridLayout{}), {}};
  GridBuffers<float> gl_grid{GridLayout{}};
  if (scene.terrain.heightfield && scene.terrain.heightfield->geomipmap) {
    // GeoMipMapping: the mesh's vertices, both sides' stages 2-4 (pipeline/frame_mesh.h).
    MeshStages mesh = cpu_mesh_stages(scene, resources);
    cpu_terrain.plan = std::move(mesh.plan);
    cpu_terrain.plan.layout = mesh.grid.layout;
    cpu_terrain.grid = std::move(mesh.grid);
    gl_grid = gl_mesh_stages(scene, resources);
  } else {
    cpu_terrain = run_terrain_stages<float>(scene, resources.terrain_values(), Backend::kReference,
                                            resources.sketch_or_null());
    gl_grid = gl_terrain_stages(scene, resources.terrain_values(), resources.sketch_or_null());
  }
  const GridDifference grid = compare_grids(cpu_terrain.grid, gl_grid);
  // Bilinear filtering switches mip level in a step: the CPU's trilinear frame sizes the step
  // (crosscheck.h).
  std::optional<Frame> cpu_trilinear;
  if (scene.shading.texture_filter == TextureFilter::kBilinear && !options.all_pixels) {
    Scene trilinear = scene;
    trilinear.shading.texture_filter = TextureFilter::kTrilinear;
    double trilinear_ms = 0;
    cpu_trilinear = timed_frame(trilinear, resources, options.cpu_backend, 1, trilinear_ms);
  }
  std::optional<Shoreline> shoreline;
  if (scene.terrain.water_level) {
    shoreline = Shoreline{*scene.terrain.water_level, cpu_terrain.plan.camera.position.y};
  }
  const FrameDifference frame = compare_frames(cpu.image, gl.image, options.thresholds,
                                               cpu_trilinear ? &cpu_trilinear->image : nullptr,
                                               options.all_pixels, shoreline);

  const double amplitude = scene.terrain.amplitude;
  std::ostringstream table;
  table << std::setprecision(4);
  table << "relief crosscheck: " << backend_label(options.cpu_backend) << " against gl on "
        << renderer << "\n"
        << scene.viewport.width << "x" << scene.viewport.height << " image, "
        << cpu_terrain.plan.layout.width << "x" << cpu_terrain.plan.layout.height
        << (cpu_terrain.grid.layout.width == kMeshRowVertices ? " GeoMipMap mesh rows\n"
                                                              : " grid\n")
        << "frame time (median of " << options.repeat << "): cpu " << cpu_ms << " ms, gl " << gl_ms
        << " ms, gl / cpu " << gl_ms / cpu_ms << "\n"
        << "stage                measure                          value\n"
        << "1-2 domain           vertices valid in one grid only  " << grid.valid_mismatch << "\n"
        << "1-2 domain           max octave count error           " << grid.max_octave_error << "\n"
        << "3 fractal            max height error / amplitude     "
        << grid.max_height_error / amplitude << "\n"
        << "3 fractal            RMS height error / amplitude     "
        << grid.rms_height_error / amplitude << "\n"
        << "4 surface            max normal angle (deg)           " << grid.max_normal_angle_deg
        << "\n"
        << "6 visibility         pixels whose triangle differs    "
        << frame.pixels.primitive_mismatch << " (" << 100.0 * frame.pixels.visibility_share()
        << "%)\n"
        << "6 visibility         ... not on a CPU triangle boundary " << frame.unexplained_changes
        << " (of " << frame.boundary_pixels << " boundary pixels)\n"
        << "8 mip level          channels explained by a level switch "
        << frame.level_switch_channels
        << (cpu_trilinear ? "" : " (not judged: trilinear filtering)") << "\n"
        << "8 water              pixels explained by the shoreline " << frame.water_edge_pixels
        << "\n"
        << "6-7 depth            max error (same triangle)        " << frame.pixels.max_depth_error
        << "\n"
        << "7 normal             max angle (deg, same triangle)   "
        << frame.pixels.max_normal_angle_deg << "\n"
        << "7 height             max error / amplitude            "
        << frame.pixels.max_height_error / amplitude << "\n"
        << "7 octaves            max error                        " << frame.pixels.max_octave_error
        << "\n"
        << "8 linear radiance    max error, PSNR (dB)             " << frame.linear.max_error
        << ", " << frame.linear.psnr << "\n"
        << "9 sRGB image         max error (codes), PSNR (dB)     "
        << frame.srgb_all.max_error * 255.0 << ", " << frame.srgb_all.psnr << "\n"
        << "9 sRGB image         pixels over warn / fail          " << frame.srgb_all.warn_pixels
        << " / " << frame.srgb_all.fail_pixels << "\n"
        << "9 sRGB, judged       max error (codes), over warn / fail "
        << frame.srgb.max_error * 255.0 << ", " << frame.srgb.warn_pixels << " / "
        << frame.srgb.fail_pixels << "  ("
        << (options.all_pixels ? "every pixel" : "pixels whose triangle is the same") << ")\n"
        << verdict_name(frame.verdict) << "\n";

  const nlohmann::json json = {
      {"cpu_backend", backend_label(options.cpu_backend)},
      {"gl_renderer", renderer},
      {"width", scene.viewport.width},
      {"height", scene.viewport.height},
      {"frame_ms", {{"cpu", cpu_ms}, {"gl", gl_ms}, {"repeat", options.repeat}}},
      {"grid",
       {{"vertices", grid.vertices},
        {"valid_mismatch", grid.valid_mismatch},
        {"max_octave_error", grid.max_octave_error},
        {"max_height_error", grid.max_height_error},
        {"rms_height_error", grid.rms_height_error},
        {"amplitude", amplitude},
        {"max_normal_angle_deg", grid.max_normal_angle_deg}}},
      {"pixels",
       {{"count", frame.pixels.pixels},
        {"primitive_mismatch", frame.pixels.primitive_mismatch},
        {"unexplained_changes", frame.unexplained_changes},
        {"boundary_pixels", frame.boundary_pixels},
        {"level_switch_channels", frame.level_switch_channels},
        {"water_edge_pixels", frame.water_edge_pixels},
        {"max_depth_error", frame.pixels.max_depth_error},
        {"max_normal_angle_deg", frame.pixels.max_normal_angle_deg},
        {"max_height_error", frame.pixels.max_height_error},
        {"max_octave_error", frame.pixels.max_octave_error}}},
      {"linear", figures_json(frame.linear)},
      {"verdict", std::string(verdict_name(frame.verdict))},
      {"judged", options.all_pixels ? "every pixel" : "pixels whose triangle is the same"},
      {"srgb", figures_json(frame.srgb_all)},
      {"srgb_judged", figures_json(frame.srgb)}};

  const std::filesystem::path dir = options.out_dir;
  OutputDirectory directory(dir);
  OutputSet files;
  const int w = scene.viewport.width, h = scene.viewport.height;
  files.add(dir / "cpu.png", encode_png_rgb(w, h, cpu.image.srgb));
  files.add(dir / "gl.png", encode_png_rgb(w, h, gl.image.srgb));
  if (!frame.srgb_difference.empty()) {
    std::vector<float> top_first(frame.srgb_difference.size());
    for (int y = 0; y < h; ++y) {
      std::copy_n(frame.srgb_difference.begin() + std::ptrdiff_t(y) * w, w,
                  top_first.begin() + std::ptrdiff_t(h - 1 - y) * w);
    }
    files.add(dir / "image_difference.png", difference_heat_map_png(top_first, w, h));
    files.add(dir / "visibility_difference.png",
              encode_png_rgb(w, h, visibility_map(cpu.image, gl.image)));
  }
  const GridLayout& layout = cpu_terrain.plan.layout;
  std::vector<float> height_rows(std::size_t(layout.width) * layout.height);
  for (int j = 0; j < layout.height; ++j) {
    for (int i = 0; i < layout.width; ++i) {
      height_rows[std::size_t(j) * layout.width + i] = grid.height_error[layout.index(i, j)];
    }
  }
  files.add(dir / "height_difference.png",
            encode_png_rgb(layout.width, layout.height,
                           heat_map(height_rows, largest(grid.height_error))));
  const std::string text = table.str();
  files.add(dir / "crosscheck.txt",
            std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
  const std::string json_text = json.dump(2) + "\n";
  files.add(dir / "crosscheck.json",
            std::span(reinterpret_cast<const unsigned char*>(json_text.data()), json_text.size()));
  files.commit();
  directory.keep();
  out << text;
  out.flush();
  return exit_code(frame.verdict);
}

}  // namespace relief
