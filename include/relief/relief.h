// Relief as a library: resolve and validate a scene, render it, get the image, the outputs
// asked for and the statistics. This header is the library's whole interface and its manual.
//
// Relief renders procedural fractal landscapes (Schneider, Boldte & Westermann, VMV 2006) on
// CPU cores, deterministically: a scene renders to the same bits on every run and for every
// thread count. The relief command line is built on the same code; a scene, an override or a
// render that the command line refuses is refused here with the same message.
//
// Building against it (CMake):
//
//   find_package(relief 0.1 REQUIRED)
//   target_link_libraries(app PRIVATE relief::relief)  // also makes `app` C++20
//
// The header needs only the standard library (C++20). relief::relief links Relief's static
// libraries and their run-time dependencies (oneTBB, stb); its configuration finds them
// (Debian 12: libtbb-dev, libstb-dev, pkg-config).
//
// A whole program:
//
//   #include <relief/relief.h>
//   #include <fstream>
//   #include <iostream>
//
//   int main() {
//     namespace api = relief::api;
//     const api::Result<api::Scene> scene = api::Scene::load("lava", {"viewport.width=640"});
//     if (!scene) {
//       std::cerr << "error: " << scene.error().message << "\n";
//       return scene.error().exit_code;
//     }
//     const api::Result<api::Rendering> frame = api::render(*scene, {.threads = 4});
//     if (!frame) {
//       std::cerr << "error: " << frame.error().message << "\n";
//       return frame.error().exit_code;
//     }
//     const api::Result<std::vector<unsigned char>> png = api::encode_png(frame->image, *scene);
//     std::ofstream("lava.png", std::ios::binary)
//         .write(reinterpret_cast<const char*>(png->data()), std::streamsize(png->size()));
//   }
//
// Conventions of the whole interface:
// - No exception leaves a function of this header (std::bad_alloc included): whatever can
//   fail returns a Result<T>, which holds either the value or an Error. The Error's message is
//   what `relief` prints after "relief: error: ", and its exit code what `relief` exits with.
//   The functions that return a plain value are noexcept: they allocate a few kilobytes at
//   most, and should even that fail, the program ends (std::terminate).
// - Images are stored rows bottom to top (row 0 is the bottom row of the picture), as
//   OpenGL's window is; pixels are interleaved (RGB: 3 values a pixel). encode_png writes
//   the PNG top to bottom, as every image viewer expects.
// - Every object here is a value: copying a Scene is cheap (it shares its immutable state);
//   functions may be called from several threads at once, on the same Scene too.
// - The scene format (JSON, every field, its range) is documented in Relief's
//   docs/scene-reference.md; `relief scene NAME` prints a preset's effective scene.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace relief::api {

// ---------------------------------------------------------------------------------------------
// Errors

// Exit codes of the relief command line, the convention Error::exit_code follows.
inline constexpr int kExitFailure = 1;   // out of memory although the estimate fitted; a fault
inline constexpr int kExitBadInput = 2;  // bad input, a job too large for its memory budget

// Why an operation failed.
struct Error {
  // kExitBadInput (2): the input is at fault: a scene file, preset name or override that is
  // invalid, a texture file that cannot be used, an option out of range, a render whose
  // estimated memory exceeds its budget. Nothing was done; correct the input and retry.
  // kExitFailure (1): memory ran out although the estimate fitted, or an internal error
  // ("internal error: ..."; please report it with the scene).
  int exit_code = kExitBadInput;
  // One line (no trailing newline) that names the cause: for bad input the JSON path, the
  // value and the allowed range, e.g. "--set grid.width=1: grid.width = 1 is out of range;
  // allowed 2 <= grid.width <= 8192". The relief command line prints it after "relief: error: ".
  std::string message;
};

// Either a T (the operation succeeded) or an Error. Test it before use:
//
//   if (const Result<Scene> s = Scene::load(file)) { use(*s); } else { report(s.error()); }
//
// value(), operator* and operator-> require has_value(); error() requires !has_value().
// Breaking that precondition is a programming error: it prints a line to stderr and aborts
// (this interface throws no exceptions, so it cannot throw one either).
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::in_place_index<0>, std::move(value)) {}
  Result(Error error) : state_(std::in_place_index<1>, std::move(error)) {}

  bool has_value() const noexcept { return state_.index() == 0; }
  explicit operator bool() const noexcept { return has_value(); }

  const T& value() const& { return *checked_value(); }
  T& value() & { return *checked_value(); }
  T&& value() && { return std::move(*checked_value()); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  const T* operator->() const { return checked_value(); }
  T* operator->() { return checked_value(); }

  const Error& error() const {
    const Error* error = std::get_if<1>(&state_);
    if (error == nullptr) {
      fail("error() called on a Result that holds a value");
    }
    return *error;
  }

 private:
  const T* checked_value() const {
    const T* value = std::get_if<0>(&state_);
    if (value == nullptr) {
      fail("value() called on a Result that holds an Error");
    }
    return value;
  }
  T* checked_value() { return const_cast<T*>(std::as_const(*this).checked_value()); }

  [[noreturn]] static void fail(const char* what) {
    std::fprintf(stderr, "relief::api::Result: %s\n", what);
    std::abort();
  }

  std::variant<T, Error> state_;
};

// ---------------------------------------------------------------------------------------------
// Scenes

namespace detail {
struct SceneAccess;
}

// A resolved, completely validated scene: the built-in defaults, then a preset or a scene
// file, then the overrides in order. Immutable; copies share their state.
class Scene {
 public:
  // `scene_or_preset`: a JSON scene file, or a built-in preset name (presets()); "" is the
  // default scene. A regular file of that name wins over a preset; relative texture paths in a
  // file are relative to the file's directory. `overrides`: "KEY=VALUE" assignments such as
  // "terrain.H=0.85" or "camera.position=[0, 900, 0]", applied in order; VALUE is read as JSON
  // when it parses and as a plain string otherwise (quintic). Exactly the semantics of the
  // command line's SCENE and --set options (docs/using-relief.md).
  //
  // Errors (exit code 2): a file that cannot be read or is not JSON, an unknown preset, an
  // unknown key, a wrong type, a value out of range, a rule between fields broken (grid
  // versus margin, near versus far, ...); the message names the source ("--set grid.width=1",
  // "scene file a.json"), the JSON path, the value and the allowed range. Texture files are
  // not opened here: render() reads them.
  static Result<Scene> load(std::string_view scene_or_preset = "",
                            const std::vector<std::string>& overrides = {});

  // The effective scene as JSON, every field present, exactly what `relief scene` prints
  // (two-space indentation, ending in a newline). Loading it from a file gives the same scene.
  std::string to_json() const noexcept;

  // The viewport: the size of the images render() returns, in pixels.
  int width() const noexcept;
  int height() const noexcept;

 private:
  struct Impl;
  explicit Scene(std::shared_ptr<const Impl> impl);
  friend struct detail::SceneAccess;
  std::shared_ptr<const Impl> impl_;
};

// ---------------------------------------------------------------------------------------------
// Rendering

struct RenderOptions {
  // The backend that runs the stages: one of backends(). "simd" (the default) runs the float
  // stages with Highway kernels chosen for the CPU at run time; "reference" is the scalar
  // reference in float, the specification, whose bytes "simd" gives exactly on every target;
  // "reference-double" the same stages in double, for accuracy comparisons.
  std::string backend = "simd";
  // Worker threads for this call: 0 uses the calling thread's oneTBB arena (all cores unless
  // the application limited it); 1 to 1024 runs the call in an arena of that many threads (at
  // most as many as the process may run: the cores, or a tbb::global_control's limit), without
  // limiting anything else in the process. The image is bit-identical for every count.
  int threads = 0;
  // The memory budget of the call in bytes: the render is refused (exit code 2) when its
  // estimated peak memory exceeds it. 0: the memory available on the machine (Linux
  // MemAvailable, and the cgroup's remaining limit where one is set); a larger value than
  // that is lowered to it.
  std::uint64_t max_memory_bytes = 0;
  // Per-pixel outputs beside the sRGB image (Image says what each holds).
  bool linear = false;
  bool depth = false;
  bool primitive = false;
  bool normal = false;
  bool world_height = false;
  bool octaves = false;
};

// A rendered frame, width × height pixels, rows bottom to top (row 0 is the bottom row),
// pixels interleaved. Pixel (x, y) of a buffer with C values a pixel starts at index
// (y * width + x) * C. Only srgb is always filled; every other buffer is empty unless its
// RenderOptions flag was set, and then holds one entry per pixel (three for RGB). Pixels
// that show no terrain (the sky) hold 0 in every output but srgb, linear and primitive, which
// holds kNoPrimitive there.
struct Image {
  static constexpr std::uint32_t kNoPrimitive = 0xffffffffu;

  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> srgb;        // 3 a pixel: the picture, sRGB-encoded
  std::vector<float> linear;             // 3 a pixel: linear radiance after the exposure
  std::vector<float> depth;              // window depth, reverse-Z: 1 at the near plane, 0 at
                                         // infinity (the far plane is infinite)
  std::vector<std::uint32_t> primitive;  // the visible triangle of the projected grid: grid
                                         // cell (i, j) is triangles 2 (j (grid.width - 1) + i)
                                         // and that + 1
  std::vector<float> normal;             // 3 a pixel: interpolated unit normal (nx, ny, nz)
  std::vector<float> world_height;       // terrain height in world units (y up)
  std::vector<float> octaves;            // the interpolated octave count ν of stage 2
};

// One stage of a render (or one group of fused stages): its wall time, whether it ran (false:
// the frame had nothing for it to do) and the work it did, by name: "vertices evaluated",
// "point-octaves summed", "triangles set up", "texture fetches", ... (docs/stages.md,
// "Skipped work"). The names and their order depend on the backend; the counts are the same on
// every run and for every thread count.
struct StageReport {
  std::string name;
  double ms = 0;
  bool ran = true;
  std::vector<std::pair<std::string, std::uint64_t>> counters;
};

// Wall times (milliseconds) and work of a render.
struct Statistics {
  std::vector<StageReport> stages;  // in the order they ran
  double total_ms = 0;              // the frame, start to end
  double setup_ms = 0;  // the scene's resources before the frame: lattice, textures, mipmaps
  std::uint64_t triangles_submitted = 0;  // triangles of the projected grid sent to stage 6
  std::uint64_t triangles_set_up = 0;     // pieces left after culling and clipping
};

struct Rendering {
  Image image;
  Statistics statistics;
};

// Renders `scene`: builds its resources (the noise lattice; proto-textures synthesised or
// read from their PNG files), estimates the memory of the whole render and checks it against
// options.max_memory_bytes, then runs the frame on options.threads threads. The same scene
// and backend give the same bytes on every run and for every thread count.
//
// Errors, exit code 2: an unknown backend (the message lists backends()); threads out of
// range; a texture file that cannot be read or is not a square power-of-two 8-bit PNG; a
// render whose estimated memory (or the rasteriser's bins, counted before they are
// allocated) exceeds the budget: the message gives the estimate by part and the budget.
// Exit code 1: memory ran out although the estimate fitted.
Result<Rendering> render(const Scene& scene, const RenderOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Encoding

// image.srgb as an 8-bit RGB PNG file's bytes (top row first, as PNG stores it), with a
// "Software" text chunk ("relief VERSION"). Error (exit code 2) unless 1 <= width, height <=
// 16384 and srgb holds width × height × 3 bytes.
Result<std::vector<unsigned char>> encode_png(const Image& image);

// The same with the scene that made the image in a text chunk "relief:scene" (scene.to_json(),
// UTF-8; docs/using-relief.md, "Image metadata"): the file `relief render` writes for that scene.
Result<std::vector<unsigned char>> encode_png(const Image& image, const Scene& scene);

// A float buffer of an Image (linear, depth, normal, world_height, octaves) as a PFM file's
// bytes (Portable Float Map, the format of `relief render --float`): "PF" (3 channels) or
// "Pf" (1 channel), "width height" and "-1.0" (little-endian), each on its own line, then the
// values as IEEE-754 binary32, rows bottom to top, exactly as stored. Error (exit code 2)
// unless channels is 1 or 3, 1 <= width, height <= 16384 and `values` holds
// width × height × channels floats.
Result<std::vector<unsigned char>> encode_pfm(int width, int height, int channels,
                                              std::span<const float> values);

// ---------------------------------------------------------------------------------------------
// What is available

// The built-in presets Scene::load accepts by name, sorted; "default" is the default scene.
std::vector<std::string> presets() noexcept;

// The names RenderOptions::backend accepts.
std::vector<std::string> backends() noexcept;

// Relief's version, "MAJOR.MINOR.PATCH", as find_package(relief VERSION) checks it.
std::string_view version() noexcept;

}  // namespace relief::api
