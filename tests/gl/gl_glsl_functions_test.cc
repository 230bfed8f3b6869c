// The GLSL ports of core's deterministic functions (gpu/shaders/common.glsl: log2_det,
// exp2_det, normalize_or; gpu/shaders/det_trig.glsl.in: sin_cos_det, atan2_det) against the C++
// originals, bit for bit, through a compute shader.
// docs/gl-shading.md: where GLSL only promises bounded error, llvmpipe's IEEE arithmetic
// still gives the CPU's bits, which is what these tests pin down.
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <catch2/catch.hpp>

#include "core/det_math.h"
#include "core/vec3.h"
#include "gpu/gl_program.h"
#include "gpu/gl_shader_prelude.h"
#include "gpu/gl_shader_sources.h"
#include "gpu/glsl_sources.h"
#include "tests/gl/gl_test_context.h"

namespace relief {
namespace {

// Which GLSL library the test shader is built with.
enum class Library {
  kShading,  // stage 8's prelude and common.glsl
  kTerrain,  // the terrain stages' prelude and det_math.glsl
};

// Runs `body` (GLSL statements reading float x = in_values[i], writing out_values[3 i + c])
// over `inputs` in a compute shader with `library`; returns the outputs.
std::vector<float> run_glsl(const std::string& body, const std::vector<float>& inputs,
                            int outputs_per_input, Library library = Library::kShading) {
  test::gl_context();
  const std::string main = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { float in_values[]; };
layout(std430, binding = 1) writeonly buffer Out { float out_values[]; };
uniform uint u_count;
void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) { return; }
  const float x = in_values[i];
)" + body + "\n}\n";
  const bool terrain = library == Library::kTerrain;
  const std::string prelude = terrain ? gpu::shader_prelude() : gpu::glsl_prelude();
  // Both libraries take log2_det from the one log2_det.glsl, each under its own prelude.
  const std::string functions =
      (terrain ? std::string(gpu::shader_file("det_math.glsl")) : std::string(gpu::glsl::kCommon)) +
      std::string(gpu::glsl::kLog2Det);
  const gpu::GlProgram program(
      {{GL_COMPUTE_SHADER, {{"prelude", prelude}, {"functions", functions}, {"test", main}}}});
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  const auto count = static_cast<GLuint>(inputs.size());
  glNamedBufferData(buffers[0], GLsizeiptr(inputs.size() * sizeof(float)), inputs.data(),
                    GL_STATIC_DRAW);
  std::vector<float> out(inputs.size() * std::size_t(outputs_per_input));
  glNamedBufferData(buffers[1], GLsizeiptr(out.size() * sizeof(float)), nullptr, GL_STATIC_READ);
  glUseProgram(program.id());
  glProgramUniform1ui(program.id(), glGetUniformLocation(program.id(), "u_count"), count);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glDispatchCompute((count + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
  glUseProgram(0);
  glDeleteBuffers(2, buffers);
  gpu::check_gl("run_glsl");
  return out;
}

// Positive normal floats spread over the exponent range, and values near 1 and sqrt(2).
std::vector<float> log_inputs() {
  std::vector<float> x;
  for (std::uint32_t bits = 0x00800000u; bits < 0x7f000000u; bits += 0x000fffffu) {
    x.push_back(std::bit_cast<float>(bits));
  }
  for (int k = -2000; k <= 2000; ++k) {
    x.push_back(1.0f + float(k) * 1e-4f);
    x.push_back(1.41421356f + float(k) * 1e-6f);
  }
  return x;
}

TEST_CASE("glslLog2DetIsTheCppLog2DetBitForBit", "[gl]") {
  const std::vector<float> x = log_inputs();
  const std::vector<float> gl = run_glsl("out_values[i] = log2_det(x);", x, 1);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    differ += std::bit_cast<std::uint32_t>(gl[k]) != std::bit_cast<std::uint32_t>(log2_det(x[k]));
  }
  INFO(differ << " of " << x.size() << " differ");
  CHECK(differ == 0);
}

TEST_CASE("glslExp2DetIsTheCppExp2DetBitForBit", "[gl]") {
  std::vector<float> x;
  for (int k = -140000; k <= 140000; k += 7) {
    x.push_back(float(k) * 1e-3f);
  }
  const std::vector<float> gl = run_glsl("out_values[i] = exp2_det(x);", x, 1);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    differ += std::bit_cast<std::uint32_t>(gl[k]) != std::bit_cast<std::uint32_t>(exp2_det(x[k]));
  }
  INFO(differ << " of " << x.size() << " differ");
  CHECK(differ == 0);
}

TEST_CASE("glslNormalizeOrIsTheCppNormalizeOrBitForBit", "[gl]") {
  std::vector<float> x;
  for (int k = 0; k < 20000; ++k) {
    x.push_back(float(k) * 0.37f - 3000.0f);
  }
  const std::string body = R"(
  const vec3 v = vec3(x, 0.5 * x - 7.0, 3.0 - 0.25 * x);
  const vec3 n = normalize_or(v, vec3(0.0, 1.0, 0.0));
  out_values[3u * i] = n.x;
  out_values[3u * i + 1u] = n.y;
  out_values[3u * i + 2u] = n.z;)";
  const std::vector<float> gl = run_glsl(body, x, 3);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const float v = x[k];
    const Vec3<float> n =
        normalize_or(Vec3<float>{v, 0.5f * v - 7.0f, 3.0f - 0.25f * v}, Vec3<float>{0, 1, 0});
    differ += gl[3 * k] != n.x || gl[3 * k + 1] != n.y || gl[3 * k + 2] != n.z;
  }
  INFO(differ << " of " << x.size() << " differ");
  CHECK(differ == 0);
}

TEST_CASE("glslSinCosDetIsTheCppSinCosDetBitForBit", "[gl][planet]") {
  // The bend's and the sky's range (central angles up to pi, nadir angles), the reduction's
  // quadrant boundaries, tiny arguments, and out to the clamp of the reduction (|x| > 64 pi/2).
  std::vector<float> x;
  for (int k = -120000; k <= 120000; k += 3) {
    x.push_back(float(k) * 1e-3f);
  }
  for (int q = -8; q <= 8; ++q) {
    for (int k = -50; k <= 50; ++k) {
      x.push_back(float(q) * 1.57079633f + float(k) * 1e-6f);
    }
  }
  for (float v = 1e-30f; v < 1e-2f; v *= 1.7f) {
    x.push_back(v);
    x.push_back(-v);
  }
  x.push_back(0.0f);
  const std::string body = R"(
  float s, c;
  sin_cos_det(x, s, c);
  out_values[3u * i] = s;
  out_values[3u * i + 1u] = c;
  out_values[3u * i + 2u] = sin_det(x);)";
  const std::vector<float> gl = run_glsl(body, x, 3, Library::kTerrain);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    float s = 0, c = 0;
    sin_cos_det(x[k], s, c);
    differ += std::bit_cast<std::uint32_t>(gl[3 * k]) != std::bit_cast<std::uint32_t>(s) ||
              std::bit_cast<std::uint32_t>(gl[3 * k + 1]) != std::bit_cast<std::uint32_t>(c) ||
              std::bit_cast<std::uint32_t>(gl[3 * k + 2]) != std::bit_cast<std::uint32_t>(s);
  }
  INFO(differ << " of " << x.size() << " differ");
  CHECK(differ == 0);
}

TEST_CASE("glslAtan2DetIsTheCppAtan2DetBitForBit", "[gl][planet]") {
  // y >= 0 (the domain), x of both signs: every octant boundary (t = tan(pi/8), y = |x|, x = 0)
  // and the (0, 0) guard.
  std::vector<float> ys, xs;
  for (int a = 0; a <= 400; ++a) {
    for (int b = -400; b <= 400; b += 3) {
      ys.push_back(float(a) * 0.0125f);
      xs.push_back(float(b) * 0.0125f);
    }
  }
  for (int k = -100; k <= 100; ++k) {
    ys.push_back(0.41421356f + float(k) * 1e-7f);  // t near tan(pi/8)
    xs.push_back(1.0f);
    ys.push_back(1.0f + float(k) * 1e-7f);  // y near |x|
    xs.push_back(-1.0f);
  }
  ys.push_back(3e-30f);
  xs.push_back(-2e-30f);
  // The pairs lie interleaved in the input (y, x, y, x, ...): an even invocation reads its
  // pair, an odd one writes 0.
  std::vector<float> packed;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    packed.push_back(ys[k]);
    packed.push_back(xs[k]);
  }
  const std::string body = R"(
  out_values[i] = (i & 1u) == 0u ? atan2_det(x, in_values[i + 1u]) : 0.0;)";
  const std::vector<float> gl = run_glsl(body, packed, 1, Library::kTerrain);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    differ += std::bit_cast<std::uint32_t>(gl[2 * k]) !=
              std::bit_cast<std::uint32_t>(atan2_det(ys[k], xs[k]));
  }
  INFO(differ << " of " << ys.size() << " differ");
  CHECK(differ == 0);
}

}  // namespace
}  // namespace relief
