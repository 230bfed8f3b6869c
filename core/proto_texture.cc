#include "core/proto_texture.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/det_math.h"

namespace relief {

namespace {

// x minus a whole number of periods n (a power of two), |result| < n, exactly: x / n and
// n trunc(x / n) are exact, and when |x| >= n both x and n trunc(x / n) are multiples of ulp(x)
// (or x is a multiple of n and the result 0), so their difference, smaller than |x|, is exact
// too. The fraction x - floor(x) and the texel index mod n are therefore unchanged, and floor
// of the result converts to int without overflow however large |x| is (GL_REPEAT, GL 4.5
// §8.14.2). Domain: finite x; anything else (never produced by stage 7) samples texel 0.
float wrap(float x, float n) {
  if (!std::isfinite(x)) {
    return 0.0f;
  }
  return x - n * std::trunc(x / n);
}

// The four texels around (u, v), bilinearly weighted, with repeat wrapping.
Rgb sample_bilinear(const ProtoTexture& texture, int level, float u, float v) {
  const int n = texture.levels[level].size;
  const float* rgb = texture.level_texels(level);
  const float s = wrap(u * float(n) - 0.5f, float(n));
  const float t = wrap(v * float(n) - 0.5f, float(n));
  const float fs = std::floor(s), ft = std::floor(t);
  const float a = s - fs, b = t - ft;
  // -n <= fs, ft < n after the wrap; the mask wraps negatives (two's complement).
  const int i0 = static_cast<int>(fs) & (n - 1), j0 = static_cast<int>(ft) & (n - 1);
  const int i1 = (i0 + 1) & (n - 1), j1 = (j0 + 1) & (n - 1);
  const float* p00 = &rgb[3 * (std::size_t(j0) * n + i0)];
  const float* p10 = &rgb[3 * (std::size_t(j0) * n + i1)];
  const float* p01 = &rgb[3 * (std::size_t(j1) * n + i0)];
  const float* p11 = &rgb[3 * (std::size_t(j1) * n + i1)];
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    const float bottom = p00[c] + a * (p10[c] - p00[c]);
    const float top = p01[c] + a * (p11[c] - p01[c]);
    out[c] = bottom + b * (top - bottom);
  }
  return out;
}

}  // namespace

ProtoTexture build_proto_texture(const RgbImage& image, double mip_blend) {
  assert(image.size > 0 && (image.size & (image.size - 1)) == 0);
  ProtoTexture texture;
  double sum[3] = {0, 0, 0};
  for (std::size_t k = 0; k < image.rgb.size(); k += 3) {
    for (int c = 0; c < 3; ++c) {
      sum[c] += image.rgb[k + c];
    }
  }
  const double texels = double(image.size) * image.size;
  for (int c = 0; c < 3; ++c) {
    texture.mean[c] = static_cast<float>(sum[c] / texels);
  }
  // The chain's size: 3 n^2 floats per level of side n, halving down to 1.
  std::size_t floats = 0;
  for (int n = image.size; n >= 1; n /= 2) {
    texture.levels.push_back({n, floats});
    floats += 3 * std::size_t(n) * n;
  }
  texture.texels.resize(floats + ProtoTexture::kTexelPadding);
  std::copy(image.rgb.begin(), image.rgb.end(), texture.texels.begin());
  for (std::size_t k = 1; k < texture.levels.size(); ++k) {
    const int fine_size = texture.levels[k - 1].size;
    const float* fine = texture.level_texels(int(k) - 1);
    const int size = texture.levels[k].size;
    float* coarse = texture.texels.data() + texture.levels[k].offset;
    for (int j = 0; j < size; ++j) {
      for (int i = 0; i < size; ++i) {
        for (int c = 0; c < 3; ++c) {
          const auto at = [&](int x, int y) {
            return double(fine[3 * (std::size_t(y) * fine_size + x) + c]);
          };
          const double box = 0.25 * (at(2 * i, 2 * j) + at(2 * i + 1, 2 * j) +
                                     at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1));
          coarse[3 * (std::size_t(j) * size + i) + c] =
              static_cast<float>((1.0 - mip_blend) * box + mip_blend * texture.mean[c]);
        }
      }
    }
  }
  return texture;
}

float texture_lod(int texture_size, float dudx, float dvdx, float dudy, float dvdy) {
  const float n = float(texture_size);
  const float ax = dudx * n, bx = dvdx * n, ay = dudy * n, by = dvdy * n;
  const float rho_sq = std::max(ax * ax + bx * bx, ay * ay + by * by);
  // Domain of the log: rho^2 > 0 and finite; below FLT_MIN it is magnification anyway.
  if (!(rho_sq > 1e-30f)) {
    return kMagnificationLod;
  }
  return 0.5f * log2_det(rho_sq);
}

float nearest_mip_lod(float lod) {
  // ceil(lambda + 1/2) - 1 as ceil(lambda - 1/2): lambda - 1/2 is exact for lambda > 1/2
  // (below 2^23), where lambda + 1/2 would round up to a whole number just above 1/2.
  return lod > 0.5f ? std::ceil(lod - 0.5f) : 0.0f;
}

Rgb sample_trilinear(const ProtoTexture& texture, float u, float v, float lod) {
  const int last = static_cast<int>(texture.levels.size()) - 1;
  if (!(lod > 0.0f)) {
    return sample_bilinear(texture, 0, u, v);  // magnification: GL_LINEAR on level 0
  }
  if (lod >= float(last)) {
    return sample_bilinear(texture, last, u, v);
  }
  const int level = static_cast<int>(lod);
  const float fraction = lod - float(level);
  const Rgb a = sample_bilinear(texture, level, u, v);
  if (fraction == 0.0f) {
    return a;  // a whole lod: one level (nearest_mip_lod's)
  }
  const Rgb b = sample_bilinear(texture, level + 1, u, v);
  return {a[0] + fraction * (b[0] - a[0]), a[1] + fraction * (b[1] - a[1]),
          a[2] + fraction * (b[2] - a[2])};
}

}  // namespace relief
