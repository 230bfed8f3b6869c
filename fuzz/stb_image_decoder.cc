// stb_image's decoder from Debian's libstb-dev header, for the texture fuzzer alone: compiled
// with the fuzzer's coverage and sanitizers, where libstb.so (which the library links) is not.
// Warnings are third-party and off for this file (fuzz/CMakeLists.txt).
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
