// What every compute program of gl_terrain.h starts with: the GLSL version and the constants
// the C++ side defines, written from their C++ definitions so that there is one of each: the
// storage block bindings, limits::kMaxOctaves, the work group size, the need flag kDraw, and
// the float constants of the stages bit for bit (uintBitsToFloat of the C++ float's bits: a
// decimal literal would be rounded by the GLSL compiler's own parser).
#pragma once

#include <string>

#include "gpu/gl_streams.h"

namespace relief::gpu {

// Storage block bindings of the compute programs (GL_SHADER_STORAGE_BUFFER).
inline constexpr int kBindingParams = 0;       // the stage's parameter struct
inline constexpr int kBindingRows = 1;         // DomainRows
inline constexpr int kBindingFirstStream = 2;  // + GlStream
inline constexpr int kBindingLattice = kBindingFirstStream + kGlStreamCount;
inline constexpr int kBindingMask = kBindingLattice + 1;   // need flags, or valid
inline constexpr int kBindingReach = kBindingMask + 1;     // octave_reach per finest octave
inline constexpr int kBindingSketch = kBindingReach + 1;   // the sketch's texel heights
inline constexpr int kBindingPlanet = kBindingSketch + 1;  // PlanetParams (stage 2, the bend)
inline constexpr int kBindingCount = kBindingPlanet + 1;

inline constexpr int stream_binding(GlStream stream) {
  return kBindingFirstStream + static_cast<int>(stream);
}

// Invocations per work group, along a row: a multiple of 4, so that a group writes whole words
// of the packed valid stream (rows are a multiple of 16 vertices long).
inline constexpr int kGroupSize = 64;

// "#version 450 core" and the #defines above.
std::string shader_prelude();

}  // namespace relief::gpu
