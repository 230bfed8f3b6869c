// Proto-textures (§4.2): tiling RGB textures with the paper's variance-reduced mipmap, and
// sampling the way a GPU does.
//
// §4.2: "build a custom mipmap such that the variance is continuously decreased with each
// level ... by first applying the smoothing filter as is usually done to compute mipmaps, and
// then take a weighted average between the smoothed image and the global mean of the colors."
// Relief: level k = (1 - b) box(level k-1) + b mean, with the user weight b (mip_blend). The
// 2 x 2 box filter of a periodic power-of-two texture keeps the mean, and so does the blend;
// the variance falls by (1 - b)^2 per level on top of the filter's own reduction, so distant
// terrain shows the material's colour without its repeating pattern.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace relief {

using Rgb = std::array<float, 3>;

// A square, power-of-two texture of linear RGB, row-major, texel (i, j) at rgb[3 (j n + i)].
struct RgbImage {
  int size = 0;
  std::vector<float> rgb;
};

// One level of a mip chain: its side and where its texels start in the chain.
struct MipLevel {
  int size = 0;
  std::size_t offset = 0;  // texel (i, j) at texels[offset + 3 (j size + i)]
};

// The mip chain in one array, level 0 first: the vector kernels address any level of it from
// one base (simd/texture-inl.h), and a GPU uploads it level by level. Level k of a side-n
// texture starts at 4 (n^2 - (n / 2^k)^2) floats (3 n^2 (1 + 1/4 + ...)). The array holds
// kTexelPadding more floats (zero) after the chain, so that a vector kernel may load eight
// floats from any texel.
struct ProtoTexture {
  static constexpr std::size_t kTexelPadding = 8;
  std::vector<float> texels;
  std::vector<MipLevel> levels;  // level 0 is the full texture, the last is 1 x 1
  Rgb mean{};                    // the global mean colour of level 0

  const float* level_texels(int level) const { return texels.data() + levels[level].offset; }
};

// Precondition: image.size is a power of two >= 1; 0 <= mip_blend <= 1.
ProtoTexture build_proto_texture(const RgbImage& image, double mip_blend);

// GL 4.5 §8.14.1 (isotropic): lambda = log2(rho), rho = max(|(du/dx, dv/dx)|,
// |(du/dy, dv/dy)|) in texels of level 0; u, v are in texture repeats. Computed as
// log2_det(rho^2) / 2. Derivatives of zero length give the magnification limit -inf, returned
// as a large negative number (kMagnificationLod).
float texture_lod(int texture_size, float dudx, float dvdx, float dudy, float dvdy);

inline constexpr float kMagnificationLod = -64.0f;

// GL_REPEAT, GL_LINEAR_MIPMAP_LINEAR (GL_LINEAR when lambda <= 0): bilinear in the two levels
// around lambda (clamped to the chain), blended by its fractional part (where it is 0, the
// first level alone: a + 0 (b - a) = a for finite texels). Texel centres at
// (i + 1/2) / size. Any finite u, v: coordinates are wrapped exactly before they become texel
// indices (callers still keep u small, subtracting the camera's position in whole repeats, so
// that float keeps sub-texel precision near the camera).
Rgb sample_trilinear(const ProtoTexture& texture, float u, float v, float lod);

// GL_LINEAR_MIPMAP_NEAREST's level (GL 4.5 §8.14.3) as a lod sample_trilinear reads as that
// level alone: 0 for lambda <= 1/2 (or NaN), else ceil(lambda + 1/2) - 1, in float (a whole
// number: its fraction is 0, and sample_trilinear fetches one level), computed as
// ceil(lambda - 1/2), exactly.
float nearest_mip_lod(float lod);

}  // namespace relief
