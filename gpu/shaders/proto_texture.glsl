// Proto-texture sampling (§4.2; core/proto_texture.cc): the CPU filters by hand (GL_REPEAT,
// GL_LINEAR_MIPMAP_LINEAR with GL's isotropic LOD), so the same filter is written here over
// texelFetch of the very mip chain the CPU built (each level uploaded as it is). GL's own
// sampler would filter with its own, unspecified, weight precision (8 bits on many GPUs).
layout(binding = 0) uniform sampler2D proto_texture[kMaxLayers];
// Level 0's side of each layer's texture (a power of two; the chain runs down to 1 x 1). Not
// queried with textureSize per level: the level differs between the pixels of one invocation
// group, and llvmpipe answers a size query with one lane's level for all.
uniform int u_texture_size[kMaxLayers];

// x minus a whole number of periods n (a power of two), exactly (proto_texture.cc, wrap).
// x * (1 / n) is x / n exactly (n a power of two, whose reciprocal is exact where division is
// correctly rounded, and on every GL measured: llvmpipe, an NVIDIA H100).
float wrap_repeat(float x, float n) {
  if (isinf(x) || isnan(x)) {
    return 0.0;
  }
  precise float r = x - n * trunc(x * divide(1.0, n));
  return r;
}

vec3 sample_bilinear(int layer, int level, float u, float v) {
  const int n = u_texture_size[layer] >> level;
  precise float size = float(n);
  precise float s = wrap_repeat(u * size - 0.5, size);
  precise float t = wrap_repeat(v * size - 0.5, size);
  precise float fs = floor(s), ft = floor(t);
  precise float a = s - fs, b = t - ft;
  const int i0 = int(fs) & (n - 1), j0 = int(ft) & (n - 1);
  const int i1 = (i0 + 1) & (n - 1), j1 = (j0 + 1) & (n - 1);
  const vec3 p00 = texelFetch(proto_texture[layer], ivec2(i0, j0), level).rgb;
  const vec3 p10 = texelFetch(proto_texture[layer], ivec2(i1, j0), level).rgb;
  const vec3 p01 = texelFetch(proto_texture[layer], ivec2(i0, j1), level).rgb;
  const vec3 p11 = texelFetch(proto_texture[layer], ivec2(i1, j1), level).rgb;
  precise vec3 bottom = p00 + a * (p10 - p00);
  precise vec3 top = p01 + a * (p11 - p01);
  precise vec3 r = bottom + b * (top - bottom);
  return r;
}

// GL 4.5 §8.14.1, isotropic: lambda = log2(rho) = log2_det(rho^2) / 2, texels of level 0.
float texture_lod(int texture_size, float dudx, float dvdx, float dudy, float dvdy) {
  precise float n = float(texture_size);
  precise float ax = dudx * n, bx = dvdx * n, ay = dudy * n, by = dvdy * n;
  precise float rho_sq = max_cpp(ax * ax + bx * bx, ay * ay + by * by);
  if (!(rho_sq > kMinRhoSq)) {
    return kMagnificationLod;
  }
  precise float r = 0.5 * log2_det(rho_sq);
  return r;
}

vec3 sample_trilinear(int layer, float u, float v, float lod) {
  const int last = findMSB(u_texture_size[layer]);  // log2 of the side: the 1 x 1 level
  if (!(lod > 0.0)) {
    return sample_bilinear(layer, 0, u, v);  // magnification: GL_LINEAR on level 0
  }
  if (lod >= float(last)) {
    return sample_bilinear(layer, last, u, v);
  }
  const int level = int(lod);
  precise float fraction = lod - float(level);
  precise vec3 a = sample_bilinear(layer, level, u, v);
  if (fraction == 0.0) {
    return a;  // a whole lod: one level (nearest_mip_lod's)
  }
  precise vec3 b = sample_bilinear(layer, level + 1, u, v);
  precise vec3 r = a + fraction * (b - a);
  return r;
}

// GL_LINEAR_MIPMAP_NEAREST's level as a whole lod (proto_texture.h, nearest_mip_lod).
float nearest_mip_lod(float lod) {
  precise float r = lod > 0.5 ? ceil(lod - 0.5) : 0.0;
  return r;
}

// shade.cc, sample(): the LOD from the quad derivatives, then the trilinear fetch.
vec3 sample_layer(int layer, bool nearest_mip, float u, float v, float dudx, float dvdx,
                  float dudy, float dvdy) {
  const int size = u_texture_size[layer];
  float lod = texture_lod(size, dudx, dvdx, dudy, dvdy);
  if (nearest_mip) {
    lod = nearest_mip_lod(lod);
  }
  return sample_trilinear(layer, u, v, lod);
}
