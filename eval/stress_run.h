// One case of the stability stress suite (stress_cases.h) run on each backend, with its checks:
// every grid buffer (stages 2-4 at every vertex) and every per-pixel output finite, the peak
// memory within the render's estimate (job_memory.h), refusals where the case expects them
// and nowhere else, and on the distance axis the float error against reference-double within
// the bounds below. docs/stress.md, "Stability stress suite", shows the table.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "eval/stress_cases.h"
#include "pipeline/frame.h"
#include "pipeline/memory_budget.h"

namespace relief {

// Bounds of the float backends against reference-double at the same scene (the distance axis
// checks them; the other axes report the figures). Heights: the largest difference at a
// vertex valid in both grids, relative to terrain.amplitude. The default frame measures about
// 5e-5 (docs/scene-limits.md: float stage 3 within 1e-4 of double at the same inputs, plus
// stage 2's rounding of the vertex positions). Image: the share of sRGB bytes more than two
// codes apart, which moves only at silhouettes where a vertex's rounding moves coverage
// (tests/pipeline/frame_test.cc's bound).
inline constexpr double kStressHeightErrorBound = 2e-4;
inline constexpr double kStressSrgbShareBound = 0.02;

// What the render estimate (job_memory.h) leaves out on purpose, allowed on top of it when the
// measured peak is checked: the set-up triangles' first slab page (a 2 MiB huge page however
// few triangles there are), each worker thread's tile scratch (64 x 64 pixels of about twenty
// attributes, 0.7 MiB in double, with its visibility and bins: 1 MiB), and for the GL
// backend the driver's own per-frame state (llvmpipe: command buffers, shader variants;
// measured up to 6 MiB).
inline constexpr std::uintmax_t kStressFixedAllowanceBytes = std::uintmax_t{2} << 20;
inline constexpr std::uintmax_t kStressThreadAllowanceBytes = std::uintmax_t{1} << 20;
inline constexpr std::uintmax_t kStressGlAllowanceBytes = std::uintmax_t{16} << 20;
std::uintmax_t stress_memory_allowance(Backend backend);

enum class StressStatus {
  kOk,       // rendered; the checks are in `failures`
  kRefused,  // refused before any work (scene error, memory estimate, GL limit): `message`
  kSkipped,  // the backend cannot run here (no GL): `message`
};

struct StressRow {
  std::string axis, name;
  std::string backend;  // "all" for a case the scene validation refuses
  StressStatus status = StressStatus::kOk;
  std::string message;
  std::vector<std::string> failures;             // checks that did not hold; empty: passed
  double frame_ms = 0;                           // render_frame's total
  std::uint64_t values = 0;                      // grid and per-pixel values checked
  std::uint64_t nonfinite = 0;                   // of them NaN or infinite
  std::uintmax_t estimate_bytes = 0;             // estimate_render_memory, every output requested
  std::optional<std::uintmax_t> measured_bytes;  // peak resident growth (process_memory.h)
  std::optional<double> height_error;            // max |h - h_double| / amplitude
  std::optional<double> srgb_share;              // sRGB bytes > 2 codes from the double frame
  std::optional<double> psnr_db;                 // of the sRGB image against the double frame
  // The frame's sRGB image (rows bottom to top), when StressSettings::keep_images.
  int width = 0, height = 0;
  std::vector<std::uint8_t> srgb;

  bool passed() const { return failures.empty(); }
};

struct StressSettings {
  std::vector<Backend> backends;  // reference-double, when listed, runs first: it is the truth
  MemoryBudget budget;            // a backend whose estimate exceeds it is refused
  std::string gl_unavailable;     // non-empty: the gl backend is skipped with this reason
  bool measure_memory = true;     // and peak_memory_measurable()
  bool keep_images = false;       // StressRow::srgb and its size
};

// Applies the case's overrides to `base` and runs it on every backend of `settings`: one row
// per backend, or one row ("all") when the scene refuses the case.
std::vector<StressRow> run_stress_case(const Scene& base, const StressCase& stress_case,
                                       const StressSettings& settings);

// Renders one small frame of `base` on each backend of `settings`, so that what every process
// does once (worker threads, GL context and shader programs) is not measured as a case's peak.
void warm_up_stress_backends(const Scene& base, const StressSettings& settings);

// The backends of this build, and why gl cannot run (empty when it can): no GL side, or no
// context could be made.
std::vector<Backend> stress_backends(std::string& gl_unavailable);

}  // namespace relief
