// Shader programs and GL errors for gpu/: compile a program from several source strings
// (GLSL's #line numbers them, so a log names the file), and turn GL errors into exceptions.
// Requires a current context on the calling thread.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace relief::gpu {

// One source string of a shader: a name for the log and the text.
struct GlslSource {
  std::string name;
  std::string text;
};

// A linked program, deleted with the object.
class GlProgram {
 public:
  GlProgram() = default;
  // Compiles each (stage, sources) pair and links them. Throws std::runtime_error with the
  // compiler's or linker's log, the failing stage and the sources' names.
  explicit GlProgram(const std::vector<std::pair<unsigned, std::vector<GlslSource>>>& stages);
  ~GlProgram();
  GlProgram(GlProgram&& other) noexcept : id_(std::exchange(other.id_, 0u)) {}
  GlProgram& operator=(GlProgram&& other) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  std::uint32_t id() const { return id_; }

 private:
  std::uint32_t id_ = 0;
};

// Throws std::runtime_error naming `what` when GL has recorded an error.
void check_gl(const char* what);

// One member of a program's interface block as GL laid it out (glGetProgramResourceiv).
struct GlBlockMember {
  std::string name;          // as GL names it, e.g. "ShadeParamsBlock.layers[1].height_up.open"
  int offset = -1;           // GL_OFFSET, bytes from the start of the block
  int array_stride = 0;      // GL_ARRAY_STRIDE: 0 unless the member is an array
  int top_level_stride = 0;  // GL_TOP_LEVEL_ARRAY_STRIDE (storage blocks only; GL lists element
                             // 0 of a top-level array of structs, with this stride)
};

// Every member of the named storage block (GL_BUFFER_VARIABLE) or uniform block (GL_UNIFORM)
// of `program` that GL reports, in GL's order.
std::vector<GlBlockMember> block_members(std::uint32_t program, bool storage_block,
                                         const std::string& block);

// GL_BUFFER_DATA_SIZE of that block: the bytes a buffer bound to it must hold; -1 if the
// program has no such block.
int block_size(std::uint32_t program, bool storage_block, const std::string& block);

}  // namespace relief::gpu
