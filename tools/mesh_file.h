// A height field's triangle mesh as a file, for `relief export --mesh`: Wavefront OBJ (text) or
// binary glTF 2.0 (.glb). Two triangles per cell of the samples, counter-clockwise seen from
// above (+y, glTF's and Relief's up), the cell split along the same diagonal as Relief's grid
// (from (i, j + 1) to (i + 1, j)); positions, unit normals and texture coordinates (u along x,
// 0 to 1 over the region; v down the image in glTF, up it in OBJ, as each format defines v, so
// the splat and normal maps drape over it the same way).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace relief {

enum class MeshFormat { kObj, kGlb };

// By the file name's extension (.obj or .glb, any letter case), or nullopt.
std::optional<MeshFormat> mesh_format(const std::string& name);

struct MeshGrid {
  int width = 2, height = 2;                  // samples along x and z (>= 2)
  std::array<double, 4> rect = {0, 0, 1, 1};  // the region: sample (i, j) at its texel centre
  std::span<const float> heights;             // width x height world heights, row j along z
  std::span<const float> normals;             // 3 per sample, unit
};

// Bytes the file will take at most (for the memory estimate).
std::uintmax_t mesh_file_bytes(MeshFormat format, int width, int height);

// The file's bytes. OBJ: world coordinates, as decimal text with enough digits to read back
// the same floats (and doubles for x and z). glTF: positions relative to the region's centre
// in float (a region far from the origin keeps its detail), the centre as the node's
// translation (JSON numbers: doubles).
std::vector<unsigned char> encode_mesh(MeshFormat format, const MeshGrid& grid);

}  // namespace relief
