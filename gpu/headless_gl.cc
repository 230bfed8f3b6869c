#include "gpu/headless_gl.h"

#include <string>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

namespace relief::gpu {

namespace {

// A GL 4.5 core context on `display` (initialised), current on this thread; EGL_NO_CONTEXT
// and `error` set when the display cannot give one.
EGLContext core_context(EGLDisplay display, std::string& error) {
  if (!eglBindAPI(EGL_OPENGL_API)) {
    error = "EGL cannot bind the desktop OpenGL API";
    return EGL_NO_CONTEXT;
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT ||
      !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    error = "no OpenGL 4.5 core context without a surface (EGL error " +
            std::to_string(eglGetError()) + ")";
    if (context != EGL_NO_CONTEXT) {
      eglDestroyContext(display, context);
    }
    return EGL_NO_CONTEXT;
  }
  return context;
}

bool has_extension(const char* extensions, const char* name) {
  if (extensions == nullptr) {
    return false;
  }
  const std::string list = std::string(" ") + extensions + " ";
  return list.find(std::string(" ") + name + " ") != std::string::npos;
}

}  // namespace

std::unique_ptr<HeadlessGl> HeadlessGl::open(std::string& error) {
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) {
    error = "EGL has no eglGetPlatformDisplayEXT (install libegl-mesa0)";
    return nullptr;
  }
  // What is current now: release() makes it current again.
  void* const previous_display = eglGetCurrentDisplay();
  void* const previous_draw = eglGetCurrentSurface(EGL_DRAW);
  void* const previous_read = eglGetCurrentSurface(EGL_READ);
  void* const previous_context = eglGetCurrentContext();
  const auto make = [&](EGLDisplay display, EGLContext context, const char* platform) {
    std::unique_ptr<HeadlessGl> gl(new HeadlessGl());
    gl->display_ = display;
    gl->context_ = context;
    gl->platform_ = platform;
    gl->previous_display_ = previous_display;
    gl->previous_draw_ = previous_draw;
    gl->previous_read_ = previous_read;
    gl->previous_context_ = previous_context;
    return gl;
  };
  // The device platform: each EGL device in turn (a GPU driver's), software devices last
  // (Mesa lists llvmpipe as one; the surfaceless platform below gives it too).
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  const auto query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  std::string device_error;
  if (has_extension(client_extensions, "EGL_EXT_platform_device") && query_devices &&
      query_device_string) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices(16, devices, &count)) {
      for (EGLint d = 0; d < count; ++d) {
        const char* extensions = query_device_string(devices[d], EGL_EXTENSIONS);
        if (has_extension(extensions, "EGL_MESA_device_software")) {
          continue;
        }
        EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[d], nullptr);
        EGLint major = 0, minor = 0;
        if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
          continue;
        }
        EGLContext context = core_context(display, device_error);
        if (context != EGL_NO_CONTEXT) {
          return make(display, context, "EGL device");
        }
        eglTerminate(display);
      }
    }
  }
  EGLDisplay display =
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
    error =
        "neither an EGL device nor EGL's surfaceless platform could be initialised (install "
        "libegl-mesa0 and libgl1-mesa-dri, or a GPU driver's EGL)";
    if (!device_error.empty()) {
      error += "; the EGL device said: " + device_error;
    }
    return nullptr;
  }
  EGLContext context = core_context(display, error);
  if (context == EGL_NO_CONTEXT) {
    eglTerminate(display);
    return nullptr;
  }
  return make(display, context, "EGL surfaceless (Mesa)");
}

HeadlessGl::~HeadlessGl() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

bool HeadlessGl::make_current() {
  if (eglGetCurrentContext() == context_) {
    return true;  // already here: what it replaced stays remembered
  }
  previous_display_ = eglGetCurrentDisplay();
  previous_draw_ = eglGetCurrentSurface(EGL_DRAW);
  previous_read_ = eglGetCurrentSurface(EGL_READ);
  previous_context_ = eglGetCurrentContext();
  return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE;
}

void HeadlessGl::release() {
  if (previous_context_ != EGL_NO_CONTEXT && previous_context_ != context_) {
    eglMakeCurrent(previous_display_, previous_draw_, previous_read_, previous_context_);
  } else {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  previous_context_ = EGL_NO_CONTEXT;
}

std::string HeadlessGl::version() const {
  const auto* text = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return text ? text : "";
}

std::string HeadlessGl::renderer() const {
  const auto* text = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return text ? text : "";
}

}  // namespace relief::gpu
