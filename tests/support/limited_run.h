// The real relief binary of this build run as a process, under an address-space limit
// (ulimit -v) that an in-process run cannot take.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/cli_support.h"

namespace relief::test {

// The relief binary of this build (tests/CMakeLists.txt builds it before the tests), or
// $RELIEF_BINARY; empty when neither exists.
inline std::filesystem::path relief_binary() {
  if (const char* env = std::getenv("RELIEF_BINARY")) {
    return env;
  }
  return std::filesystem::exists(RELIEF_BINARY_PATH) ? std::filesystem::path(RELIEF_BINARY_PATH)
                                                     : std::filesystem::path();
}

struct Exit {
  bool signalled;
  int code;
  std::string err;
};

// `relief ARGS` run by the shell after `setup` (an environment variable, a limit), so that
// both are the process's own.
inline Exit run_binary(const std::filesystem::path& binary, const std::string& setup,
                       const std::string& args, const std::filesystem::path& dir) {
  const std::filesystem::path err = dir / "stderr.txt";
  const std::string command = test::concat({"/bin/sh -c \"", setup, "; exec '", binary.string(),
                                            "' ", args, "\" >/dev/null 2>'", err.string(), "'"});
  const int status = std::system(command.c_str());
  const std::vector<unsigned char> text = test::read_bytes(err);
  return {WIFSIGNALED(status), WIFEXITED(status) ? WEXITSTATUS(status) : -1,
          std::string(text.begin(), text.end())};
}

// `relief ARGS` under `ulimit -v kib`.
inline Exit run_limited(const std::filesystem::path& binary, long kib, const std::string& args,
                        const std::filesystem::path& dir) {
  return run_binary(binary, "ulimit -v " + std::to_string(kib), args, dir);
}

// AddressSanitizer reserves terabytes of shadow address space: no ulimit -v run there.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

}  // namespace relief::test
