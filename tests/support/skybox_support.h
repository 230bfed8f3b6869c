// Skybox faces written for tests: six PNGs of one size, each a checkerboard of its own colour
// (so that a face, its orientation and its filter show), and the override that names them.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "image/png_encoder.h"
#include "tests/support/cli_support.h"

namespace relief::test {

// Face f's colour: bright and dark squares of `check` texels, the dark ones 0.6 of the bright.
inline std::array<std::uint8_t, 3> face_colour(int face) {
  static constexpr std::uint8_t kColours[6][3] = {{255, 60, 60},  {60, 255, 60},  {60, 60, 255},
                                                  {255, 255, 60}, {60, 255, 255}, {255, 60, 255}};
  return {kColours[face][0], kColours[face][1], kColours[face][2]};
}

// y counts the file's rows from its first (the image's top); encode_png_rgb8 takes them from
// the bottom.
inline std::vector<unsigned char> checker_face_png(int face, int size, int check) {
  std::vector<std::uint8_t> rgb(3 * std::size_t(size) * size);
  const auto colour = face_colour(face);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const bool dark = ((x / check + y / check) % 2) != 0;
      for (int c = 0; c < 3; ++c) {
        rgb[3 * (std::size_t(size - 1 - y) * size + x) + c] =
            static_cast<std::uint8_t>(dark ? colour[c] * 6 / 10 : colour[c]);
      }
    }
  }
  return encode_png_rgb8(size, size, rgb);
}

// Writes px.png ... nz.png into `dir`; returns their paths in face order.
inline std::array<std::string, 6> write_checker_faces(const std::filesystem::path& dir, int size,
                                                      int check = 8) {
  static constexpr const char* kNames[6] = {"px", "nx", "py", "ny", "pz", "nz"};
  std::array<std::string, 6> paths;
  for (int f = 0; f < 6; ++f) {
    const std::vector<unsigned char> png = checker_face_png(f, size, check);
    paths[std::size_t(f)] =
        write_file(dir / (std::string(kNames[f]) + ".png"), std::string(png.begin(), png.end()));
  }
  return paths;
}

// `sky.skybox={"faces": [...], ...}` for --set or resolve_scene.
inline std::string skybox_override(const std::array<std::string, 6>& faces,
                                   const std::string& extra = "") {
  std::string out = "sky.skybox={\"faces\": [";
  for (std::size_t f = 0; f < faces.size(); ++f) {
    out += (f ? ", \"" : "\"") + faces[f] + "\"";
  }
  return out + "]" + extra + "}";
}

}  // namespace relief::test
