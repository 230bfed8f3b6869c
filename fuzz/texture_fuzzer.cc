// libFuzzer target: A texture PNG's bytes, as `relief render` reads a layer's texture file.
// The input's format and the properties checked: fuzz/fuzz_inputs.h, texture_input.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  relief::fuzz::texture_input(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
