// A compute program run over float inputs on the test context: the harness of the GLSL
// function tests and of the arithmetic probe (tests/gl/gl_glsl_functions_test.cc,
// tests/gl/gl_arithmetic.h).
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/gl_checks.h"
#include "gpu/gl_program.h"
#include "tests/gl/gl_test_context.h"

namespace relief::test {

// The compute shader's head: 64 invocations a group, the inputs as In.in_values[], the outputs
// as Out.out_values[], u_count the invocations that run.
inline constexpr const char* kComputeRunHead = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { float in_values[]; };
layout(std430, binding = 1) writeonly buffer Out { float out_values[]; };
uniform uint u_count;
)";

// Builds a compute program of `prelude`, `functions` and kComputeRunHead + `main`, runs `count`
// invocations over `inputs` and returns the `outputs` floats it wrote.
inline std::vector<float> run_compute(const std::string& prelude, const std::string& functions,
                                      const std::string& main, const std::vector<float>& inputs,
                                      std::size_t count, std::size_t outputs) {
  gl_context();
  const gpu::GlProgram program({{GL_COMPUTE_SHADER,
                                 {{"prelude", prelude},
                                  {"functions", functions},
                                  {"test", std::string(kComputeRunHead) + main}}}});
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferData(buffers[0], GLsizeiptr(inputs.size() * sizeof(float)), inputs.data(),
                    GL_STATIC_DRAW);
  // The outputs start as NaN, so that one the shader fails to write cannot pass as a value.
  std::vector<float> out(outputs, std::numeric_limits<float>::quiet_NaN());
  glNamedBufferData(buffers[1], GLsizeiptr(out.size() * sizeof(float)), out.data(), GL_STATIC_READ);
  glUseProgram(program.id());
  glProgramUniform1ui(program.id(), glGetUniformLocation(program.id(), "u_count"), GLuint(count));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
  glUseProgram(0);
  glDeleteBuffers(2, buffers);
  gpu::check_gl("run_compute");
  return out;
}

}  // namespace relief::test
