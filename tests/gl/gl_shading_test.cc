// Stages 5-9 in OpenGL (gpu/gl_shading.h) against the CPU's frame (pipeline/frame.h, the
// float reference): the same grid buffers drawn by GL must give the same triangles at every
// pixel not within rounding distance of an edge, and an image within the bounds
// docs/gl-shading.md derives. `-s` prints the figures with each passing check.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "core/vertex_culling.h"
#include "gpu/gl_shading.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "raster/rasterize.h"
#include "raster/topology.h"
#include "tests/gl/gl_arithmetic.h"
#include "tests/gl/gl_cloud_envelope.h"
#include "tests/gl/gl_frame_compare.h"
#include "tests/gl/gl_presets.h"
#include "tests/gl/gl_test_context.h"
#include "tests/oracles/whole_frame.h"

namespace relief {
namespace {

// The grid keeps the defaults' ratio of grid to viewport (512 vertices over 1280 pixels).
const std::vector<std::string> kSize = {"viewport.width=256", "viewport.height=160",
                                        "grid.width=128", "grid.height=128"};

// docs/gl-shading.md, "Thresholds", gives the reason for each bound.
constexpr double kEdgeTolerancePixels = 2.0 / 256.0;  // two snapping units

// What both paths draw from: the frame's grid buffers and parameters, with the whole-frame
// stages (tests/oracles/whole_frame.h) for the clip coordinates.
struct FrameInputs {
  TerrainFrame terrain;  // stages 1-6 over every vertex: the drawn values are the frame's
  ShadeParams<float> shade;
  TransformParams<float> transform;
  double camera_y = 0;
};

FrameInputs frame_inputs(const Scene& scene, const SceneResources& resources) {
  FrameInputs in{rasterize_terrain(scene, resources), {}, {}, 0.0};
  const ShadingPlan shading = make_shading_plan(scene, in.terrain.plan, resources.lattice.size);
  in.shade = make_shade_params<float>(shading);
  add_planet_shading(in.terrain.plan, scene.terrain.base_height, in.shade);  // the plane: none
  in.transform = make_terrain_params<float>(in.terrain.plan).transform;
  add_gouraud_lighting(shading, in.transform);  // gradient mode lights the vertices
  in.camera_y = in.terrain.plan.camera.position.y;
  return in;
}

// Triangle t in window coordinates (double, from the float clip coordinates); false for a
// triangle the CPU does not draw or one reaching behind the camera.
bool window_triangle(const FrameInputs& in, const raster::GridTriangles& triangles, std::uint32_t t,
                     std::uint32_t vertex[3], test::WindowTriangle& out) {
  if (t == raster::kNoPrimitive || !triangles.vertices(t, vertex)) {
    return false;
  }
  const double half_w = in.shade.width / 2.0, half_h = in.shade.height / 2.0;
  for (int i = 0; i < 3; ++i) {
    const double w = in.terrain.clip_w[vertex[i]];
    if (!(w > 0.0)) {
      return false;
    }
    out.inv_w[i] = 1.0 / w;
    out.x[i] = in.terrain.clip_x[vertex[i]] / w * half_w + half_w;
    out.y[i] = in.terrain.clip_y[vertex[i]] / w * half_h + half_h;
  }
  return true;
}

// Per pixel with terrain, the tolerance of each interpolated output
// (tests/oracles/gl_interpolation_bound.h).
test::ReferenceTolerances reference_tolerances(const FrameInputs& in, const FrameImage& cpu) {
  test::ReferenceTolerances tol;
  const std::size_t pixels = cpu.primitive.size();
  tol.depth.assign(pixels, INFINITY);
  tol.height.assign(pixels, INFINITY);
  tol.normal.assign(3 * pixels, INFINITY);
  tol.octaves.assign(pixels, INFINITY);
  tol.dx_rounding.assign(pixels, INFINITY);
  tol.dz_rounding.assign(pixels, INFINITY);
  tol.height_rounding.assign(pixels, INFINITY);
  const raster::GridTriangles triangles = in.terrain.triangles();
  const GridBuffers<float>& g = in.terrain.grid;
  for (std::size_t k = 0; k < pixels; ++k) {
    std::uint32_t v[3];
    test::WindowTriangle t;
    if (!window_triangle(in, triangles, cpu.primitive[k], v, t)) {
      continue;
    }
    const double u = double(k % std::size_t(cpu.width)) + 0.5;
    const double w = double(k / std::size_t(cpu.width)) + 0.5;
    const auto values = [&](const AlignedVector<float>& s, double out[3]) {
      for (int i = 0; i < 3; ++i) {
        out[i] = s[v[i]];
      }
    };
    double a[3];
    for (int i = 0; i < 3; ++i) {
      a[i] = in.terrain.clip_z[v[i]] * t.inv_w[i];
    }
    tol.depth[k] = test::depth_tolerance(t, a, u, w);
    values(g.height, a);
    tol.height[k] = test::attribute_tolerance(t, a, u, w);
    tol.height_rounding[k] = test::attribute_rounding(t, a, u, w);
    values(g.nu, a);
    tol.octaves[k] = test::attribute_tolerance(t, a, u, w);
    values(g.dx, a);
    tol.dx_rounding[k] = test::attribute_rounding(t, a, u, w);
    values(g.dz, a);
    tol.dz_rounding[k] = test::attribute_rounding(t, a, u, w);
    // The normal output is renormalised: a component moves by its own error and its share of
    // the length's, over the length.
    const AlignedVector<float>* n[3] = {&g.nx, &g.ny, &g.nz};
    double component[3], length_sq = 0, sum = 0;
    for (int c = 0; c < 3; ++c) {
      values(*n[c], a);
      const double b[3] = {a[0] * t.inv_w[0], a[1] * t.inv_w[1], a[2] * t.inv_w[2]};
      const test::Plane top(t.x, t.y, b), bottom(t.x, t.y, t.inv_w);
      component[c] = top.at(u, w) / bottom.at(u, w);
      length_sq += component[c] * component[c];
      tol.normal[3 * k + c] = test::attribute_tolerance(t, a, u, w);
      sum += tol.normal[3 * k + c];
    }
    const double length = std::sqrt(length_sq);
    for (int c = 0; c < 3; ++c) {
      tol.normal[3 * k + c] =
          (tol.normal[3 * k + c] + std::abs(component[c]) / length * sum) / length +
          8.0 * test::kFloatEpsilon;
    }
  }
  return tol;
}

gpu::GlFrameImage draw_with_gl(const FrameInputs& in, const SceneResources& resources,
                               std::span<const std::uint8_t> need = {}) {
  test::gl_context();
  const gpu::GlGridUpload grid(in.terrain.grid, need);
  const gpu::GlShadeResources textures(ShadeResources{&resources.lattice, resources.textures});
  gpu::GlTerrainDraw draw;
  gpu::GlGridStreams streams = grid.streams();
  const PlanetPlan& planet = in.terrain.plan.planet;
  streams.height_origin = planet.enabled ? static_cast<float>(-planet.altitude) : 0.0f;  // as GL
  return draw.draw(streams, in.transform, in.shade, textures, in.camera_y);
}

// Distance in pixels from (u, v) to the nearest edge of triangle t in window coordinates
// (double): infinite for no triangle, -1 for a triangle the CPU does not draw, 0 (nothing
// claimed) for one reaching behind the camera, whose image is not that of its window vertices.
double edge_distance(const FrameInputs& in, const raster::GridTriangles& triangles, std::uint32_t t,
                     double u, double v) {
  std::uint32_t vertex[3];
  test::WindowTriangle w;
  if (t == raster::kNoPrimitive) {
    return std::numeric_limits<double>::infinity();
  }
  if (!window_triangle(in, triangles, t, vertex, w)) {
    return triangles.vertices(t, vertex) ? 0.0 : -1.0;
  }
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double ex = w.x[j] - w.x[i], ey = w.y[j] - w.y[i];
    const double length_sq = ex * ex + ey * ey;
    const double s = length_sq > 0
                         ? std::clamp(((u - w.x[i]) * ex + (v - w.y[i]) * ey) / length_sq, 0.0, 1.0)
                         : 0.0;
    nearest = std::min(nearest, std::hypot(u - w.x[i] - s * ex, v - w.y[i] - s * ey));
  }
  return nearest;
}

// A pixel may change hands only on the framebuffer's border (llvmpipe clips there in float)
// or within two snapping units of an edge of the CPU's or GL's triangle there.
std::function<bool(std::size_t)> edge_rule(const FrameInputs& in, const FrameImage& cpu,
                                           const gpu::GlFrameImage& gl,
                                           std::span<const std::uint8_t> need = {}) {
  return [&in, &cpu, &gl, need](std::size_t k) {
    const int width = cpu.width, height = cpu.height;
    const int px = int(k % std::size_t(width)), py = int(k / std::size_t(width));
    if (px == 0 || py == 0 || px == width - 1 || py == height - 1) {
      return true;
    }
    const raster::GridTriangles triangles{in.terrain.plan.layout, in.terrain.grid.valid, need};
    const double d_cpu = edge_distance(in, triangles, cpu.primitive[k], px + 0.5, py + 0.5);
    const double d_gl = edge_distance(in, triangles, gl.primitive[k], px + 0.5, py + 0.5);
    if (d_cpu < 0.0 || d_gl < 0.0) {
      return false;  // a triangle the CPU does not draw
    }
    return std::min(d_cpu, d_gl) <= kEdgeTolerancePixels;
  };
}

void check_preset(const std::string& preset, const std::vector<std::string>& size) {
  const Scene scene = resolve_scene(preset, size);
  const SceneResources resources = load_scene_resources(scene);
  FrameRequest request;
  request.outputs = {true, true, true, true, true, true};
  const Frame cpu = render_frame(scene, resources, request);
  const FrameInputs in = frame_inputs(scene, resources);
  const gpu::GlFrameImage gl = draw_with_gl(in, resources);
  // Bilinear filtering's level step, sized by the CPU's trilinear frame (level_switch_envelope).
  std::vector<double> envelope;
  if (scene.shading.texture_filter == TextureFilter::kBilinear) {
    Scene trilinear = scene;
    trilinear.shading.texture_filter = TextureFilter::kTrilinear;
    envelope =
        test::level_switch_envelope(cpu.image, render_frame(trilinear, resources, request).image);
  }
  const test::ReferenceTolerances tolerances = reference_tolerances(in, cpu.image);
  if (scene.sky.clouds) {  // the layer's staircase over GL's positions (gl_cloud_envelope.h)
    const std::vector<double> clouds =
        test::cloud_position_envelope(in.terrain, in.shade, resources, tolerances.dx_rounding,
                                      tolerances.dz_rounding, tolerances.height_rounding);
    envelope.resize(clouds.size(), 0.0);
    for (std::size_t i = 0; i < clouds.size(); ++i) {
      envelope[i] += clouds[i];
    }
  }
  const test::FrameDifference d = test::compare_frames(cpu.image, gl, in.camera_y, tolerances,
                                                       edge_rule(in, cpu.image, gl), envelope);
  std::string setting;  // what the call sets beyond the size
  for (std::size_t i = kSize.size(); i < size.size(); ++i) {
    setting += " with " + size[i];
  }
  INFO(test::gl_context().renderer() << ", " << preset << setting << ": " << d);
  CHECK(d.unexplained == 0);
  CHECK(d.encode_mismatches == 0);
  CHECK(d.srgb_beyond == 0);
  CHECK(d.srgb_psnr >= d.srgb_allowed_psnr);
  CHECK(d.linear_ratio <= 1.0);
  CHECK(d.background_relative <= test::kBackgroundRelative);
  // Where the draw divides and takes square roots as the CPU does (llvmpipe), the background
  // (sky, fog, open water, the cloud layer over them) is the same operations on the same
  // floats: the CPU's bits (docs/gl-shading.md, "Background").
  if (test::gl_arithmetic().draw_exact() && test::gl_arithmetic().precise_unfused) {
    CHECK(d.background_exact == d.background);
  }
  CHECK(d.depth_ratio <= 1.0);
  CHECK(d.height_ratio <= 1.0);
  CHECK(d.normal_ratio <= 1.0);
  CHECK(d.octaves_ratio <= 1.0);
}

TEST_CASE("glFramesOfEveryPresetMatchTheCpuFrameWithinTheDocumentedBounds", "[gl]") {
  for (const std::string& preset : test::gl_preset_names()) {
    check_preset(preset, kSize);
  }
  // The nearest mip level (GL_LINEAR_MIPMAP_NEAREST) on both sides.
  std::vector<std::string> bilinear = kSize;
  bilinear.push_back("shading.texture_filter=\"bilinear\"");
  check_preset("alpine", bilinear);
  // Gradient shading: the vertex shader's Lambert term, its interpolation and the gradient.
  for (const char* preset : {"default", "lake", "planet"}) {
    std::vector<std::string> gradient = kSize;
    gradient.push_back("shading.mode=\"gradient\"");
    check_preset(preset, gradient);
  }
  // The cloud layer (clouds.glsl) beside the clouds preset's view from above: seen from below
  // over open water, under the atmosphere, over the gradient's Gouraud light.
  const std::pair<const char*, const char*> clouded[] = {{"lake", "sky.clouds={\"altitude\": 900}"},
                                                         {"clouds", "sky.atmosphere={}"},
                                                         {"clouds", "shading.mode=\"gradient\""}};
  for (const auto& [preset, setting] : clouded) {
    std::vector<std::string> size = kSize;
    size.push_back(setting);
    check_preset(preset, size);
  }
}

TEST_CASE("glCloudLayersInHostileSettingsMatchTheCpuFrameWithinTheDocumentedBounds", "[gl]") {
  // The camera inside an opaque layer, a layer reaching through the terrain, a layer under the
  // camera, an octave-rich warped one; each under a zenith sun, a set sun and one on the
  // horizon (clouds.glsl's guards: the sun's floored sine, the path's floored slope).
  for (const char* clouds :
       {"sky.clouds={\"altitude\": 650, \"thickness\": 100, \"density\": 100, \"coverage\": 1}",
        "sky.clouds={\"altitude\": -500, \"thickness\": 3000, \"coverage\": 0.7}",
        "sky.clouds={\"altitude\": 150, \"thickness\": 250, \"coverage\": 0.5}",
        "sky.clouds={\"octaves\": 8, \"warp\": 16, \"scale\": 400}"}) {
    for (const char* sun : {"lighting.sun_elevation_deg=90", "lighting.sun_elevation_deg=-30",
                            "lighting.sun_elevation_deg=0"}) {
      std::vector<std::string> size = kSize;
      size.push_back(sun);
      size.push_back(clouds);
      check_preset("default", size);
    }
  }
}

TEST_CASE("glDrawsOnlyTheTrianglesWhoseVerticesAllHaveKDraw", "[gl]") {
  // The need stream (core/vertex_culling.h) as the compute stages will pass it: a triangle is
  // drawn only if its three vertices have kDraw. Here a pattern clears kDraw on every fifth
  // diagonal; GL's triangles must be those the CPU's rasteriser draws from the same flags.
  const Scene scene = resolve_scene("lake", kSize);
  const SceneResources resources = load_scene_resources(scene);
  const FrameInputs in = frame_inputs(scene, resources);
  const GridLayout& layout = in.terrain.plan.layout;
  std::vector<std::uint8_t> need(layout.size(), 0);
  for (int j = 0; j < layout.height; ++j) {
    for (int i = 0; i < layout.width; ++i) {
      need[layout.index(i, j)] = (i + 2 * j) % 5 == 0 ? kEvaluate : (kEvaluate | kDraw);
    }
  }
  raster::VisibilityBuffer cpu;
  raster::rasterize(in.terrain.state, in.terrain.clip(),
                    raster::GridTriangles{layout, in.terrain.grid.valid, need}, cpu);
  const gpu::GlFrameImage gl = draw_with_gl(in, resources, need);
  FrameImage cpu_image;
  cpu_image.width = cpu.width;
  cpu_image.height = cpu.height;
  cpu_image.primitive.assign(cpu.primitive.begin(), cpu.primitive.end());
  const auto explained = edge_rule(in, cpu_image, gl, need);
  std::size_t differ = 0, unexplained = 0, covered = 0;
  for (std::size_t k = 0; k < gl.primitive.size(); ++k) {
    covered += cpu.primitive[k] != raster::kNoPrimitive;
    if (cpu.primitive[k] != gl.primitive[k]) {
      ++differ;
      unexplained += !explained(k);
    }
  }
  INFO(covered << " pixels covered, " << differ << " with another triangle, " << unexplained
               << " unexplained");
  CHECK(covered > 0);
  CHECK(unexplained == 0);
}

TEST_CASE("glDrawRefusesInputsThatDoNotFit", "[gl]") {
  const Scene scene = resolve_scene("default", kSize);
  const SceneResources resources = load_scene_resources(scene);
  const FrameInputs in = frame_inputs(scene, resources);
  test::gl_context();
  const gpu::GlGridUpload grid(in.terrain.grid);
  const gpu::GlShadeResources textures(ShadeResources{&resources.lattice, resources.textures});
  gpu::GlTerrainDraw draw;
  ShadeParams<float> shade = in.shade;
  shade.layer_count = int(resources.textures.size()) + 1;
  CHECK_THROWS_WITH(draw.draw(grid.streams(), in.transform, shade, textures, in.camera_y),
                    Catch::Contains("layer_count"));
  shade = in.shade;
  shade.width = 0;
  CHECK_THROWS_WITH(draw.draw(grid.streams(), in.transform, shade, textures, in.camera_y),
                    Catch::Contains("image"));
  gpu::GlGridStreams streams = grid.streams();
  streams.height = 0;
  CHECK_THROWS_WITH(draw.draw(streams, in.transform, in.shade, textures, in.camera_y),
                    Catch::Contains("stream"));
  streams = grid.streams();
  streams.layout.height = 1;
  CHECK_THROWS_WITH(draw.draw(streams, in.transform, in.shade, textures, in.camera_y),
                    Catch::Contains("2 x 2"));
  // The draw still works after refusing.
  CHECK(draw.draw(grid.streams(), in.transform, in.shade, textures, in.camera_y).width ==
        in.shade.width);
}

// The figures of docs/gl-shading.md at the README's image size (hidden, [gl-figures]: run it by
// name).
TEST_CASE("glFramesAtTheReadmeSize", "[.][gl-figures]") {
  for (const std::string& preset : test::gl_preset_names()) {
    check_preset(preset, {"viewport.width=480", "viewport.height=384"});
  }
}

}  // namespace
}  // namespace relief
