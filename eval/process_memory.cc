#include "eval/process_memory.h"

#include <fstream>
#include <string>

#include "core/frame_memory.h"
#include "raster/triangle_storage.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace relief {

namespace {

// "VmRSS:     1636 kB" from /proc/self/status, in bytes.
std::optional<std::uintmax_t> status_bytes(const std::string& key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(key + ":", 0) == 0) {
      try {
        return std::uintmax_t(std::stoull(line.substr(key.size() + 1))) * 1024;
      } catch (const std::exception&) {
        return std::nullopt;
      }
    }
  }
  return std::nullopt;
}

}  // namespace

bool peak_memory_measurable() {
#ifdef RELIEF_FRAME_MAPPINGS  // Linux without a sanitizer (core/frame_memory.h)
  return status_bytes("VmHWM").has_value();
#else
  return false;
#endif
}

void release_free_memory() {
  release_cached_frame_buffers();
  raster::release_spare_triangle_storage();
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

std::optional<std::uintmax_t> start_peak_measurement() {
  if (!peak_memory_measurable()) {
    return std::nullopt;
  }
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";  // resets VmHWM to VmRSS (Linux 4.0)
  clear.flush();
  if (!clear) {
    return std::nullopt;
  }
  return status_bytes("VmRSS");
}

std::optional<std::uintmax_t> peak_resident_bytes() {
  if (!peak_memory_measurable()) {
    return std::nullopt;
  }
  return status_bytes("VmHWM");
}

}  // namespace relief
