// The bend of a planet frame (§4.1, docs/planet.md): bend_vertices of core/planet_bend.cc, one
// invocation per vertex of the row pitch, after stage 3. Each valid vertex's arc offset
// (dx, dz) and camera-relative height to its camera-relative position on the sphere, with no
// R-sized term cancelling; zeros where invalid. sin and cos are det_math.glsl's, the CPU's
// operation order, so the GL bends as every CPU backend does.
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_PLANET) readonly buffer PlanetParamsBlock {
  PlanetParams planet;
};
layout(std430, binding = RELIEF_BINDING_DX) readonly buffer DxBlock { float in_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) readonly buffer DzBlock { float in_dz[]; };
layout(std430, binding = RELIEF_BINDING_HEIGHT) readonly buffer HeightBlock { float in_height[]; };
layout(std430, binding = RELIEF_BINDING_VALID) readonly buffer ValidBlock { uint in_valid[]; };
layout(std430, binding = RELIEF_BINDING_BENT_X) writeonly buffer BentXBlock { float out_x[]; };
layout(std430, binding = RELIEF_BINDING_BENT_Y) writeonly buffer BentYBlock { float out_y[]; };
layout(std430, binding = RELIEF_BINDING_BENT_Z) writeonly buffer BentZBlock { float out_z[]; };
layout(std430, binding = RELIEF_BINDING_BENT_DROP) writeonly buffer DropBlock { float out_drop[]; };

uniform int grid_pitch;

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i >= grid_pitch) {
    return;  // the last work group of a row may overhang it
  }
  const int k = int(gl_GlobalInvocationID.y) * grid_pitch + i;
  precise float x = 0.0, y = 0.0, z = 0.0, drop = 0.0;
  if (RELIEF_BYTE(in_valid, k) != 0u) {
    const float dx = in_dx[k], dz = in_dz[k], height = in_height[k];
    precise float rho = square_root(dx * dx + dz * dz);
    precise float theta = rho * planet.inv_radius;
    float sine, cosine;
    sin_cos_det(theta, sine, cosine);
    // sinc: 1 at 0 (the limit); domain of the division: theta > 0.
    precise float sinc = theta > 0.0 ? divide(sine, theta) : 1.0;
    precise float half_sine = sin_det(theta * 0.5);
    precise float radius_here = planet.center_distance + height;  // R + e
    precise float scale = radius_here * planet.inv_radius * sinc;
    drop = radius_here * (2.0 * half_sine * half_sine);
    x = dx * scale;
    z = dz * scale;
    y = height - drop;
  }
  out_x[k] = x;
  out_y[k] = y;
  out_z[k] = z;
  out_drop[k] = drop;
}
