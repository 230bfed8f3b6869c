// Stages 7-9 for a covered pixel: the attributes GL interpolated (perspective-correct), their
// fine quad derivatives (GL's helper invocations evaluate the pixel's own triangle at the quad
// partners, as raster/resolve.h does), the shading of stage 8 and the sRGB code of stage 9.
in float v_dx, v_dz, v_height;
in float v_nx, v_ny, v_nz;
in float v_slope, v_water_depth, v_nu;
in float v_drop;
in float v_lambert;

uniform double u_camera_y;  // world height = camera y + the camera-relative height, in double
uniform float u_height_origin;  // v_height is the height less this (terrain.vert)

layout(location = 0) out vec4 out_linear;
layout(location = 1) out uvec4 out_srgb;
layout(location = 2) out uint out_primitive;
layout(location = 3) out vec4 out_normal;
layout(location = 4) out vec2 out_height_octaves;

void main() {
  Attributes a;
  a.dx = v_dx;
  a.dz = v_dz;
  precise float height = u_height_origin + v_height;  // rounded once, as the CPU's resolve
  a.height = height;
  // In uniform control flow, before any branch.
  a.dx_ddx = dFdxFine(v_dx);
  a.dx_ddy = dFdyFine(v_dx);
  a.dz_ddx = dFdxFine(v_dz);
  a.dz_ddy = dFdyFine(v_dz);
  a.height_ddx = dFdxFine(v_height);
  a.height_ddy = dFdyFine(v_height);
  a.nx = v_nx;
  a.ny = v_ny;
  a.nz = v_nz;
  a.slope = v_slope;
  a.water_depth = v_water_depth;
  a.drop = v_drop;
  a.lambert = v_lambert;
  const vec3 radiance = terrain_radiance(a);
  precise vec3 rgb = radiance * P.exposure;
  out_linear = vec4(rgb, 1.0);
  out_srgb = uvec4(srgb_byte(rgb.r), srgb_byte(rgb.g), srgb_byte(rgb.b), 255u);
  out_primitive = uint(gl_PrimitiveID);  // the index list's order: the grid's, or the mesh's
  out_normal = vec4(normalize_or(vec3(v_nx, v_ny, v_nz), vec3(0.0, 1.0, 0.0)), 0.0);
  out_height_octaves = vec2(float(u_camera_y + double(a.height)), v_nu);
}
