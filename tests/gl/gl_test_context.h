// The one OpenGL context of the test binary, shared by every [gl] test file: an inline
// function's static is a single object across translation units, so the context is opened
// once, stays current on the test thread, and its EGL display is terminated once at exit.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <catch2/catch.hpp>

#include "gpu/headless_gl.h"

namespace relief::test {

// The messages of type error GL's debug output reported on the test context since the last
// call (KHR_debug, synchronous: each arrives during the call that caused it).
inline std::vector<std::string>& gl_debug_errors() {
  static std::vector<std::string> errors;
  return errors;
}

inline void GLAPIENTRY record_gl_debug_message(GLenum /*source*/, GLenum type, GLuint /*id*/,
                                               GLenum /*severity*/, GLsizei length,
                                               const GLchar* message, const void* /*user*/) {
  if (type == GL_DEBUG_TYPE_ERROR) {
    gl_debug_errors().emplace_back(
        message, length < 0 ? std::string(message).size() : static_cast<std::size_t>(length));
  }
}

inline gpu::HeadlessGl& gl_context() {
  static std::unique_ptr<gpu::HeadlessGl> context = [] {
    std::string error;
    auto opened = gpu::HeadlessGl::open(error);
    if (!opened) {
      FAIL("OpenGL through EGL is required for this test (make test installs Mesa): " << error);
    }
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(record_gl_debug_message, nullptr);
    return opened;
  }();
  return *context;
}

}  // namespace relief::test
