#include "gpu/gl_program.h"

#include <algorithm>
#include <stdexcept>

#include <epoxy/gl.h>

namespace relief::gpu {

namespace {

const char* stage_name(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    case GL_COMPUTE_SHADER:
      return "compute";
    default:
      return "shader";
  }
}

// "#line 1 k" before source k, so that the log's "k:LINE(COL)" names the file.
GLuint compile(GLenum stage, const std::vector<GlslSource>& sources) {
  std::vector<std::string> texts;
  std::string names;
  for (std::size_t k = 0; k < sources.size(); ++k) {
    std::string text;
    if (k > 0) {
      text.append("#line 1 ").append(std::to_string(k)).append("\n");
    }
    texts.push_back(text.append(sources[k].text));
    names.append(" ").append(std::to_string(k)).append("=").append(sources[k].name);
  }
  std::vector<const char*> pointers;
  for (const std::string& text : texts) {
    pointers.push_back(text.c_str());
  }
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, static_cast<GLsizei>(pointers.size()), pointers.data(), nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw std::runtime_error(std::string(stage_name(stage)) + " shader compilation failed (" +
                             names.substr(1) + "): " + log.c_str());
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(const std::vector<std::pair<unsigned, std::vector<GlslSource>>>& stages) {
  std::vector<GLuint> shaders;
  try {
    for (const auto& [stage, sources] : stages) {
      shaders.push_back(compile(stage, sources));
    }
  } catch (...) {
    for (GLuint s : shaders) {
      glDeleteShader(s);
    }
    throw;
  }
  id_ = glCreateProgram();
  for (GLuint s : shaders) {
    glAttachShader(id_, s);
  }
  glLinkProgram(id_);
  for (GLuint s : shaders) {
    glDetachShader(id_, s);
    glDeleteShader(s);
  }
  GLint linked = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &linked);
  if (!linked) {
    GLint length = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(id_, length, nullptr, log.data());
    glDeleteProgram(id_);
    id_ = 0;
    throw std::runtime_error(std::string("shader program failed to link: ") + log.c_str());
  }
}

GlProgram::~GlProgram() {
  if (id_ != 0) {
    glDeleteProgram(id_);
  }
}

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) {
      glDeleteProgram(id_);
    }
    id_ = std::exchange(other.id_, 0u);
  }
  return *this;
}

void check_gl(const char* what) {
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    throw std::runtime_error(std::string("OpenGL error ") + std::to_string(e) + " in " + what);
  }
}

std::vector<GlBlockMember> block_members(std::uint32_t program, bool storage_block,
                                         const std::string& block) {
  const GLenum interface = storage_block ? GL_BUFFER_VARIABLE : GL_UNIFORM;
  const GLenum block_interface = storage_block ? GL_SHADER_STORAGE_BLOCK : GL_UNIFORM_BLOCK;
  const GLuint block_index = glGetProgramResourceIndex(program, block_interface, block.c_str());
  std::vector<GlBlockMember> members;
  if (block_index == GL_INVALID_INDEX) {
    return members;
  }
  GLint count = 0;
  glGetProgramInterfaceiv(program, interface, GL_ACTIVE_RESOURCES, &count);
  GLint max_name = 0;
  glGetProgramInterfaceiv(program, interface, GL_MAX_NAME_LENGTH, &max_name);
  std::string name(static_cast<std::size_t>(max_name) + 1, '\0');
  for (GLint r = 0; r < count; ++r) {
    const GLenum properties[] = {GL_BLOCK_INDEX, GL_OFFSET, GL_ARRAY_STRIDE,
                                 GL_TOP_LEVEL_ARRAY_STRIDE};
    GLint values[4] = {-1, -1, 0, 0};
    const GLsizei queried = storage_block ? 4 : 3;
    glGetProgramResourceiv(program, interface, static_cast<GLuint>(r), queried, properties, 4,
                           nullptr, values);
    if (values[0] != static_cast<GLint>(block_index)) {
      continue;
    }
    GLsizei length = 0;
    glGetProgramResourceName(program, interface, static_cast<GLuint>(r),
                             static_cast<GLsizei>(name.size()), &length, name.data());
    members.push_back(
        {name.substr(0, static_cast<std::size_t>(length)), values[1], values[2], values[3]});
  }
  check_gl("block_members");
  return members;
}

int block_size(std::uint32_t program, bool storage_block, const std::string& block) {
  const GLenum block_interface = storage_block ? GL_SHADER_STORAGE_BLOCK : GL_UNIFORM_BLOCK;
  const GLuint index = glGetProgramResourceIndex(program, block_interface, block.c_str());
  if (index == GL_INVALID_INDEX) {
    return -1;
  }
  const GLenum property = GL_BUFFER_DATA_SIZE;
  GLint size = -1;
  glGetProgramResourceiv(program, block_interface, index, 1, &property, 1, nullptr, &size);
  check_gl("block_size");
  return size;
}

}  // namespace relief::gpu
