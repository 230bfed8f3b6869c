// include/relief/relief.h over the frame (pipeline/frame.h): the library other programs link.
// Every internal exception is caught here and becomes an Error with the message the relief
// command line prints (tools/cli.cc), so none crosses the interface.
#include "relief/relief.h"

#include <algorithm>
#include <chrono>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "core/limits.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "pipeline/frame.h"
#include "pipeline/gl_backend.h"
#include "pipeline/job_memory.h"
#include "pipeline/memory_budget.h"
#include "pipeline/scene_resources.h"

#ifndef RELIEF_VERSION
#error "RELIEF_VERSION is set by pipeline/CMakeLists.txt"
#endif

namespace relief::api {

struct Scene::Impl {
  relief::Scene scene;
};

namespace detail {

struct SceneAccess {
  static Scene make(relief::Scene scene) {
    return Scene(std::make_shared<const Scene::Impl>(Scene::Impl{std::move(scene)}));
  }
  static const relief::Scene& internal(const Scene& scene) { return scene.impl_->scene; }
};

}  // namespace detail

namespace {

constexpr int kMaxThreads = 1024;  // the command line's --threads range

// Runs `body` (returning Result<T>) and turns every exception into the Error the command line
// reports for it (tools/cli.cc's run_cli).
template <class Body>
auto guarded(Body&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const SceneError& e) {
    return Error{kExitBadInput, e.what()};
  } catch (const MemoryLimitError& e) {
    return Error{kExitBadInput, e.what()};
  } catch (const GlBackendError& e) {
    return Error{kExitBadInput, e.what()};
  } catch (const std::bad_alloc&) {
    // The estimate (job_memory.h) missed, or another process took the memory meanwhile.
    return Error{kExitFailure,
                 "out of memory. Lower the image or grid size, or free memory and try again."};
  } catch (const std::exception& e) {
    std::string message = "internal error: ";
    message.append(brief_text(e.what(), 3 * kBriefChars));
    message.append(". Please report this with the scene.");
    return Error{kExitFailure, std::move(message)};
  } catch (...) {
    return Error{kExitFailure, "internal error: an unknown exception. Please report this."};
  }
}

// The budget of a call: the machine's available memory, or max_memory_bytes when lower.
MemoryBudget call_budget(std::uint64_t max_memory_bytes, bool& from_option) {
  MemoryBudget budget = memory_budget(std::nullopt, "");
  from_option = max_memory_bytes != 0 && max_memory_bytes < budget.bytes;
  if (from_option) {
    budget.bytes = max_memory_bytes;
    budget.source = "RenderOptions::max_memory_bytes";
  }
  return budget;
}

std::string join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) {
    if (!text.empty()) {
      text.append(", ");
    }
    text.append(name);
  }
  return text;
}

// Moves `from` into `to` when the output was asked for, checking its size; anything not asked
// for stays out of the Image.
template <class T>
void hand_over(bool requested, std::vector<T>& from, std::vector<T>& to, std::size_t size,
               const char* name) {
  if (!requested) {
    return;
  }
  if (from.size() != size) {
    std::string message = "the backend returned ";
    message.append(std::to_string(from.size()))
        .append(" values of the ")
        .append(name)
        .append(" output; expected ")
        .append(std::to_string(size));
    throw std::logic_error(message);
  }
  to = std::move(from);
}

Rendering render_scene(const relief::Scene& scene, Backend backend, const RenderOptions& options) {
  const int width = scene.viewport.width;
  const int height = scene.viewport.height;
  FrameRequest request;
  request.backend = backend;
  request.outputs.linear = options.linear;
  request.outputs.depth = options.depth;
  request.outputs.primitive = options.primitive;
  request.outputs.normal = options.normal;
  request.outputs.world_height = options.world_height;
  request.outputs.octaves = options.octaves;
  const MemoryEstimate estimate = estimate_render_memory(scene, backend, request.outputs);
  bool from_option = false;
  const MemoryBudget budget = call_budget(options.max_memory_bytes, from_option);
  check_memory(estimate, budget, "this render",
               from_option
                   ? render_memory_advice(scene) + ", or raise RenderOptions::max_memory_bytes"
                   : render_memory_advice(scene));

  const auto setup_start = std::chrono::steady_clock::now();
  const SceneResources resources = load_scene_resources(scene);  // validates texture files
  const double setup_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - setup_start)
          .count();

  request.max_bin_bytes = memory_left(estimate, budget);
  Frame frame = render_frame(scene, resources, request);

  FrameImage& from = frame.image;
  if (from.width != width || from.height != height) {
    throw std::logic_error("the backend returned an image of another size than the viewport");
  }
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  Rendering out;
  Image& image = out.image;
  image.width = width;
  image.height = height;
  hand_over(true, from.srgb, image.srgb, 3 * pixels, "sRGB");
  hand_over(options.linear, from.linear, image.linear, 3 * pixels, "linear");
  hand_over(options.depth, from.depth, image.depth, pixels, "depth");
  hand_over(options.primitive, from.primitive, image.primitive, pixels, "primitive");
  hand_over(options.normal, from.normal, image.normal, 3 * pixels, "normal");
  hand_over(options.world_height, from.world_height, image.world_height, pixels, "world height");
  hand_over(options.octaves, from.octaves, image.octaves, pixels, "octaves");

  Statistics& stats = out.statistics;
  for (StageTime& stage : frame.stats.stages) {
    StageReport report{std::move(stage.name), stage.ms, stage.ran, {}};
    for (WorkCounter& counter : stage.counters) {
      report.counters.emplace_back(std::move(counter.name), counter.value);
    }
    stats.stages.push_back(std::move(report));
  }
  stats.total_ms = frame.stats.total_ms;
  stats.setup_ms = setup_ms;
  stats.triangles_submitted = frame.stats.raster.triangles;  // the grid's: culling is counted
                                                             // in the stages' counters
  stats.triangles_set_up = frame.stats.raster.setup;
  return out;
}

// Width and height of an image handed to an encoder, checked like a viewport.
std::optional<Error> check_image_size(const char* function, int width, int height) {
  if (width < 1 || height < 1 || width > limits::kMaxViewportSide ||
      height > limits::kMaxViewportSide) {
    std::string message = function;
    message.append(": the image is ")
        .append(std::to_string(width))
        .append("x")
        .append(std::to_string(height))
        .append("; allowed 1 <= width, height <= ")
        .append(std::to_string(limits::kMaxViewportSide));
    return Error{kExitBadInput, std::move(message)};
  }
  return std::nullopt;
}

Error size_mismatch(const char* function, std::size_t actual, std::size_t expected,
                    const char* what) {
  std::string message = function;
  message.append(": the buffer holds ")
      .append(std::to_string(actual))
      .append(" values; expected ")
      .append(std::to_string(expected))
      .append(" (")
      .append(what)
      .append(")");
  return Error{kExitBadInput, std::move(message)};
}

}  // namespace

Scene::Scene(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

Result<Scene> Scene::load(std::string_view scene_or_preset,
                          const std::vector<std::string>& overrides) {
  return guarded([&]() -> Result<Scene> {
    return detail::SceneAccess::make(resolve_scene(scene_or_preset, overrides));
  });
}

std::string Scene::to_json() const noexcept {
  return scene_json_text(impl_->scene);  // as `relief scene` prints it (tools/cli.cc)
}

int Scene::width() const noexcept {
  return impl_->scene.viewport.width;
}
int Scene::height() const noexcept {
  return impl_->scene.viewport.height;
}

Result<Rendering> render(const Scene& scene, const RenderOptions& options) {
  return guarded([&]() -> Result<Rendering> {
    const std::optional<Backend> backend = backend_from_name(options.backend);
    if (!backend) {
      std::string message = "RenderOptions::backend \"";
      message.append(brief_text(options.backend))
          .append("\" is unknown; allowed: ")
          .append(join(backends()));
      return Error{kExitBadInput, std::move(message)};
    }
    if (options.threads < 0 || options.threads > kMaxThreads) {
      std::string message = "RenderOptions::threads = ";
      message.append(std::to_string(options.threads))
          .append(" is out of range; allowed 0 (all cores) or 1 <= value <= ")
          .append(std::to_string(kMaxThreads));
      return Error{kExitBadInput, std::move(message)};
    }
    const relief::Scene& internal = detail::SceneAccess::internal(scene);
    if (options.threads == 0) {
      return render_scene(internal, *backend, options);
    }
    // An arena of its own limits this call only; a tbb::global_control would limit every
    // thread of the process, the application's own work and other renders included. More
    // threads than the process may run (the cores, or a global_control's limit) would only
    // make oneTBB print a warning: the image is the same for every count.
    const std::size_t allowed =
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    tbb::task_arena arena(static_cast<int>(std::min<std::size_t>(
        static_cast<std::size_t>(options.threads), std::max<std::size_t>(allowed, 1))));
    return arena.execute([&] { return render_scene(internal, *backend, options); });
  });
}

namespace {

// The PNG with image_metadata.h's text: Software, and the scene when there is one.
Result<std::vector<unsigned char>> encode_png_with(const Image& image, const relief::Scene* scene) {
  return guarded([&]() -> Result<std::vector<unsigned char>> {
    if (std::optional<Error> error = check_image_size("encode_png", image.width, image.height)) {
      return *std::move(error);
    }
    const std::size_t expected = std::size_t(image.width) * std::size_t(image.height) * 3;
    if (image.srgb.size() != expected) {
      return size_mismatch("encode_png", image.srgb.size(), expected, "3 sRGB bytes a pixel");
    }
    const std::vector<ImageText> text = scene ? scene_metadata(*scene) : software_metadata();
    std::vector<unsigned char> png = encode_png_rgb(image.width, image.height, image.srgb, text);
    if (png.empty()) {  // the encoder reports nothing else (png_encoder.h)
      throw std::bad_alloc();
    }
    return png;
  });
}

}  // namespace

Result<std::vector<unsigned char>> encode_png(const Image& image) {
  return encode_png_with(image, nullptr);
}

Result<std::vector<unsigned char>> encode_png(const Image& image, const Scene& scene) {
  return encode_png_with(image, &detail::SceneAccess::internal(scene));
}

Result<std::vector<unsigned char>> encode_pfm(int width, int height, int channels,
                                              std::span<const float> values) {
  return guarded([&]() -> Result<std::vector<unsigned char>> {
    if (std::optional<Error> error = check_image_size("encode_pfm", width, height)) {
      return *std::move(error);
    }
    if (channels != 1 && channels != 3) {
      std::string message = "encode_pfm: channels = ";
      message.append(std::to_string(channels)).append("; allowed 1 or 3");
      return Error{kExitBadInput, std::move(message)};
    }
    const std::size_t row = std::size_t(width) * std::size_t(channels);
    if (values.size() != row * std::size_t(height)) {
      return size_mismatch("encode_pfm", values.size(), row * std::size_t(height),
                           channels == 1 ? "1 float a pixel" : "3 floats a pixel");
    }
    return relief::encode_pfm(width, height, channels, values, row);
  });
}

std::vector<std::string> presets() noexcept {
  return preset_names();
}

std::vector<std::string> backends() noexcept {
  std::vector<std::string> names;
  for (const std::string_view name : backend_names()) {
    names.emplace_back(name);
  }
  return names;
}

std::string_view version() noexcept {
  return RELIEF_VERSION;
}

}  // namespace relief::api
