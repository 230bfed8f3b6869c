// Stage 5 (core/vertex_transform.cc) per grid vertex: the camera-relative position
// (dx, h, dz) through the rows of the view-projection matrix, for glClipControl(GL_LOWER_LEFT,
// GL_ZERO_TO_ONE) and reverse-Z (z_clip = near, w = distance along the view axis). The grid's
// streams arrive as vertex attributes read straight from their buffer objects (no copy): the
// index buffer holds grid vertex indices j * pitch + i, so attribute k is stream[k].

// TransformParams<float> as its bytes lie in C++: scalars only, so std140 places them at
// 0, 4, ..., 36 like the struct (a float[3] would take a 16-byte stride under std140).
layout(std140, binding = 0) uniform TransformBlock {
  float row_x0, row_x1, row_x2;
  float row_y0, row_y1, row_y2;
  float row_w0, row_w1, row_w2;
  float z_clip;
}
T;

layout(location = 0) in float a_dx;
layout(location = 1) in float a_dz;
layout(location = 2) in float a_height;
layout(location = 3) in float a_nx;
layout(location = 4) in float a_ny;
layout(location = 5) in float a_nz;
layout(location = 6) in float a_slope;
layout(location = 7) in float a_water_depth;
layout(location = 8) in float a_nu;
layout(location = 9) in uint a_valid;
layout(location = 10) in uint a_need;  // VertexNeed flags; kDraw (2) where no stream is bound
// The y stage 5 transforms: the height on the plane, a planet's bent y (whose x and z are then
// a_dx and a_dz); and a planet's curvature drop, 0 where no stream is bound (docs/planet.md).
layout(location = 11) in float a_position_y;
layout(location = 12) in float a_drop;

out float v_dx, v_dz, v_height;
out float v_nx, v_ny, v_nz;
out float v_slope, v_water_depth, v_nu;
out float v_drop;

// The height is interpolated as an offset from this camera-relative height (a planet's datum,
// 0 on the plane): GL's interpolation arithmetic errs by a few ulps of the interpolated
// values' size, and a planet's heights are the camera's altitude in size (docs/gl-shading.md).
uniform float u_height_origin;

void main() {
  v_dx = a_dx;
  v_dz = a_dz;
  precise float offset = a_height - u_height_origin;  // exact: both near the datum (Sterbenz)
  v_height = offset;
  v_nx = a_nx;
  v_ny = a_ny;
  v_nz = a_nz;
  v_slope = a_slope;
  v_water_depth = a_water_depth;
  v_nu = a_nu;
  v_drop = a_drop;
  if (a_valid == 0u || (a_need & 2u) == 0u) {
    // In no drawn triangle (only in the degenerate ones of skipped cells): whatever the
    // stream holds there, a fixed finite position.
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  const float px = a_dx, py = a_position_y, pz = a_dz;
  precise float x = T.row_x0 * px + T.row_x1 * py + T.row_x2 * pz;
  precise float y = T.row_y0 * px + T.row_y1 * py + T.row_y2 * pz;
  precise float w = T.row_w0 * px + T.row_w1 * py + T.row_w2 * pz;
  gl_Position = vec4(x, y, T.z_clip, w);
}
