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

float sample_sketch(float sx_in, float sz_in) {
  precise float sx = clamp_float(sx_in, -2.0, sketch.max_x);
  precise float sz = clamp_float(sz_in, -2.0, sketch.max_z);
  precise float fx = floor(sx);
  precise float fz = floor(sz);
  float wx[4], wz[4];
  bspline_weights(sx - fx, wx);
  bspline_weights(sz - fz, wz);
  const int i = int(fx);
  const int j = int(fz);
  int column[4];
  for (int k = 0; k < 4; ++k) {
    column[k] = clamp_int(i + k - 1, 0, sketch.width - 1);  // clamp to the edge
  }
  precise float sum = 0.0;
  for (int m = 0; m < 4; ++m) {
    const int row = clamp_int(j + m - 1, 0, sketch.height - 1) * sketch.width;
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
  precise float height = io_height[k] + sample_sketch(sx, sz);
  io_height[k] = height;
}
