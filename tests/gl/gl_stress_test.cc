// The stability stress suite on the GL backend (Mesa's llvmpipe where there is no GPU), against
// reference-double: every case of relief stress at the tests' small size.
#include <catch2/catch.hpp>

#include "tests/support/stress_support.h"

namespace relief {
namespace {

TEST_CASE("stressEveryAxisRendersFiniteFramesOnTheGlBackend", "[gl][stress]") {
  const StressSettings settings = test::stress_settings({Backend::kReferenceDouble, Backend::kGl});
  // Without a context every gl row would be skipped, and skipped rows once counted as passed.
  if (!settings.gl_unavailable.empty()) {
    FAIL("OpenGL through EGL is required for this test (make test installs Mesa): "
         << settings.gl_unavailable);
  }
  test::run_stress_axes(stress_axes(), settings);
}

}  // namespace
}  // namespace relief
