// The OpenGL side's failures, reported, never crashed on: no current context, a GL older than
// the code needs, a capability too small, a shader that does not compile or link, a GL error
// after a call. libepoxy aborts the process when a GL function is called with no context
// current, so the context is checked through EGL before the first GL call.
#pragma once

#include <stdexcept>
#include <string>

namespace relief::gpu {

class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The EGL context current on this thread (nullptr when none), as an opaque handle.
void* current_egl_context();

// Throws GlError naming `who` unless an EGL context is current on this thread and it offers
// OpenGL 4.5 (compute shaders, direct state access, std430 storage blocks, fp64).
void require_gl45(const char* who);

// Throws GlError naming `what` and the error (e.g. "GL_INVALID_OPERATION") if glGetError
// reports one; reads every pending error first, so the message names the first.
void check_gl(const std::string& what);

// Discards errors a caller left pending, so that check_gl reports only this code's.
void clear_gl_errors();

// Throws std::invalid_argument naming `who` and `field` unless a stream's size `value` is the
// grid's, `expected` (GlTerrain's uploads and read-backs).
void require_grid_size(const char* who, const char* field, long long value, long long expected);

// The GL error code's name ("GL_INVALID_VALUE"), or its number.
std::string gl_error_name(unsigned int code);

}  // namespace relief::gpu
