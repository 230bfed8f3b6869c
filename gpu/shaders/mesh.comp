// GeoMipMapping's vertex stages 2, 3 and 4 (terrain.heightfield.geomipmap): the GLSL twin of
// mesh_domain, mesh_heights and mesh_surface of core/heightfield/field_mesh.cc, operation for
// operation and in double as there, one invocation per vertex of the mesh's rows (the grid
// streams laid out as rows of kMeshRowVertices, gl_terrain.h). The CPU chooses the tiles, their
// levels and the stitched index list once per frame (de Boer's GeoMipMapping and Scape choose
// levels on the CPU and draw index buffers on the GPU); vertex k is the field lattice's point
// (column, row) = mesh_vertex[k], mesh_vertex[u_vertices + k]. One file, three programs: the prelude
// defines RELIEF_MESH_STAGE (2, 3 or 4), so each declares only the blocks it binds.
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_ROWS) readonly buffer MeshVertexBlock {
  int mesh_vertex[];  // every vertex's column, then every vertex's row
};

uniform int u_vertices;  // the mesh's vertices: those after them are padding

// Vertex k: a work group per RELIEF_GROUP_SIZE vertices of a row, a row of groups per row.
int vertex_index() {
  return int(gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) +
             gl_GlobalInvocationID.x);
}

#if RELIEF_MESH_STAGE == 2
layout(std430, binding = RELIEF_BINDING_DX) writeonly buffer DxBlock { float out_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) writeonly buffer DzBlock { float out_dz[]; };
layout(std430, binding = RELIEF_BINDING_SIGMA) writeonly buffer SigmaBlock { float out_sigma[]; };
layout(std430, binding = RELIEF_BINDING_NU) writeonly buffer NuBlock { float out_nu[]; };
layout(std430, binding = RELIEF_BINDING_VALID) writeonly buffer ValidBlock { uint out_valid[]; };

uniform dvec4 u_extent;       // world (x, z) of lattice vertex (0, 0) and of the last one
uniform ivec2 u_lattice;      // lattice vertices along x and z (>= 2)
uniform dvec2 u_camera_xz;    // the camera's world x and z
uniform float u_spacing;      // sigma: float(max(cell_x, cell_z))

// The work group's valid bytes, four to a word (a group is a multiple of 4 vertices and starts
// on a word), as domain.comp writes them.
shared uint valid_words[RELIEF_GROUP_SIZE / 4];

void main() {
  const uint local = gl_LocalInvocationID.x;
  if ((local & 3u) == 0u) {
    valid_words[local >> 2] = 0u;
  }
  barrier();
  const int k = vertex_index();
  const bool vertex = k < u_vertices;
  precise float dx = 0.0, dz = 0.0, sigma = 0.0;
  if (vertex) {
    // FieldLattice::position: the divisions by columns - 1 >= 1 and rows - 1 >= 1.
    precise double fx = double(mesh_vertex[k]) / double(u_lattice.x - 1);
    precise double fz = double(mesh_vertex[u_vertices + k]) / double(u_lattice.y - 1);
    precise double x = u_extent.x + (u_extent.z - u_extent.x) * fx;
    precise double z = u_extent.y + (u_extent.w - u_extent.y) * fz;
    precise double relative_x = x - u_camera_xz.x;
    precise double relative_z = z - u_camera_xz.y;
    dx = float(relative_x);
    dz = float(relative_z);
    sigma = u_spacing;
    atomicOr(valid_words[local >> 2], 1u << (8u * (local & 3u)));
  }
  out_dx[k] = dx;
  out_dz[k] = dz;
  out_sigma[k] = sigma;
  out_nu[k] = 0.0;  // no octave: the field alone
  barrier();
  if ((local & 3u) == 0u) {
    out_valid[k >> 2] = valid_words[local >> 2];
  }
}
#else
// The field's texels (level 0 first, as the sketch's storage holds them), row j at j * width.
layout(std430, binding = RELIEF_BINDING_SKETCH) readonly buffer SketchBlock { float texel[]; };

uniform ivec2 u_texels;       // width, height (>= 2)
uniform dvec2 u_knot_weight;  // the B-spline's weights at a knot: 1/6 and 4/6 (the CPU's)

// The texel (i, j), the edge texels extended (GL_CLAMP_TO_EDGE).
double texel_at(int i, int j) {
  const int column = clamp(i, 0, u_texels.x - 1);
  const int row = clamp(j, 0, u_texels.y - 1);
  return double(texel[row * u_texels.x + column]);
}

double knot_weight(int a) { return a == 0 ? u_knot_weight.y : u_knot_weight.x; }

#if RELIEF_MESH_STAGE == 3
layout(std430, binding = RELIEF_BINDING_HEIGHT) writeonly buffer HeightBlock {
  float out_height[];
};

uniform double u_camera_above_base;  // the camera's height above terrain.base_height

void main() {
  const int k = vertex_index();
  float height = 0.0;
  if (k < u_vertices) {
    const int c = mesh_vertex[k], r = mesh_vertex[u_vertices + k];
    // build_field_mesh's lattice height: the B-spline at the texel centre, summed in double
    // in its order and rounded once to float; then mesh_heights' difference, in double.
    precise double sum = 0.0LF;
    for (int b = -1; b <= 1; ++b) {
      precise double row = 0.0LF;
      for (int a = -1; a <= 1; ++a) {
        row += knot_weight(a) * texel_at(c + a, r + b);
      }
      sum += knot_weight(b) * row;
    }
    const float lattice_height = float(sum);
    precise double relative = double(lattice_height) - u_camera_above_base;
    height = float(relative);
  }
  out_height[k] = height;
}
#else
layout(std430, binding = RELIEF_BINDING_HEIGHT) readonly buffer HeightBlock { float in_height[]; };
layout(std430, binding = RELIEF_BINDING_NX) writeonly buffer NxBlock { float out_nx[]; };
layout(std430, binding = RELIEF_BINDING_NY) writeonly buffer NyBlock { float out_ny[]; };
layout(std430, binding = RELIEF_BINDING_NZ) writeonly buffer NzBlock { float out_nz[]; };
layout(std430, binding = RELIEF_BINDING_SLOPE) writeonly buffer SlopeBlock { float out_slope[]; };
layout(std430, binding = RELIEF_BINDING_WATER_DEPTH) writeonly buffer WaterDepthBlock {
  float out_water_depth[];
};

uniform dvec2 u_inverse_twice_cell;  // 0.5 / cell_x, 0.5 / cell_z (cells > 0)
uniform double u_max_slope;          // limits::kMaxSlope
uniform int u_water;                 // water enabled (SurfaceParams::water_enabled)
uniform float u_water_level;         // camera-relative (SurfaceParams::water_level)

void main() {
  const int k = vertex_index();
  float nx = 0.0, ny = 1.0, nz = 0.0, slope = 0.0, water_depth = 0.0;
  if (k < u_vertices) {
    const int c = mesh_vertex[k], r = mesh_vertex[u_vertices + k];
    // The B-spline's gradient at the knot: central differences of the texels on either side,
    // weighted (1, 4, 1) / 6 across (mesh_surface).
    precise double gx = 0.0LF, gz = 0.0LF;
    for (int b = -1; b <= 1; ++b) {
      gx += knot_weight(b) * (texel_at(c + 1, r + b) - texel_at(c - 1, r + b));
      gz += knot_weight(b) * (texel_at(c + b, r + 1) - texel_at(c + b, r - 1));
    }
    gx *= u_inverse_twice_cell.x;
    gz *= u_inverse_twice_cell.y;
    // |g| is finite (finite texels, positive cells): the length is >= 1, the divisions defined.
    precise double length = sqrt(gx * gx + gz * gz + 1.0LF);
    precise double x = -gx / length, y = 1.0LF / length, z = -gz / length;
    nx = float(x);
    ny = float(y);
    nz = float(z);
    precise double steepness = sqrt(gx * gx + gz * gz);
    slope = float(u_max_slope < steepness ? u_max_slope : steepness);  // std::min's order
    if (u_water != 0) {
      precise float depth = u_water_level - in_height[k];
      water_depth = 0.0 < depth ? depth : 0.0;  // std::max(0, depth): (0 < depth) ? depth : 0
    }
  }
  out_nx[k] = nx;
  out_ny[k] = ny;
  out_nz[k] = nz;
  out_slope[k] = slope;
  out_water_depth[k] = water_depth;
}
#endif
#endif
