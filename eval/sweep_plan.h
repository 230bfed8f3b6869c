// The configurations of relief sweep (docs/sweep.md): the scene's own settings (the default
// row), then every knob that trades speed for accuracy varied one at a time around them, and a
// few combined moves. A configuration is data: `--set` overrides on the scene, a backend, and a
// supersampling factor, so a new knob is one line of the table in sweep_plan.cc.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "pipeline/frame.h"

namespace relief {

struct SweepConfiguration {
  std::string name;                    // unique, short: "grid 1024", "bias +1", "default"
  std::string knob;                    // "default", "grid", "lod.bias", ..., "combined"
  std::string value;                   // the knob's value: "1024x1024", "+1", "nyquist"
  std::vector<std::string> overrides;  // KEY=VALUE, as --set takes them, in order
  Backend backend = Backend::kSimd;
  int supersample = 1;  // N: the frame rendered N x N times larger, box-filtered to the viewport
  bool is_default = false;
};

// A configuration that is not run, and why (its value is the scene's own, it is out of the
// scene's range, GL cannot be used).
struct SweepSkipped {
  std::string name;
  std::string reason;
};

struct SweepPlan {
  std::vector<SweepConfiguration> configurations;  // the default first
  std::vector<SweepSkipped> skipped;
};

// `quick`: a small subset (the default, grid x1/2 and x2, bias -1 and +1, the other fractional
// setting, supersample 2, reference-double, one combined move) for tests; never GL.
// `gl_unavailable`: why the GL backend cannot run (nullopt: it can); ignored when quick.
SweepPlan plan_sweep(const Scene& scene, bool quick,
                     const std::optional<std::string>& gl_unavailable);

// Why the GL backend cannot run here (no GL in this build, no context: the message), or
// nullopt when it can; opens the shared context to find out.
std::optional<std::string> gl_unavailable_reason();

// The scene with the configuration's overrides applied and validated (throws SceneError), at
// the scene's viewport: the frame the configuration approximates.
Scene configured_scene(const Scene& scene, const SweepConfiguration& configuration);

// The scene that is rendered: configured_scene with the viewport `supersample` times larger.
Scene rendered_scene(const Scene& scene, const SweepConfiguration& configuration);

}  // namespace relief
