#include "eval/sweep_plan.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string_view>

#include "core/limits.h"
#include "core/scene/scene_json.h"
#include "pipeline/gl_backend.h"

namespace relief {

namespace {

// One row of the table: a name, the knob and its value, and what it changes.
struct Variation {
  std::string name;
  std::string knob;
  std::string value;
  std::vector<std::string> overrides;
  Backend backend = Backend::kSimd;
  int supersample = 1;
};

// The grid with its larger side `side`, the other scaled to keep the scene's aspect (at least
// 2 vertices, the scene's minimum; validation catches a margin that no longer fits).
Variation grid_variation(const Scene& scene, int side) {
  const int w = scene.grid.width, h = scene.grid.height;  // >= 2 each (validated)
  const double scale = double(side) / std::max(w, h);
  const int width = std::max(2, int(std::lround(w * scale)));
  const int height = std::max(2, int(std::lround(h * scale)));
  const std::string label =
      w == h ? std::to_string(width) : std::to_string(width) + "x" + std::to_string(height);
  return {"grid " + label,
          "grid",
          std::to_string(width) + "x" + std::to_string(height),
          {"grid.width=" + std::to_string(width), "grid.height=" + std::to_string(height)}};
}

Variation bias_variation(int bias) {
  // Appended, not "+" + string: GCC 12 warns falsely about that operator+ (bug 105651).
  std::string label = bias > 0 ? std::string("+") : std::string();
  label.append(std::to_string(bias));
  return {"bias " + label, "lod.bias", label, {"terrain.lod.bias=" + std::to_string(bias)}};
}

Variation supersample_variation(int n) {
  const std::string label = std::to_string(n) + "x" + std::to_string(n);
  return {label + " samples", "supersample", label, {}, Backend::kSimd, n};
}

Variation backend_variation(Backend backend) {
  const std::string name(backend_name(backend));
  return {name, "backend", name, {}, backend};
}

// Two moves at once: names and overrides joined, the larger supersampling kept.
Variation combined(const Variation& a, const Variation& b) {
  Variation out{a.name + " + " + b.name,
                "combined",
                a.value + " + " + b.value,
                a.overrides,
                a.backend,
                std::max(a.supersample, b.supersample)};
  out.overrides.insert(out.overrides.end(), b.overrides.begin(), b.overrides.end());
  return out;
}

// The largest terrain.last_octave this scene accepts (scene_json.cc: at most kMaxOctaves
// octaves, last * log2 r <= 40), found by validation so the rule lives in one place.
int max_last_octave(const Scene& scene) {
  for (int last = scene.terrain.first_octave + limits::kMaxOctaves - 1;
       last > scene.terrain.first_octave; --last) {
    Scene trial = scene;
    trial.terrain.last_octave = last;
    try {
      validate_scene(trial);
      return last;
    } catch (const SceneError&) {
    }
  }
  return scene.terrain.first_octave;
}

int scene_grid_side(const Scene& scene) {
  return std::max(scene.grid.width, scene.grid.height);
}

std::vector<Variation> quick_variations(const Scene& scene) {
  const int side = scene_grid_side(scene);
  const bool fractional = !scene.terrain.lod.fractional;
  return {grid_variation(scene, side / 2),
          grid_variation(scene, side * 2),
          bias_variation(int(std::lround(scene.terrain.lod.bias)) - 1),
          bias_variation(int(std::lround(scene.terrain.lod.bias)) + 1),
          {fractional ? "fractional octave" : "whole octaves",
           "lod.fractional",
           fractional ? "true" : "false",
           {fractional ? "terrain.lod.fractional=true" : "terrain.lod.fractional=false"}},
          supersample_variation(2),
          backend_variation(Backend::kReferenceDouble),
          combined(grid_variation(scene, side * 2),
                   bias_variation(int(std::lround(scene.terrain.lod.bias)) + 1))};
}

// Every knob of the real-time path that trades speed for accuracy, one at a time. Values equal
// to the scene's own collapse into the default row (plan_sweep).
std::vector<Variation> full_variations(const Scene& scene) {
  std::vector<Variation> out;
  for (int side : {128, 256, 512, 1024, 2048}) {
    out.push_back(grid_variation(scene, side));
  }
  out.push_back({"amplitude", "lod.criterion", "amplitude", {"terrain.lod.criterion=amplitude"}});
  out.push_back({"nyquist", "lod.criterion", "nyquist", {"terrain.lod.criterion=nyquist"}});
  for (int bias : {-2, -1, 0, 1, 2, 3}) {
    out.push_back(bias_variation(bias));
  }
  std::vector<int> lasts = {6, 8, 10, 12, 16, 20};
  lasts.push_back(max_last_octave(scene));
  for (int last : lasts) {
    out.push_back({"octaves to " + std::to_string(last),
                   "last_octave",
                   std::to_string(last),
                   {"terrain.last_octave=" + std::to_string(last)}});
  }
  out.push_back({"fractional octave", "lod.fractional", "true", {"terrain.lod.fractional=true"}});
  out.push_back({"whole octaves", "lod.fractional", "false", {"terrain.lod.fractional=false"}});
  for (const char* interpolant : {"linear", "cubic", "quintic"}) {
    out.push_back({interpolant,
                   "interpolant",
                   interpolant,
                   {std::string("terrain.interpolant=") + interpolant}});
  }
  for (const char* filter : {"trilinear", "bilinear"}) {
    out.push_back({std::string(filter) + " filtering",
                   "texture_filter",
                   filter,
                   {std::string("shading.texture_filter=") + filter}});
  }
  for (int n : {1, 2, 3}) {
    out.push_back(supersample_variation(n));
  }
  for (Backend backend :
       {Backend::kSimd, Backend::kReference, Backend::kReferenceDouble, Backend::kGl}) {
    out.push_back(backend_variation(backend));
  }
  // Cast shadows', sky light's and the reflections' horizon cache (core/sun_horizons.h), where
  // the scene has one.
  const bool reflections = scene.water.reflect_terrain && scene.terrain.water_level;
  if (scene.lighting.shadows || scene.lighting.sky_occlusion || reflections) {
    for (int n : {128, 256, 512, 1024}) {
      out.push_back({"shadows " + std::to_string(n),
                     "shadow_resolution",
                     std::to_string(n),
                     {"lighting.shadow_resolution=" + std::to_string(n)}});
    }
  }
  // The reflections themselves (core/water_reflection.h): their error is the truth's reflected
  // terrain missing from the water.
  if (reflections) {
    out.push_back({"no reflections", "reflect_terrain", "false", {"water.reflect_terrain=false"}});
  }
  // The cloud layer's octaves (core/clouds.h), where the scene has one: each costs a lattice
  // sample per path through the layer.
  if (scene.sky.clouds) {
    for (int n : {2, 3, 5, 8}) {
      out.push_back({"cloud octaves " + std::to_string(n),
                     "cloud_octaves",
                     std::to_string(n),
                     {"sky.clouds.octaves=" + std::to_string(n)}});
    }
  }
  // Combined moves along the axes that buy the most accuracy per millisecond, so that the
  // front is not made of one-knob moves alone.
  const int side = scene_grid_side(scene);
  out.push_back(combined(grid_variation(scene, side * 2), bias_variation(1)));
  out.push_back(combined(grid_variation(scene, side / 2), bias_variation(-1)));
  out.push_back(combined(grid_variation(scene, side * 4), bias_variation(1)));
  out.push_back(combined(grid_variation(scene, side * 2), supersample_variation(2)));
  out.push_back(combined(grid_variation(scene, side / 2), supersample_variation(2)));
  out.push_back(combined(bias_variation(1), supersample_variation(2)));
  const Variation bilinear{
      "bilinear filtering", "texture_filter", "bilinear", {"shading.texture_filter=bilinear"}};
  out.push_back(combined(bias_variation(2), bilinear));
  out.push_back(combined(combined(grid_variation(scene, side * 2), bias_variation(1)), bilinear));
  return out;
}

// What makes two configurations the same frame: the effective scene, the backend, the samples.
std::string identity(const Scene& configured, Backend backend, int supersample) {
  return scene_json_text(configured) + "\n" + std::string(backend_name(backend)) + " " +
         std::to_string(supersample);
}

}  // namespace

Scene configured_scene(const Scene& scene, const SweepConfiguration& configuration) {
  Scene out = scene;
  for (const std::string& assignment : configuration.overrides) {
    apply_scene_layer(out, parse_override(assignment), "--set " + assignment);
  }
  validate_scene(out);
  return out;
}

Scene rendered_scene(const Scene& scene, const SweepConfiguration& configuration) {
  Scene out = configured_scene(scene, configuration);
  out.viewport.width *= configuration.supersample;
  out.viewport.height *= configuration.supersample;
  return out;
}

std::optional<std::string> gl_unavailable_reason() {
  if (!gl_backend_built()) {
    return "this build has no GL side (configured with RELIEF_WITH_GL=OFF)";
  }
  try {
    gl_renderer();
    return std::nullopt;
  } catch (const GlBackendError& e) {
    return std::string("no OpenGL 4.5 context: ") + e.what();
  }
}

SweepPlan plan_sweep(const Scene& scene, bool quick,
                     const std::optional<std::string>& gl_unavailable) {
  SweepPlan plan;
  SweepConfiguration base{"default", "default", "the scene's", {}, Backend::kSimd, 1, true};
  const std::string default_identity = identity(scene, base.backend, base.supersample);
  std::set<std::string> seen = {default_identity};
  plan.configurations.push_back(base);
  for (const Variation& v : quick ? quick_variations(scene) : full_variations(scene)) {
    SweepConfiguration c{v.name, v.knob, v.value, v.overrides, v.backend, v.supersample, false};
    if (c.backend == Backend::kGl && gl_unavailable) {
      plan.skipped.push_back({c.name, *gl_unavailable});
      continue;
    }
    if (const std::string missing = gl_missing_feature(scene);
        c.backend == Backend::kGl && !missing.empty()) {
      plan.skipped.push_back({c.name, missing});
      continue;
    }
    try {
      const Scene configured = configured_scene(scene, c);
      const Scene rendered = rendered_scene(scene, c);  // the viewport's limit too
      const std::string id = identity(configured, c.backend, c.supersample);
      if (!seen.insert(id).second) {
        plan.skipped.push_back({c.name, id == default_identity
                                            ? "the scene's own setting: the default row"
                                            : "the same frame as an earlier row"});
        continue;
      }
      if (std::max(rendered.viewport.width, rendered.viewport.height) > limits::kMaxViewportSide) {
        plan.skipped.push_back({c.name, "the supersampled viewport exceeds " +
                                            std::to_string(limits::kMaxViewportSide) +
                                            " pixels a side"});
        continue;
      }
    } catch (const SceneError& e) {
      plan.skipped.push_back({c.name, e.what()});
      continue;
    }
    plan.configurations.push_back(std::move(c));
  }
  return plan;
}

}  // namespace relief
