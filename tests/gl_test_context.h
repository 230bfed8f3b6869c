// The one OpenGL context of the test binary, shared by every [gl] test file: an inline
// function's static is a single object across translation units, so the context is opened
// once, stays current on the test thread, and its EGL display is terminated once at exit.
#pragma once

#include <memory>
#include <string>

#include <catch2/catch.hpp>

#include "gpu/headless_gl.h"

namespace relief::test {

inline gpu::HeadlessGl& gl_context() {
  static std::unique_ptr<gpu::HeadlessGl> context = [] {
    std::string error;
    auto opened = gpu::HeadlessGl::open(error);
    if (!opened) {
      FAIL("OpenGL through EGL is required for this test (make test installs Mesa): " << error);
    }
    return opened;
  }();
  return *context;
}

}  // namespace relief::test
