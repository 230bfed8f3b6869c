// Owners of GL object names (buffers, programs, queries): deleted when the owner dies, if the
// context they were made in is still current on this thread (otherwise they went, or go, with
// it; a GL call with no context current would abort the process through libepoxy).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace relief::gpu {

class GlName {
 public:
  enum class Kind { kBuffer, kProgram, kQuery };

  GlName() = default;
  GlName(Kind kind, unsigned int name, void* context)
      : kind_(kind), name_(name), context_(context) {}
  ~GlName() { reset(); }
  GlName(GlName&& other) noexcept
      : kind_(other.kind_),
        name_(std::exchange(other.name_, 0u)),
        context_(std::exchange(other.context_, nullptr)) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      reset();
      kind_ = other.kind_;
      name_ = std::exchange(other.name_, 0u);
      context_ = std::exchange(other.context_, nullptr);
    }
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;

  unsigned int get() const { return name_; }
  void reset();

 private:
  Kind kind_ = Kind::kBuffer;
  unsigned int name_ = 0;
  void* context_ = nullptr;
};

// A buffer of `bytes` bytes of immutable storage that glNamedBufferSubData may update,
// zero-filled. Throws GlError on failure.
GlName make_storage_buffer(std::size_t bytes, const std::string& what);

// Compiles the concatenation of `sources` as one compute shader and links it; throws GlError
// with `name` and the compiler's or linker's log on failure.
GlName link_compute_program(std::span<const std::string_view> sources, const std::string& name);

}  // namespace relief::gpu
