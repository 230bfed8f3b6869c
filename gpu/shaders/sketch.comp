// Stage 3's second part, §3's low-frequency sketch: add_sketch and sample_sketch of
// core/height_sketch.cc, one invocation per vertex of the row pitch, after fbm.comp has
// written the fractal's heights. docs/terrain-spec.md, section 11, is the specification.
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_PARAMS) readonly buffer SketchParamsBlock {
  SketchParams sketch;
};
// The texels' world heights, row j (along z) at j * width.
layout(std430, binding = RELIEF_BINDING_SKETCH) readonly buffer SketchBlock {
  float sketch_heights[];
};
layout(std430, binding = RELIEF_BINDING_DX) readonly buffer DxBlock { float in_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) readonly buffer DzBlock { float in_dz[]; };
// Stage 2's octave count, read as a height field's level (sketch.levels > 1).
layout(std430, binding = RELIEF_BINDING_NU) readonly buffer NuBlock { float in_nu[]; };
layout(std430, binding = RELIEF_BINDING_MASK) readonly buffer MaskBlock { uint in_mask[]; };
layout(std430, binding = RELIEF_BINDING_HEIGHT) buffer HeightBlock { float io_height[]; };

uniform int grid_pitch;

// std::min(std::max(s, lo), hi), the C++ argument order: (s < lo ? lo : s), then
// (hi < v ? hi : v).
float clamp_float(float s, float lo, float hi) {
  precise float low = s < lo ? lo : s;
  precise float clamped = hi < low ? hi : low;
  return clamped;
}

int clamp_int(int s, int lo, int hi) {
  const int low = s < lo ? lo : s;
  return hi < low ? hi : low;
}

// bspline_weights (core/height_sketch.h).
void bspline_weights(float t, out float w[4]) {
  precise float s = 1.0 - t;
  precise float w0 = divide((s * s) * s, 6.0);
  precise float w1 = divide((((t * 3.0) - 6.0) * t) * t + 4.0, 6.0);
  precise float w2 = divide((((3.0 - t * 3.0) * t + 3.0) * t) + 1.0, 6.0);
  precise float w3 = divide((t * t) * t, 6.0);
  w[0] = w0;
  w[1] = w1;
  w[2] = w2;
  w[3] = w3;
}

// sample_grid (core/height_sketch.cc): the B-spline of a width x height grid of samples from
// sketch_heights[offset], at texel coordinate (sx_in, sz_in).
float sample_grid(int offset, int width, int height, float max_x, float max_z, float sx_in,
                  float sz_in) {
  precise float sx = clamp_float(sx_in, -2.0, max_x);
  precise float sz = clamp_float(sz_in, -2.0, max_z);
  precise float fx = floor(sx);
  precise float fz = floor(sz);
  float wx[4], wz[4];
  bspline_weights(sx - fx, wx);
  bspline_weights(sz - fz, wz);
  const int i = int(fx);
  const int j = int(fz);
  int column[4];
  for (int k = 0; k < 4; ++k) {
    column[k] = offset + clamp_int(i + k - 1, 0, width - 1);  // clamp to the edge
  }
  precise float sum = 0.0;
  for (int m = 0; m < 4; ++m) {
    const int row = clamp_int(j + m - 1, 0, height - 1) * width;
    precise float r = ((wx[0] * sketch_heights[row + column[0]] +
                        wx[1] * sketch_heights[row + column[1]]) +
                       wx[2] * sketch_heights[row + column[2]]) +
                      wx[3] * sketch_heights[row + column[3]];
    if (m == 0) {
      sum = wz[0] * r;
    } else {
      sum = sum + wz[m] * r;
    }
  }
  return sum;
}

// sample_field_level: level `level` at level 0's texel coordinate (sx, sz).
float sample_field_level(int level, float sx, float sz) {
  const int width = sketch.level_width[level];
  const int height = sketch.level_height[level];
  precise float lx = sx * sketch.level_scale[level];
  precise float lz = sz * sketch.level_scale[level];
  return sample_grid(sketch.level_offset[level], width, height, float(width + 1),
                     float(height + 1), lx, lz);
}

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i >= grid_pitch) {
    return;
  }
  const int k = int(gl_GlobalInvocationID.y) * grid_pitch + i;
  if (RELIEF_BYTE(in_mask, k) == 0u) {
    return;  // not evaluated: fbm.comp left 0, no consumer reads it
  }
  precise float sx = sketch.offset_x + in_dx[k] * sketch.inv_cell_x;
  precise float sz = sketch.offset_z + in_dz[k] * sketch.inv_cell_z;
  if (sketch.levels <= 1) {
    precise float height =
        io_height[k] + sample_grid(0, sketch.width, sketch.height, sketch.max_x, sketch.max_z, sx,
                                   sz);
    io_height[k] = height;
    return;
  }
  // A height field's level of detail (add_sketch): lambda clamped to [0, levels - 1], both
  // levels sampled and blended.
  precise float lambda =
      clamp_float(sketch.lod_origin - in_nu[k], 0.0, float(sketch.levels - 1));
  precise float floor_lambda = floor(lambda);
  precise float t = lambda - floor_lambda;
  const int a = int(floor_lambda);
  const int b = min(a + 1, sketch.levels - 1);
  precise float fine = sample_field_level(a, sx, sz);
  precise float coarse = sample_field_level(b, sx, sz);
  precise float height = io_height[k] + (fine + t * (coarse - fine));
  io_height[k] = height;
}
