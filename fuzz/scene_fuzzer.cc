// libFuzzer target: A scene file's bytes, as `relief render FILE` reads them.
// The input's format and the properties checked: fuzz/fuzz_inputs.h, scene_input.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  relief::fuzz::scene_input(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
