#include "tools/mesh_file.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/input_file.h"

namespace relief {

namespace {

struct Vertex {
  double x, z;  // world
};

// width, height >= 2 (MeshGrid): the divisions' domain.
Vertex vertex(const MeshGrid& g, int i, int j) {
  const auto& r = g.rect;
  return {r[0] + (double(i) + 0.5) * ((r[2] - r[0]) / g.width),
          r[1] + (double(j) + 0.5) * ((r[3] - r[1]) / g.height)};
}

// The two triangles of cell (i, j), counter-clockwise seen from +y: (i, j), (i, j + 1),
// (i + 1, j) and (i + 1, j), (i, j + 1), (i + 1, j + 1), as indices of row-major samples.
template <class Emit>
void for_each_triangle(const MeshGrid& g, Emit emit) {
  for (int j = 0; j + 1 < g.height; ++j) {
    for (int i = 0; i + 1 < g.width; ++i) {
      const std::uint32_t a = std::uint32_t(j) * std::uint32_t(g.width) + std::uint32_t(i);
      const std::uint32_t below = a + std::uint32_t(g.width);
      emit(a, below, a + 1);
      emit(a + 1, below, below + 1);
    }
  }
}

// Appends the shortest decimal text that reads back as `value` (std::to_chars).
template <class Number>
void append_digits(std::string& text, Number value) {
  char digits[32];  // a double's shortest form takes at most 24 characters
  const auto [stop, error] = std::to_chars(digits, digits + sizeof digits, value);
  text.append(digits, error == std::errc() ? stop : digits);
}

template <class Number>
void append_number(std::string& text, Number value, char end) {
  append_digits(text, value);
  text.push_back(end);
}

std::vector<unsigned char> encode_obj(const MeshGrid& g) {
  std::string text = "# relief export: " + std::to_string(g.width) + " x " +
                     std::to_string(g.height) + " samples, y up\n";
  text.reserve(mesh_file_bytes(MeshFormat::kObj, g.width, g.height));
  // Each number as the shortest text that reads back the same: x and z as doubles, heights,
  // normals and texture coordinates as floats.
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const std::size_t k = std::size_t(j) * std::size_t(g.width) + std::size_t(i);
      const Vertex v = vertex(g, i, j);
      text += "v ";
      append_number(text, v.x, ' ');
      append_number(text, g.heights[k], ' ');
      append_number(text, v.z, '\n');
      text += "vn ";
      append_number(text, g.normals[3 * k], ' ');
      append_number(text, g.normals[3 * k + 1], ' ');
      append_number(text, g.normals[3 * k + 2], '\n');
      text += "vt ";
      append_number(text, static_cast<float>((double(i) + 0.5) / g.width), ' ');
      // OBJ's v runs up the image (OpenGL's convention): the top row, z0, at v near 1.
      append_number(text, static_cast<float>(1.0 - (double(j) + 0.5) / g.height), '\n');
    }
  }
  for_each_triangle(g, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    // OBJ indices count from 1; each corner's position, texture coordinate and normal share
    // one: "f a/a/a b/b/b c/c/c".
    text += "f";
    const std::uint32_t corners[3] = {a + 1, b + 1, c + 1};
    for (const std::uint32_t corner : corners) {
      text.push_back(' ');
      append_number(text, corner, '/');
      append_number(text, corner, '/');
      append_digits(text, corner);
    }
    text.push_back('\n');
  });
  return {text.begin(), text.end()};
}

void append_bytes(std::vector<unsigned char>& out, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  out.insert(out.end(), p, p + size);
}

void append_u32(std::vector<unsigned char>& out, std::uint32_t v) {  // little-endian
  for (int b = 0; b < 4; ++b) {
    out.push_back(static_cast<unsigned char>(v >> (8 * b)));
  }
}

void append_floats(std::vector<unsigned char>& out, std::span<const float> values) {
  for (const float v : values) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    append_u32(out, bits);
  }
}

// glTF 2.0 binary (the Khronos specification, section 4.4 "GLB File Format Specification"):
// a 12-byte header, a JSON chunk padded with spaces and a BIN chunk padded with zeros, each
// to 4 bytes.
std::vector<unsigned char> encode_glb(const MeshGrid& g) {
  const std::size_t count = std::size_t(g.width) * std::size_t(g.height);
  const double cx = 0.5 * g.rect[0] + 0.5 * g.rect[2], cz = 0.5 * g.rect[1] + 0.5 * g.rect[3];
  std::vector<unsigned char> bin;
  bin.reserve(mesh_file_bytes(MeshFormat::kGlb, g.width, g.height));
  float lo[3] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                 std::numeric_limits<float>::max()};
  float hi[3] = {-lo[0], -lo[1], -lo[2]};
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const Vertex v = vertex(g, i, j);
      const float p[3] = {static_cast<float>(v.x - cx),
                          g.heights[std::size_t(j) * std::size_t(g.width) + std::size_t(i)],
                          static_cast<float>(v.z - cz)};
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], p[c]);
        hi[c] = std::max(hi[c], p[c]);
      }
      append_floats(bin, p);
    }
  }
  const std::size_t normals_at = bin.size();
  append_floats(bin, g.normals.first(3 * count));
  const std::size_t uv_at = bin.size();
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const float uv[2] = {static_cast<float>((double(i) + 0.5) / g.width),
                           static_cast<float>((double(j) + 0.5) / g.height)};
      append_floats(bin, uv);
    }
  }
  const std::size_t indices_at = bin.size();
  std::size_t indices = 0;
  for_each_triangle(g, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    append_u32(bin, a);
    append_u32(bin, b);
    append_u32(bin, c);
    indices += 3;
  });
  const std::size_t bin_bytes = bin.size();  // every part a multiple of 4 bytes
  using nlohmann::json;
  const auto view = [](std::size_t offset, std::size_t length, int target) {
    return json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}};
  };
  const json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "relief export"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({{{"mesh", 0}, {"translation", {cx, 0.0, cz}}}})},
      {"meshes",
       json::array(
           {{{"primitives",
              json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                            {"indices", 3},
                            {"mode", 4}}})}}})},
      {"buffers", json::array({{{"byteLength", bin_bytes}}})},
      {"bufferViews",
       json::array({view(0, normals_at, 34962), view(normals_at, uv_at - normals_at, 34962),
                    view(uv_at, indices_at - uv_at, 34962),
                    view(indices_at, bin_bytes - indices_at, 34963)})},
      {"accessors",
       json::array(
           {{{"bufferView", 0},
             {"componentType", 5126},
             {"count", count},
             {"type", "VEC3"},
             {"min", {lo[0], lo[1], lo[2]}},
             {"max", {hi[0], hi[1], hi[2]}}},
            {{"bufferView", 1}, {"componentType", 5126}, {"count", count}, {"type", "VEC3"}},
            {{"bufferView", 2}, {"componentType", 5126}, {"count", count}, {"type", "VEC2"}},
            {{"bufferView", 3},
             {"componentType", 5125},
             {"count", indices},
             {"type", "SCALAR"}}})}};
  std::string text = gltf.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  std::vector<unsigned char> out;
  out.reserve(12 + 8 + text.size() + 8 + bin_bytes);
  append_u32(out, 0x46546C67);  // "glTF"
  append_u32(out, 2);
  append_u32(out, std::uint32_t(12 + 8 + text.size() + 8 + bin_bytes));
  append_u32(out, std::uint32_t(text.size()));
  append_u32(out, 0x4E4F534A);  // "JSON"
  append_bytes(out, text.data(), text.size());
  append_u32(out, std::uint32_t(bin_bytes));
  append_u32(out, 0x004E4942);  // "BIN\0"
  append_bytes(out, bin.data(), bin_bytes);
  return out;
}

}  // namespace

std::optional<MeshFormat> mesh_format(const std::string& name) {
  if (has_extension(name, ".obj")) {
    return MeshFormat::kObj;
  }
  if (has_extension(name, ".glb")) {
    return MeshFormat::kGlb;
  }
  return std::nullopt;
}

std::uintmax_t mesh_file_bytes(MeshFormat format, int width, int height) {
  const std::uintmax_t samples = std::uintmax_t(width) * std::uintmax_t(height);
  // OBJ: at most 3 + 3 x 25, 4 + 3 x 16 and 4 + 2 x 16 characters of a sample's v, vn and vt
  // lines, and 2 faces of 2 + 3 x 33 (indices below 2^32: 10 digits each). glTF: 32 bytes of
  // attributes and 6 indices of 4 bytes.
  return format == MeshFormat::kObj ? samples * 370 + 256 : samples * 56 + 4096;
}

std::vector<unsigned char> encode_mesh(MeshFormat format, const MeshGrid& grid) {
  return format == MeshFormat::kObj ? encode_obj(grid) : encode_glb(grid);
}

}  // namespace relief
