// The per-vertex streams of the GL terrain stages (gl_terrain.h): one storage buffer each, in
// the CPU's structure-of-arrays layout (core/grid_buffers.h): vertex (i, j) at index
// j * pitch + i, pitch = width rounded up to limits::kRowAlignFloats. Every stream is 32-bit
// float but `valid`, which is the CPU's uint8_t array byte for byte: four vertices to a 32-bit
// word, vertex k in bits 8 (k mod 4) .. 8 (k mod 4) + 7 of word k / 4 (little-endian, as the
// bytes lie in memory); GLSL reads it as `uint valid[]` and
// `(valid[k >> 2] >> (8 * (k & 3))) & 0xff`.
#pragma once

#include <array>
#include <string_view>

namespace relief::gpu {

enum class GlStream : int {
  kDx,  // stage 2: camera-relative base-domain position, world units
  kDz,
  kSigma,   // stage 2: local grid spacing
  kNu,      // stage 2: octave count
  kValid,   // stage 2: uint8 per vertex, packed (above)
  kHeight,  // stage 3: camera-relative height
  kNx,      // stage 4: unit normal
  kNy,
  kNz,
  kSlope,       // stage 4: |grad h|
  kWaterDepth,  // stage 4: max(0, water level - h)
  // A planet frame's bend (core/planet_bend.h), after stage 3: the camera-relative position on
  // the sphere and how far it lies below the unbent height. Allocated by the first planet
  // frame (buffer() is 0 before).
  kBentX,
  kBentY,
  kBentZ,
  kBentDrop,
};

inline constexpr int kGlStreamCount = 15;

inline constexpr std::array<GlStream, kGlStreamCount> kGlStreams = {
    GlStream::kDx,    GlStream::kDz,     GlStream::kSigma,      GlStream::kNu,
    GlStream::kValid, GlStream::kHeight, GlStream::kNx,         GlStream::kNy,
    GlStream::kNz,    GlStream::kSlope,  GlStream::kWaterDepth, GlStream::kBentX,
    GlStream::kBentY, GlStream::kBentZ,  GlStream::kBentDrop};

// The streams every frame has (the bent ones only a planet's).
inline constexpr bool is_bent_stream(GlStream stream) {
  return static_cast<int>(stream) >= static_cast<int>(GlStream::kBentX);
}

// The GridBuffers field name: "dx", "valid", "water_depth", ...
std::string_view gl_stream_name(GlStream stream);

}  // namespace relief::gpu
