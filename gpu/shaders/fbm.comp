// Stage 3, the octave-LOD fractal (§2.1 Eq. 1, §2.2 domain warping, §4.1 fractional octave):
// fbm_point of core/fbm.cc, one invocation per vertex of the row pitch. docs/terrain-spec.md is
// the specification this follows line by line.
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_PARAMS) readonly buffer FbmParamsBlock {
  FbmParams fbm;
};
layout(std430, binding = RELIEF_BINDING_DX) readonly buffer DxBlock { float in_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) readonly buffer DzBlock { float in_dz[]; };
layout(std430, binding = RELIEF_BINDING_NU) readonly buffer NuBlock { float in_nu[]; };
// Where to evaluate (non-zero bytes): the need flags of core/vertex_culling.h, or the valid
// stream when every valid vertex is evaluated.
layout(std430, binding = RELIEF_BINDING_MASK) readonly buffer MaskBlock { uint in_mask[]; };
layout(std430, binding = RELIEF_BINDING_HEIGHT) writeonly buffer HeightBlock {
  float out_height[];
};

uniform int grid_pitch;

// Octave n's coordinate g_n d without offset and warp, in the form the frame chose
// (octave_coordinates.h): exact modulo P, or direct (f_n u).
float scaled(int n, float d, float u) {
  precise float g;
  if (fbm.exact_coordinates[n] == 0) {
    g = fbm.frequency[n] * u;
  } else {
    float piece[3], hi[3], lo[3];
    for (int q = 0; q < 3; ++q) {
      piece[q] = fbm.scale_piece[q][n];
      hi[q] = fbm.scale_piece_hi[q][n];
      lo[q] = fbm.scale_piece_lo[q][n];
    }
    g = exact_scaled_mod(piece, hi, lo, d, split_halves(d), fbm.period, fbm.inv_period);
  }
  return g;
}

float fbm_point(float dx, float dz, float nu) {
  precise float ux = dx * fbm.inv_scale;
  precise float uz = dz * fbm.inv_scale;
  precise float whole = floor(nu);
  const int full_octaves = whole < float(fbm.count) ? int(whole) : fbm.count;
  precise float fraction = nu - whole;
  precise float h = 0.0;
  precise float wx = fbm.t0x, wz = fbm.t0z;  // W_n, §2.2, in lattice cells of octave n
  precise float rx = fbm.r0x, rz = fbm.r0z;  // rot_n, §2.2
  for (int n = 0; n < fbm.count; ++n) {
    // §4.1: floor(nu) whole octaves, then one weighted by the fractional part.
    precise float weight = n < full_octaves ? 1.0 : fraction;
    if (n > full_octaves || weight == 0.0) {
      break;
    }
    // Eq. 1: S(r^k x), camera-relative, displaced by the warp.
    precise float px = fbm.offset_x[n] + scaled(n, dx, ux) + wx;
    precise float pz = fbm.offset_z[n] + scaled(n, dz, uz) + wz;
    precise float s = sample_lattice(fbm.interpolant, px, pz);
    h = h + (weight * fbm.amplitude[n]) * s;
    if (fbm.warp == 0 || n == full_octaves || n + 1 == fbm.count) {
      continue;  // no further octave reads W
    }
    // §2.2: roughness R_n = R0 - h_n and the guarded 1/R_n (kRoughnessGuard).
    precise float roughness = fbm.roughness0 - h;
    precise float inv_roughness = divide(roughness, roughness * roughness + fbm.guard_sq);
    // §2.2: rot_{n+1} = c1 R_n + c2 + rot_n, renormalised; kept when its length vanishes.
    precise float vx = fbm.c1x * roughness + fbm.c2x + rx;
    precise float vz = fbm.c1z * roughness + fbm.c2z + rz;
    precise float length_sq = vx * vx + vz * vz;
    if (length_sq > fbm.min_rotation_sq) {
      precise float inv_length = divide(1.0, square_root(length_sq));
      rx = vx * inv_length;
      rz = vz * inv_length;
    }
    // §2.2: t_{n+1} = c3 h_n / R_n; W_{n+1} = r (Rot(rot_{n+1}) W_n + t_{n+1}).
    precise float height_over_roughness = h * inv_roughness;
    precise float next_wx = (rx * wx - rz * wz) + fbm.c3x * height_over_roughness;
    precise float next_wz = (rz * wx + rx * wz) + fbm.c3z * height_over_roughness;
    wx = fbm.lacunarity * next_wx;
    wz = fbm.lacunarity * next_wz;
  }
  precise float height = fbm.relative_base_height + fbm.height_scale * h;
  return height;
}

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i >= grid_pitch) {
    return;
  }
  const int k = int(gl_GlobalInvocationID.y) * grid_pitch + i;
  precise float height = 0.0;  // not needed (core/vertex_culling.h): no consumer reads it
  if (RELIEF_BYTE(in_mask, k) != 0u) {
    height = fbm_point(in_dx[k], in_dz[k], in_nu[k]);
  }
  out_height[k] = height;
}
