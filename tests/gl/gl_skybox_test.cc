// The skybox on the GL backend (gpu/shaders/sky.glsl) against the CPU's (core/skybox.cc):
// the same face, texels and filter, so every background pixel (the sky, and open water
// reflecting it) has the CPU's bits where the draw divides as the CPU does (llvmpipe). On a
// GL whose division is not correctly rounded (GLSL 4.50 §4.7.1 allows 2.5 ulps) a face
// coordinate moves, and a sky pixel by at most that move times the face's steepest step
// between neighbouring texels, derived below from the GL's measured division.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "core/shading_plan.h"
#include "core/stage_params.h"
#include "pipeline/frame.h"
#include "pipeline/scene_resources.h"
#include "tests/gl/gl_arithmetic.h"
#include "tests/gl/gl_frame_compare.h"
#include "tests/gl/gl_test_context.h"
#include "tests/oracles/gl_interpolation_bound.h"
#include "tests/support/skybox_support.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// The largest difference between neighbouring texels of any face and channel.
double steepest_step(const Skybox& box) {
  double step = 0;
  for (int f = 0; f < 6; ++f) {
    for (int r = 0; r < box.size; ++r) {
      for (int c = 0; c < box.size; ++c) {
        for (int k = 0; k < 3; ++k) {
          const double v = box.texel(f, r, c)[k];
          if (c + 1 < box.size) {
            step = std::max(step, std::abs(v - box.texel(f, r, c + 1)[k]));
          }
          if (r + 1 < box.size) {
            step = std::max(step, std::abs(v - box.texel(f, r + 1, c)[k]));
          }
        }
      }
    }
  }
  return step;
}

TEST_CASE("glSkyboxBackgroundsHaveTheCpusBitsOrStayWithinTheDivisionsBound", "[gl][skybox]") {
  const test::TempDir dir("gl-skybox");
  const auto faces = test::write_checker_faces(dir.path(), 64, 4);
  const test::GlArithmetic& gl = test::gl_arithmetic();
  for (const char* preset : {"lake", "sunset"}) {
    for (const std::string extra : {"", ", \"sun_disc\": false"}) {
      const Scene scene = resolve_scene(
          preset, {"viewport.width=160", "viewport.height=120", "grid.width=96", "grid.height=96",
                   "lighting.shadows=false", "lighting.sky_occlusion=false",
                   test::skybox_override(faces, extra)});
      const SceneResources resources = load_scene_resources(scene);
      FrameRequest request;
      request.outputs.linear = true;
      request.outputs.primitive = true;
      const Frame cpu = render_frame(scene, resources, request);
      request.backend = Backend::kGl;
      const Frame gpu = render_frame(scene, resources, request);
      // Which background pixels look above the horizon (the sky; below it: open water): the
      // background's ray in double, as stage 8 forms it.
      const FramePlan plan = make_frame_plan(scene, resources.terrain_values(), nullptr);
      const ShadeParams<double> p =
          make_shade_params<double>(make_shading_plan(scene, plan, resources.lattice.size));
      // A face coordinate s = (q + 1) / 2 with q = sc / |ma| in [-1, 1]: the division's error
      // (its ulps of 2^-24 at most), the direction's and s's own rounding (an ulp each), in
      // texels of the face; the bilinear filter moves by at most that times the steepest step.
      const double moved = (gl.division_ulps + 2.0) * 0x1.0p-24 * resources.skybox->size;
      const double step = steepest_step(*resources.skybox) * p.exposure;
      std::size_t background = 0, exact = 0, sky = 0, not_finite = 0;
      double worst = 0;
      for (std::size_t k = 0; k < cpu.image.primitive.size(); ++k) {
        if (cpu.image.primitive[k] != raster::kNoPrimitive ||
            gpu.image.primitive[k] != raster::kNoPrimitive) {
          continue;
        }
        ++background;
        const int py = int(k / std::size_t(p.width));
        const double sy = (2.0 * (py + 0.5) / p.height - 1.0) * p.tan_half_fov_y;
        const bool above = p.forward[1] + sy * p.up[1] > 1e-6;  // the px term is 0: no roll
        bool same = true;
        for (int c = 0; c < 3; ++c) {
          const double a = cpu.image.linear[3 * k + c], b = gpu.image.linear[3 * k + c];
          same = same && a == b;
          not_finite += std::isfinite(b) ? 0 : 1;
          if (above) {
            const double allowed =
                moved * step + 4.0 * test::float_ulp(a) + test::kBackgroundRelative * std::abs(a);
            worst = std::max(worst, std::abs(a - b) / allowed);
          }
        }
        exact += same;
        sky += above;
      }
      INFO(test::gl_context().renderer()
           << ", " << preset << extra << ": " << background << " background pixels, " << exact
           << " exact, " << sky << " sky, worst " << worst << " of the bound");
      REQUIRE(sky > 1000);
      // Open water below the horizon is checked bit for bit where the draw divides as the CPU
      // does; elsewhere its wave normals take other roundings too, and only finiteness is.
      CHECK(not_finite == 0);
      REQUIRE(background > sky);  // open water too
      if (gl.draw_exact()) {
        CHECK(exact == background);
      } else {
        CHECK(worst <= 1.0);
      }
    }
  }
}

}  // namespace
}  // namespace relief
