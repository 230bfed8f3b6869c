// A headless OpenGL 4.5 core context through EGL's surfaceless platform (Mesa's llvmpipe on a
// machine without a GPU, the GPU's driver where there is one). No window system is needed.
#pragma once

#include <memory>
#include <string>

namespace relief::gpu {

class HeadlessGl {
 public:
  // Opens a context and makes it current on this thread; nullptr and `error` set when EGL or
  // GL 4.5 is unavailable.
  static std::unique_ptr<HeadlessGl> open(std::string& error);
  ~HeadlessGl();
  HeadlessGl(const HeadlessGl&) = delete;
  HeadlessGl& operator=(const HeadlessGl&) = delete;

  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

 private:
  HeadlessGl() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace relief::gpu
