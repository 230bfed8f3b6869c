// The skybox (core/skybox.h) against OpenGL 4.5's cube map rules, written here from Table 8.19
// in the other direction: a face and (s, t) give a direction, which must come back as that
// face and (s, t); and the filter against a linear function of the texel position, which
// bilinear filtering reproduces exactly between texel centres and clamps past them.
#include <algorithm>
#include <array>
#include <cmath>

#include <catch2/catch.hpp>

#include "core/scene/scene_json.h"
#include "core/shading_plan.h"
#include "core/sky.h"
#include "core/skybox.h"
#include "core/stage_params.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

// Table 8.19 read backwards: the point of face `face` at (s, t) on the cube [-1, 1]^3.
Vec3<double> cube_point(int face, double s, double t) {
  const double sc = 2 * s - 1, tc = 2 * t - 1;
  switch (face) {
    case 0:
      return {1, -tc, -sc};  // +x: sc = -rz, tc = -ry
    case 1:
      return {-1, -tc, sc};  // -x: sc = +rz, tc = -ry
    case 2:
      return {sc, 1, tc};  // +y: sc = +rx, tc = +rz
    case 3:
      return {sc, -1, -tc};  // -y: sc = +rx, tc = -rz
    case 4:
      return {sc, -tc, 1};  // +z: sc = +rx, tc = -ry
    default:
      return {-sc, -tc, -1};  // -z: sc = -rx, tc = -ry
  }
}

// A box whose texel (face f, row r, column c) holds (c + 0.5, r + 0.5, 100 f): linear in the
// texel position, so that the filter gives (clamp(s n, 1/2, n - 1/2), clamp(t n, ...), 100 f).
Skybox ramp_box(int n) {
  Skybox box;
  box.size = n;
  box.texels.resize(18 * std::size_t(n) * n);
  for (int f = 0; f < 6; ++f) {
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) {
        float* texel = box.texels.data() + 3 * ((std::size_t(f) * n + r) * n + c);
        texel[0] = float(c + 0.5);
        texel[1] = float(r + 0.5);
        texel[2] = float(100 * f);
      }
    }
  }
  return box;
}

TEST_CASE("eachFacePointComesBackAsItsFaceAndCoordinates", "[skybox]") {
  test::TestRandom random(11);
  for (int face = 0; face < 6; ++face) {
    for (int k = 0; k < 200; ++k) {
      // Away from the face's edges, where another face may take a tie.
      const double s = random.uniform(0.01, 0.99), t = random.uniform(0.01, 0.99);
      const Vec3<double> p = cube_point(face, s, t);
      const double scale = random.uniform(1e-3, 1e3);  // the length does not matter
      const auto d = cube_face_coordinate(Vec3<double>{p.x * scale, p.y * scale, p.z * scale});
      INFO("face " << face << " s " << s << " t " << t);
      REQUIRE(d.face == face);
      CHECK(d.s == Approx(s).margin(1e-12));
      CHECK(d.t == Approx(t).margin(1e-12));
      const auto f = cube_face_coordinate(Vec3<float>{float(p.x), float(p.y), float(p.z)});
      REQUIRE(f.face == face);
      CHECK(f.s == Approx(s).margin(1e-6));
      CHECK(f.t == Approx(t).margin(1e-6));
    }
  }
}

TEST_CASE("theAxesHitTheFaceCentresAndTiesGoToXThenY", "[skybox]") {
  const std::array<Vec3<float>, 6> axes = {
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  for (int face = 0; face < 6; ++face) {
    const auto c = cube_face_coordinate(axes[std::size_t(face)]);
    CHECK(c.face == face);
    CHECK(c.s == 0.5f);
    CHECK(c.t == 0.5f);
  }
  CHECK(cube_face_coordinate(Vec3<float>{1, 1, 1}).face == 0);
  CHECK(cube_face_coordinate(Vec3<float>{-1, 1, 1}).face == 1);
  CHECK(cube_face_coordinate(Vec3<float>{0, -1, 1}).face == 3);
  CHECK(cube_face_coordinate(Vec3<float>{0, 0.5f, -0.5f}).face == 2);
  // A corner's coordinates lie on the face's edge: s, t in {0, 1}, never past it.
  const auto corner = cube_face_coordinate(Vec3<float>{1, -1, -1});
  CHECK(corner.s == 1.0f);
  CHECK(corner.t == 1.0f);
}

TEST_CASE("zeroInfiniteAndNanDirectionsReadTheFirstFacesCentre", "[skybox]") {
  const float nan = std::nanf(""), inf = HUGE_VALF;
  for (const Vec3<float> d :
       {Vec3<float>{0, 0, 0}, Vec3<float>{nan, 0, 0}, Vec3<float>{0, nan, 1},
        Vec3<float>{nan, nan, nan}, Vec3<float>{1, 0, nan}, Vec3<float>{inf, 0, 0},
        Vec3<float>{inf, -inf, 0}, Vec3<float>{0, 0, -inf}, Vec3<float>{1, inf, nan}}) {
    INFO(d.x << " " << d.y << " " << d.z);
    const auto c = cube_face_coordinate(d);
    CHECK(c.face == 0);
    CHECK(c.s == 0.5f);
    CHECK(c.t == 0.5f);
  }
  const Skybox box = ramp_box(8);
  const Vec3<float> r = skybox_radiance(box, Vec3<float>{nan, nan, nan});
  CHECK(std::isfinite(r.x));
  CHECK(std::isfinite(r.y));
  CHECK(std::isfinite(r.z));
}

TEST_CASE("theFilterIsBilinearBetweenTexelCentresAndClampedAtTheEdges", "[skybox]") {
  test::TestRandom random(5);
  for (const int n : {4, 16, 64}) {
    const Skybox box = ramp_box(n);
    for (int face = 0; face < 6; ++face) {
      for (int k = 0; k < 300; ++k) {
        const double s = random.uniform(0.0, 1.0), t = random.uniform(0.0, 1.0);
        const Vec3<double> p = cube_point(face, std::clamp(s, 1e-9, 1 - 1e-9), t);
        const auto c = cube_face_coordinate(p);
        if (c.face != face) {
          continue;  // an edge the tie rule gave to another face
        }
        const Vec3<double> got = skybox_radiance(box, p);
        const double x = std::clamp(c.s * n, 0.5, n - 0.5);
        const double y = std::clamp(c.t * n, 0.5, n - 0.5);
        INFO("n " << n << " face " << face << " s " << c.s << " t " << c.t);
        CHECK(got.x == Approx(x).margin(1e-9));
        CHECK(got.y == Approx(y).margin(1e-9));
        CHECK(got.z == 100.0 * face);
      }
    }
  }
}

TEST_CASE("theSkyReadsTheBoxWhenTheParametersSaySoAndTheSunOnlyWhereAsked", "[skybox]") {
  Scene scene = resolve_scene("default", {});
  scene.sky.skybox = SkyboxSettings{};
  const FramePlan frame = make_frame_plan(scene, make_noise_lattice(1, 64), nullptr);
  ShadeParams<double> p = make_shade_params<double>(make_shading_plan(scene, frame, 64));
  REQUIRE(p.skybox == 1);
  REQUIRE(p.skybox_sun == 1);
  const Skybox box = ramp_box(8);
  const Vec3<double> away{-p.sun_direction.x, -p.sun_direction.y, -p.sun_direction.z};
  const Vec3<double> sun = p.sun_direction;
  // Away from the sun: the halo only, ((1 + cos) / 2)^32 = 0 exactly opposite it.
  CHECK(sky_radiance(p, &box, away).x == skybox_radiance(box, away).x);
  // Toward it: the disc, 20 x the sun, over the box.
  const double lit = sky_radiance(p, &box, sun).x - skybox_radiance(box, sun).x;
  CHECK(lit == Approx(20.06 * p.sun.x).epsilon(1e-9));
  p.skybox_sun = 0;
  CHECK(sky_radiance(p, &box, sun).x == skybox_radiance(box, sun).x);
  // Without the box (or without the flag) the gradient: the box's 100 f never shows.
  p.skybox = 0;
  CHECK(sky_radiance(p, &box, Vec3<double>{0, 0, -1}).z < 10.0);
  p.skybox = 1;
  CHECK(sky_radiance(p, nullptr, Vec3<double>{0, 0, -1}).z < 10.0);
  CHECK(sky_radiance(p, &box, Vec3<double>{0, 0, -1}).z == 500.0);
}

}  // namespace
}  // namespace relief
