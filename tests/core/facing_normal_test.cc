// The normal the light sees (core/shade.h, facing_normal) against an oracle in double computed
// here: a normal facing the eye passes unchanged, bit for bit; one facing away becomes the unit
// vector along its part perpendicular to the view ray; the turn is continuous where a normal
// starts to face away; a normal straight away from the eye becomes the direction to the eye.
#include <cmath>
#include <cstdint>

#include <catch2/catch.hpp>

#include "core/shade.h"
#include "core/vec3.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

struct Unit {
  double x, y, z;
};

Unit random_unit(test::TestRandom& random) {
  for (;;) {
    const Unit u{random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)};
    const double length = std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
    if (length > 0.1 && length <= 1) {
      return {u.x / length, u.y / length, u.z / length};
    }
  }
}

template <class Real>
void check_against_the_oracle(double tolerance) {
  test::TestRandom random(2027);
  int facing = 0, turned = 0;
  for (int k = 0; k < 20000; ++k) {
    const Unit n = random_unit(random), v = random_unit(random);
    const Vec3<Real> nr{Real(n.x), Real(n.y), Real(n.z)}, vr{Real(v.x), Real(v.y), Real(v.z)};
    ShadeWork work;
    const Vec3<Real> got = facing_normal(nr, vr, work);
    const double away =
        double(nr.x) * double(vr.x) + double(nr.y) * double(vr.y) + double(nr.z) * double(vr.z);
    INFO("n (" << n.x << ", " << n.y << ", " << n.z << "), view (" << v.x << ", " << v.y << ", "
               << v.z << ")");
    if (away <= 0) {
      ++facing;
      CHECK(work.facing_normals == 0);
      CHECK((got.x == nr.x && got.y == nr.y && got.z == nr.z));
      continue;
    }
    ++turned;
    CHECK(work.facing_normals == 1);
    // The oracle: n - (n . v) v, normalised, in double.
    const double px = double(nr.x) - away * double(vr.x), py = double(nr.y) - away * double(vr.y),
                 pz = double(nr.z) - away * double(vr.z);
    const double length = std::sqrt(px * px + py * py + pz * pz);
    if (length < 0.05) {  // nearly along the view ray: the direction is ill-conditioned
      continue;
    }
    CHECK(std::abs(double(got.x) - px / length) <= tolerance / length);
    CHECK(std::abs(double(got.y) - py / length) <= tolerance / length);
    CHECK(std::abs(double(got.z) - pz / length) <= tolerance / length);
    // Perpendicular to the view ray: it no longer faces away.
    CHECK(std::abs(double(got.x) * v.x + double(got.y) * v.y + double(got.z) * v.z) <=
          tolerance / length);
  }
  CHECK(facing > 5000);  // both branches well exercised
  CHECK(turned > 5000);
}

TEST_CASE("facingNormalIsTheNormalOrItsPartPerpendicularToTheViewRay", "[shading]") {
  check_against_the_oracle<float>(4e-7 * 8);
  check_against_the_oracle<double>(1e-15);
}

TEST_CASE("facingNormalTurnsContinuouslyAndNeverLeavesAZeroOrNan", "[shading]") {
  ShadeWork work;
  const Vec3<float> view{0.0f, 0.0f, 1.0f};
  // Leaning ever less away from the eye: the turned normal approaches the normal itself.
  for (const float lean : {1e-2f, 1e-4f, 1e-6f}) {
    const float side = std::sqrt(1.0f - lean * lean);
    const Vec3<float> got = facing_normal(Vec3<float>{side, 0.0f, lean}, view, work);
    CHECK(std::abs(got.x - side) <= lean);
    CHECK(got.z == Approx(0.0f).margin(1e-7));
  }
  CHECK(work.facing_normals == 3);
  // Straight away from the eye: no perpendicular part; the normal turns to face the eye.
  const Vec3<float> back = facing_normal(view, view, work);
  CHECK((back.x == 0.0f && back.y == 0.0f && back.z == -1.0f));
  const Vec3<double> back_d =
      facing_normal(Vec3<double>{0.0, 1.0, 0.0}, Vec3<double>{0.0, 1.0, 0.0}, work);
  CHECK((back_d.x == 0.0 && back_d.y == -1.0 && back_d.z == 0.0));
}

}  // namespace
}  // namespace relief
