// The normals of a planet frame into the bent frame (§4.1, docs/planet.md): bend_normals of
// core/planet_bend.cc, one invocation per vertex of the row pitch, after stage 4. The local
// frame at (theta, direction u) is the camera's rotated by theta about the horizontal axis
// perpendicular to u (cos theta - 1 written as -2 sin^2(theta/2): no cancellation near 0).
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_PLANET) readonly buffer PlanetParamsBlock {
  PlanetParams planet;
};
layout(std430, binding = RELIEF_BINDING_DX) readonly buffer DxBlock { float in_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) readonly buffer DzBlock { float in_dz[]; };
layout(std430, binding = RELIEF_BINDING_VALID) readonly buffer ValidBlock { uint in_valid[]; };
layout(std430, binding = RELIEF_BINDING_NX) buffer NxBlock { float io_nx[]; };
layout(std430, binding = RELIEF_BINDING_NY) buffer NyBlock { float io_ny[]; };
layout(std430, binding = RELIEF_BINDING_NZ) buffer NzBlock { float io_nz[]; };

uniform int grid_pitch;

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  if (i >= grid_pitch) {
    return;  // the last work group of a row may overhang it
  }
  const int k = int(gl_GlobalInvocationID.y) * grid_pitch + i;
  const float dx = in_dx[k], dz = in_dz[k];
  precise float rho = square_root(dx * dx + dz * dz);
  if (RELIEF_BYTE(in_valid, k) == 0u || !(rho > 0.0)) {
    return;  // the nadir's frame is the camera's
  }
  precise float theta = rho * planet.inv_radius;
  precise float sine = sin_det(theta);
  precise float half_sine = sin_det(theta * 0.5);
  precise float cos_minus_one = -2.0 * half_sine * half_sine;
  precise float ux = divide(dx, rho);  // domain: rho > 0
  precise float uz = divide(dz, rho);
  const float nx = io_nx[k], n_y = io_ny[k], nz = io_nz[k];
  precise float along = nx * ux + nz * uz;
  precise float delta = along * cos_minus_one + n_y * sine;  // the change of the along part
  precise float new_x = nx + delta * ux;
  precise float new_z = nz + delta * uz;
  precise float new_y = n_y + n_y * cos_minus_one - along * sine;
  io_nx[k] = new_x;
  io_nz[k] = new_z;
  io_ny[k] = new_y;
}
