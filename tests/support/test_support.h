// Helpers shared by the tests: small scenes, temporary directories.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

#include "core/scene/scene.h"

namespace relief::test {

// The default scene on a smaller grid, so that whole-frame tests stay fast under sanitizers.
inline Scene small_scene(int grid = 96) {
  Scene scene;
  scene.grid.width = grid;
  scene.grid.height = grid;
  return scene;
}

// A fresh, empty directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static int counter = 0;
    path_ =
        std::filesystem::temp_directory_path() /
        ("relief-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  bool empty() const { return std::filesystem::is_empty(path_); }

 private:
  std::filesystem::path path_;
};

// Test inputs only: a fixed-seed engine whose raw output (not a distribution) is specified
// by the standard, so the inputs are the same on every platform.
class TestRandom {
 public:
  explicit TestRandom(unsigned seed) : engine_(seed) {}
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(engine_() >> 11) * 0x1.0p-53);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace relief::test
