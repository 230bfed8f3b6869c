// A headless OpenGL 4.5 core context through EGL, no window system: the EGL device platform
// first (a GPU's driver: NVIDIA exposes its GPUs as EGL devices), then Mesa's surfaceless
// platform (llvmpipe on a machine without a GPU).
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
  std::string version() const;   // GL_VERSION
  // "EGL device" or "EGL surfaceless (Mesa)": which platform gave the context.
  const std::string& platform() const { return platform_; }

  // A context is current on one thread at a time: make_current() takes it to the calling
  // thread (false if EGL refuses), remembering what was current there; release() lets it go
  // and makes that current again, so that another thread can take it and a caller's own
  // context is left as it was.
  bool make_current();
  void release();

 private:
  HeadlessGl() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
  void* previous_display_ = nullptr;  // what make_current() replaced
  void* previous_draw_ = nullptr;
  void* previous_read_ = nullptr;
  void* previous_context_ = nullptr;
};

}  // namespace relief::gpu
