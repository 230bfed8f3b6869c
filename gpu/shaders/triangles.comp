// The projected grid's triangulation (raster/topology.h, GridTriangles) as an index buffer:
// cell (i, j) with corners a = (i, j), b = (i+1, j), c = (i+1, j+1), d = (i, j+1) gives
// triangle 2 cell = (a, b, c) and 2 cell + 1 = (a, c, d), cell = j (width - 1) + i. A triangle
// the CPU does not draw (a corner of its cell invalid, or one of its vertices without kDraw)
// becomes (a, a, a): zero area, so it covers nothing, yet it keeps its place in the list, and
// gl_PrimitiveID is the CPU's primitive number. Computed on the GPU from the valid and need
// streams, so buffers another stage wrote there need no round trip.
layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer ValidBlock {
  uint valid_words[];  // one byte per vertex, four to a word (little-endian)
};
layout(std430, binding = 1) readonly buffer NeedBlock {
  uint need_words[];
};
layout(std430, binding = 2) writeonly buffer IndexBlock {
  uint indices[];
};

uniform uint u_width;  // grid vertices per row
uniform uint u_pitch;
uniform uint u_count;  // triangles: 2 (width - 1) (height - 1)
uniform bool u_has_need;

uint byte_of(uint word, uint k) { return (word >> (8u * (k & 3u))) & 0xffu; }
uint valid_at(uint k) { return byte_of(valid_words[k >> 2u], k); }
uint need_at(uint k) { return u_has_need ? byte_of(need_words[k >> 2u], k) : 2u; }

void main() {
  const uint t = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * 256u) + gl_GlobalInvocationID.x;
  if (t >= u_count) {
    return;
  }
  const uint cell = t >> 1u;
  const uint columns = u_width - 1u;
  const uint i = cell % columns, j = cell / columns;
  const uint a = j * u_pitch + i;
  const uint b = a + 1u;
  const uint d = a + u_pitch;
  const uint c = d + 1u;
  uint v1 = (t & 1u) != 0u ? c : b;
  uint v2 = (t & 1u) != 0u ? d : c;
  const bool cell_valid = valid_at(a) != 0u && valid_at(b) != 0u && valid_at(c) != 0u &&
                          valid_at(d) != 0u;
  const bool drawn = cell_valid && (need_at(a) & need_at(v1) & need_at(v2) & 2u) != 0u;
  if (!drawn) {
    v1 = a;
    v2 = a;
  }
  indices[3u * t] = a;
  indices[3u * t + 1u] = v1;
  indices[3u * t + 2u] = v2;
}
