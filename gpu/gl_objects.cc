#include "gpu/gl_objects.h"

#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/gl_checks.h"

namespace relief::gpu {

namespace {

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.c_str();
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.c_str();
}

}  // namespace

void GlName::reset() {
  if (name_ != 0 && context_ != nullptr && current_egl_context() == context_) {
    if (kind_ == Kind::kBuffer) {
      glDeleteBuffers(1, &name_);
    } else if (kind_ == Kind::kQuery) {
      glDeleteQueries(1, &name_);
    } else {
      glDeleteProgram(name_);
    }
  }
  name_ = 0;
  context_ = nullptr;
}

GlName make_storage_buffer(std::size_t bytes, const std::string& what) {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  GlName owner(GlName::Kind::kBuffer, name, current_egl_context());
  glNamedBufferStorage(name, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glClearNamedBufferData(name, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, nullptr);
  check_gl("allocating " + what + " (" + std::to_string(bytes) + " bytes)");
  return owner;
}

GlName link_compute_program(std::span<const std::string_view> sources, const std::string& name) {
  std::vector<const GLchar*> strings;
  std::vector<GLint> lengths;
  for (const std::string_view s : sources) {
    strings.push_back(s.data());
    lengths.push_back(static_cast<GLint>(s.size()));
  }
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(shader, static_cast<GLsizei>(strings.size()), strings.data(), lengths.data());
  glCompileShader(shader);
  GLint compiled = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
  if (!compiled) {
    const std::string log = shader_log(shader);
    glDeleteShader(shader);
    throw GlError("compute shader " + name + " failed to compile: " + log);
  }
  const GLuint program = glCreateProgram();
  GlName owner(GlName::Kind::kProgram, program, current_egl_context());
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDetachShader(program, shader);
  glDeleteShader(shader);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked) {
    throw GlError("compute program " + name + " failed to link: " + program_log(program));
  }
  check_gl("building compute program " + name);
  return owner;
}

}  // namespace relief::gpu
