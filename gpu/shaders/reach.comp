// Between stages 2 and 3: octave_reach of core/octave_coordinates.cc, the farthest valid
// vertex per finest octave summed (octave ceil(nu) - 1), max(|dx|, |dz|). The maximum is taken
// with atomicMax on the float's bits, which order as the floats do for non-negative values;
// the reach block is cleared to 0 (+0.0) before the pass. The CPU forms the same maximum in
// double from the same floats, so the two agree exactly.
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_DX) readonly buffer DxBlock { float in_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) readonly buffer DzBlock { float in_dz[]; };
layout(std430, binding = RELIEF_BINDING_NU) readonly buffer NuBlock { float in_nu[]; };
layout(std430, binding = RELIEF_BINDING_VALID) readonly buffer ValidBlock { uint in_valid[]; };
// Per octave n, the bits of the farthest extent of a valid vertex whose finest octave is n.
layout(std430, binding = RELIEF_BINDING_REACH) buffer ReachBlock {
  uint by_finest[RELIEF_MAX_OCTAVES];
};

uniform int grid_pitch;

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i >= grid_pitch) {
    return;
  }
  const int k = int(gl_GlobalInvocationID.y) * grid_pitch + i;
  if (RELIEF_BYTE(in_valid, k) == 0u) {
    return;
  }
  // nu outside [1, N] sums what fbm.comp sums for it: octave 0 at most below 1, every octave
  // above N (the comparisons are exact in float as in double).
  const float nu = in_nu[k];
  int n = RELIEF_MAX_OCTAVES - 1;
  if (nu <= 1.0) {
    n = 0;
  } else if (nu < float(RELIEF_MAX_OCTAVES)) {
    n = int(ceil(nu)) - 1;
  }
  const float extent = max(abs(in_dx[k]), abs(in_dz[k]));
  atomicMax(by_finest[n], floatBitsToUint(extent));
}
