#include "gpu/gl_checks.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

namespace relief::gpu {

namespace {

// glGetError returns GL_NO_ERROR once the flags are read; a broken driver that never does
// must not hang the caller.
constexpr int kMaxPendingErrors = 64;

}  // namespace

void* current_egl_context() {
  const EGLContext context = eglGetCurrentContext();
  return context == EGL_NO_CONTEXT ? nullptr : context;
}

void require_gl45(const char* who) {
  if (!current_egl_context()) {
    throw GlError(std::string(who) +
                  ": no OpenGL context is current on this thread (open one with "
                  "gpu::HeadlessGl::open, or make an EGL context current, first)");
  }
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5)) {
    throw GlError(std::string(who) + ": needs OpenGL 4.5, the current context offers " +
                  std::to_string(major) + "." + std::to_string(minor));
  }
}

std::string gl_error_name(unsigned int code) {
  switch (code) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_CONTEXT_LOST:
      return "GL_CONTEXT_LOST";
    default:
      return "GL error " + std::to_string(code);
  }
}

void check_gl(const std::string& what) {
  GLenum first = GL_NO_ERROR;
  for (int n = 0; n < kMaxPendingErrors; ++n) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) {
      break;
    }
    if (first == GL_NO_ERROR) {
      first = e;
    }
  }
  if (first != GL_NO_ERROR) {
    throw GlError("OpenGL error " + gl_error_name(first) + " in " + what);
  }
}

void clear_gl_errors() {
  for (int n = 0; n < kMaxPendingErrors && glGetError() != GL_NO_ERROR; ++n) {
  }
}

void require_grid_size(const char* who, const char* field, long long value, long long expected) {
  if (value != expected) {
    throw std::invalid_argument(std::string(who) + ": " + field + " is " + std::to_string(value) +
                                ", the grid's is " + std::to_string(expected));
  }
}

}  // namespace relief::gpu
