#include "gpu/gl_rasterizer.h"

#include <stdexcept>

#include <epoxy/gl.h>

namespace relief::gpu {

namespace {

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec4 position;
void main() { gl_Position = position; }
)";

constexpr const char* kFragmentShader = R"(#version 450 core
layout(location = 0) out uint primitive;
void main() { primitive = uint(gl_PrimitiveID); }
)";

void check(const char* what) {
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    throw std::runtime_error(std::string("OpenGL error ") + std::to_string(e) + " in " + what);
  }
}

GLuint compile(GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("shader compilation failed: ") + log);
  }
  return shader;
}

GLenum depth_function(GlDepthFunc f) {
  switch (f) {
    case GlDepthFunc::kGreater:
      return GL_GREATER;
    case GlDepthFunc::kGreaterEqual:
      return GL_GEQUAL;
    case GlDepthFunc::kLess:
      return GL_LESS;
    case GlDepthFunc::kLessEqual:
      return GL_LEQUAL;
    case GlDepthFunc::kEqual:
      return GL_EQUAL;
    case GlDepthFunc::kAlways:
      return GL_ALWAYS;
    case GlDepthFunc::kNever:
      return GL_NEVER;
  }
  return GL_GREATER;
}

}  // namespace

GlImage draw_with_gl(const HeadlessGl& /*current context*/, const GlDraw& draw) {
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked) {
    glDeleteProgram(program);
    throw std::runtime_error("shader program failed to link");
  }

  GLuint targets[2];
  glGenRenderbuffers(2, targets);
  glBindRenderbuffer(GL_RENDERBUFFER, targets[0]);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_R32UI, draw.width, draw.height);
  glBindRenderbuffer(GL_RENDERBUFFER, targets[1]);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, draw.width, draw.height);
  GLuint framebuffer;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, targets[0]);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, targets[1]);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("the id/depth framebuffer is incomplete");
  }
  check("framebuffer setup");

  const std::size_t vertex_count = draw.x.size();
  std::vector<float> positions(vertex_count * 4);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    positions[4 * v] = draw.x[v];
    positions[4 * v + 1] = draw.y[v];
    positions[4 * v + 2] = draw.z[v];
    positions[4 * v + 3] = draw.w[v];
  }
  GLuint vao, buffers[2];
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(2, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(positions.size() * sizeof(float)),
               positions.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(draw.indices.size() * sizeof(std::uint32_t)),
               draw.indices.data(), GL_STATIC_DRAW);
  check("vertex upload");

  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDepthRange(0.0, 1.0);
  glViewport(draw.viewport[0], draw.viewport[1], draw.viewport[2], draw.viewport[3]);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_MULTISAMPLE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(depth_function(draw.depth_func));
  glDepthMask(GL_TRUE);
  if (draw.cull == GlCull::kNone) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(draw.cull == GlCull::kBack ? GL_BACK : GL_FRONT);
  }
  glFrontFace(draw.front_face_ccw ? GL_CCW : GL_CW);
  const GLuint no_primitive[4] = {0xffffffffu, 0, 0, 0};
  glClearBufferuiv(GL_COLOR, 0, no_primitive);
  glClearBufferfv(GL_DEPTH, 0, &draw.depth_clear);
  glUseProgram(program);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(draw.indices.size()), GL_UNSIGNED_INT, nullptr);
  check("draw");

  GlImage image;
  const std::size_t pixels = static_cast<std::size_t>(draw.width) * draw.height;
  image.primitive.resize(pixels);
  image.depth.resize(pixels);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, draw.width, draw.height, GL_RED_INTEGER, GL_UNSIGNED_INT,
               image.primitive.data());
  glReadPixels(0, 0, draw.width, draw.height, GL_DEPTH_COMPONENT, GL_FLOAT, image.depth.data());
  check("read back");

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(2, targets);
  glDeleteBuffers(2, buffers);
  glDeleteVertexArrays(1, &vao);
  glDeleteProgram(program);
  return image;
}

}  // namespace relief::gpu
