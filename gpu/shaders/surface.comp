// Stage 4, the surface pass (§4.1, "additional properties ... derived in a second pass"):
// core/surface.cc, one invocation per vertex of the row pitch. The normal and slope come from
// the neighbouring displaced vertices through the 2x2 solve that core/surface.h explains.
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_PARAMS) readonly buffer SurfaceParamsBlock {
  SurfaceParams surface;
};
layout(std430, binding = RELIEF_BINDING_DX) readonly buffer DxBlock { float in_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) readonly buffer DzBlock { float in_dz[]; };
layout(std430, binding = RELIEF_BINDING_HEIGHT) readonly buffer HeightBlock {
  float in_height[];
};
layout(std430, binding = RELIEF_BINDING_VALID) readonly buffer ValidBlock { uint in_valid[]; };
// The need flags (core/vertex_culling.h): only kDraw vertices are computed. Bound to the valid
// stream, with use_need 0, when every valid vertex is.
layout(std430, binding = RELIEF_BINDING_MASK) readonly buffer MaskBlock { uint in_need[]; };
layout(std430, binding = RELIEF_BINDING_NX) writeonly buffer NxBlock { float out_nx[]; };
layout(std430, binding = RELIEF_BINDING_NY) writeonly buffer NyBlock { float out_ny[]; };
layout(std430, binding = RELIEF_BINDING_NZ) writeonly buffer NzBlock { float out_nz[]; };
layout(std430, binding = RELIEF_BINDING_SLOPE) writeonly buffer SlopeBlock { float out_slope[]; };
layout(std430, binding = RELIEF_BINDING_WATER_DEPTH) writeonly buffer WaterDepthBlock {
  float out_water_depth[];
};

uniform int use_need;

struct Tangent {
  float x, h, z;
  bool present;
};

float abs_max3(float a, float b, float c) {
  const float ab = a < b ? b : a;
  return ab < c ? c : ab;
}

// Difference across vertex c along one grid axis: central where both neighbours are valid,
// one-sided otherwise; `minus`/`plus` are indices or -1 outside the grid. Scaled by the
// positive 1 / max(|x|, |h|, |z|) (core/surface.cc says why).
Tangent axis_tangent(int minus, int c, int plus) {
  const bool has_minus = minus >= 0 && RELIEF_BYTE(in_valid, minus) != 0u;
  const bool has_plus = plus >= 0 && RELIEF_BYTE(in_valid, plus) != 0u;
  const int from = has_minus ? minus : c;
  const int to = has_plus ? plus : c;
  Tangent t = Tangent(0.0, 0.0, 0.0, has_minus || has_plus);
  if (t.present) {
    precise float tx = in_dx[to] - in_dx[from];
    precise float th = in_height[to] - in_height[from];
    precise float tz = in_dz[to] - in_dz[from];
    const float largest = abs_max3(abs(tx), abs(th), abs(tz));
    if (largest > 0.0) {
      tx = divide(tx, largest);
      th = divide(th, largest);
      tz = divide(tz, largest);
    }
    t = Tangent(tx, th, tz, true);
  }
  return t;
}

// (x, h, z) scaled by 1 / max(|x|, |h|, |z|) where that is > 0.
void scale_to_unit_max(inout float x, inout float h, inout float z) {
  const float largest = abs_max3(abs(x), abs(h), abs(z));
  if (largest > 0.0) {
    x = divide(x, largest);
    h = divide(h, largest);
    z = divide(z, largest);
  }
}

// p[to] - p[from] (core/surface.cc, side_difference: the weighted sum takes it as it is, the
// facing weight scaled).
Tangent side_difference(int from, int to) {
  precise float x = in_dx[to] - in_dx[from];
  precise float h = in_height[to] - in_height[from];
  precise float z = in_dz[to] - in_dz[from];
  return Tangent(x, h, z, true);
}

Tangent scaled(Tangent t) {
  float x = t.x, h = t.h, z = t.z;
  scale_to_unit_max(x, h, z);
  return Tangent(x, h, z, true);
}

// How much the patch of u (along i) and w (along j) faces the eye, along `ray` (scaled) of
// length ray_length (core/surface.cc, facing_weight).
float facing_weight(Tangent u, Tangent w, vec3 ray, float ray_length) {
  precise float nx = -(u.h * w.z - u.z * w.h);
  precise float ny = u.x * w.z - u.z * w.x;
  precise float nz = -(u.x * w.h - u.h * w.x);
  precise float up = ny > 0.0 ? 1.0 : -1.0;
  precise float facing = -((nx * ray.x + ny * ray.y) + nz * ray.z) * up;
  precise float length = square_root((nx * nx + ny * ny) + nz * nz) * ray_length;
  if (!(length > 0.0)) {
    return 1.0;
  }
  precise float weight = divide(facing, length) * surface.inv_silhouette_facing;
  const float least = surface.hidden_side_weight;
  return weight < least ? least : (weight > 1.0 ? 1.0 : weight);
}

// core/surface.cc, weigh_sides: the halves as they are, summed, then scaled.
Tangent weigh_sides(Tangent t, Tangent minus, float w_minus, Tangent plus, float w_plus) {
  if (w_minus == 1.0 && w_plus == 1.0) {
    return t;
  }
  precise float x = w_minus * minus.x + w_plus * plus.x;
  precise float h = w_minus * minus.h + w_plus * plus.h;
  precise float z = w_minus * minus.z + w_plus * plus.z;
  scale_to_unit_max(x, h, z);
  return Tangent(x, h, z, t.present);
}

bool valid_at(int n) { return n >= 0 && RELIEF_BYTE(in_valid, n) != 0u; }

int index_or_none(int i, int j) {
  if (i < 0 || i >= surface.width || j < 0 || j >= surface.height) {
    return -1;
  }
  return j * surface.pitch + i;
}

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i >= surface.pitch) {
    return;
  }
  const int j = int(gl_GlobalInvocationID.y);
  const int k = j * surface.pitch + i;
  precise float nx_out = 0.0, ny_out = 1.0, nz_out = 0.0, slope = 0.0, water_depth = 0.0;
  const bool drawn = use_need == 0 || (RELIEF_BYTE(in_need, k) & RELIEF_NEED_DRAW) != 0u;
  if (i < surface.width && RELIEF_BYTE(in_valid, k) != 0u && drawn) {
    const int left = index_or_none(i - 1, j), right = index_or_none(i + 1, j);
    const int below = index_or_none(i, j - 1), above = index_or_none(i, j + 1);
    Tangent a = axis_tangent(left, k, right);
    Tangent b = axis_tangent(below, k, above);
    // Visible sides (core/surface.cc): each half of a central difference weighted by how much
    // its side faces the eye, the weights formed from the central tangents.
    float ray_x = in_dx[k], ray_h = in_height[k], ray_z = in_dz[k];
    scale_to_unit_max(ray_x, ray_h, ray_z);
    const vec3 ray = vec3(ray_x, ray_h, ray_z);
    precise float ray_length = square_root((ray_x * ray_x + ray_h * ray_h) + ray_z * ray_z);
    if (ray_length > 0.0) {
      Tangent weighted_a = a, weighted_b = b;
      if (valid_at(left) && valid_at(right)) {
        const Tangent minus = side_difference(left, k), plus = side_difference(k, right);
        weighted_a = weigh_sides(a, minus, facing_weight(scaled(minus), b, ray, ray_length), plus,
                                 facing_weight(scaled(plus), b, ray, ray_length));
      }
      if (valid_at(below) && valid_at(above)) {
        const Tangent minus = side_difference(below, k), plus = side_difference(k, above);
        weighted_b = weigh_sides(b, minus, facing_weight(a, scaled(minus), ray, ray_length), plus,
                                 facing_weight(a, scaled(plus), ray, ray_length));
      }
      a = weighted_a;
      b = weighted_b;
    }
    // Unnormalised normal (-gx, 1, -gz) scaled by a positive factor: |det| for the 2x2 solve
    // (no division), |a|^2 for the one-axis least-norm gradient.
    precise float a_sq = a.x * a.x + a.z * a.z;
    precise float b_sq = b.x * b.x + b.z * b.z;
    precise float det = a.x * b.z - a.z * b.x;
    precise float nx = 0.0, ny = 1.0, nz = 0.0;
    precise float det_sq = det * det;
    precise float sine_bound = surface.min_sine_sq * a_sq * b_sq;
    if (a.present && b.present && det_sq > sine_bound) {
      precise float det_sign = det > 0.0 ? 1.0 : -1.0;
      nx = -(a.h * b.z - a.z * b.h) * det_sign;
      ny = det * det_sign;
      nz = -(a.x * b.h - a.h * b.x) * det_sign;
    } else if (a.present && a_sq > 0.0) {
      nx = -a.h * a.x;
      ny = a_sq;
      nz = -a.h * a.z;
    } else if (b.present && b_sq > 0.0) {
      nx = -b.h * b.x;
      ny = b_sq;
      nz = -b.h * b.z;
    }
    // Divided by the largest component first (> 0 because ny > 0), so no square overflows.
    const float largest = abs_max3(abs(nx), ny, abs(nz));
    nx = divide(nx, largest);
    ny = divide(ny, largest);
    nz = divide(nz, largest);
    precise float horizontal_sq = nx * nx + nz * nz;
    precise float inv_length = divide(1.0, square_root(horizontal_sq + ny * ny));
    nx_out = nx * inv_length;
    ny_out = ny * inv_length;
    nz_out = nz * inv_length;
    // |g| = horizontal / ny, capped at kMaxSlope.
    precise float gradient = divide(square_root(horizontal_sq), ny);
    slope = surface.max_slope < gradient ? surface.max_slope : gradient;
    if (surface.water_enabled != 0) {
      precise float below = surface.water_level - in_height[k];
      water_depth = 0.0 < below ? below : 0.0;
    }
  }
  out_nx[k] = nx_out;
  out_ny[k] = ny_out;
  out_nz[k] = nz_out;
  out_slope[k] = slope;
  out_water_depth[k] = water_depth;
}
