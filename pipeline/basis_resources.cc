#include "pipeline/basis_resources.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <span>
#include <string_view>

#include "core/basis_images.h"
#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_input.h"
#include "core/scene/scene_json.h"
#include "image/png_header.h"
#include "pipeline/builtin_sketches.h"
#include "pipeline/png_checks.h"

namespace relief {

namespace {

constexpr std::string_view kBuiltin = "builtin:";

// One image file of the basis: its JSON path and the path with the file name, for messages.
struct BasisFile {
  std::string name;
  std::string path;   // terrain.basis.images[1].weight
  std::string field;  // terrain.basis.images[1].weight = "w.png"
};

std::vector<BasisFile> basis_files(const BasisSettings& basis) {
  std::vector<BasisFile> files;
  for (std::size_t k = 0; k < basis.images.size(); ++k) {
    const std::string at = "terrain.basis.images[" + std::to_string(k) + "]";
    const BasisImageSettings& image = basis.images[k];
    files.push_back({image.image, at + ".image", ""});
    if (!image.weight_image.empty()) {
      files.push_back({image.weight_image, at + ".weight", ""});
    }
  }
  for (BasisFile& f : files) {
    f.field = f.path + " = \"" + brief_text(f.name) + "\"";
  }
  return files;
}

// Refuses an image from its header: one grey channel of 8 or 16 bits, square, a power of two
// in the lattice's range (halved under mirror), the size of the first image (`side`, 0: any).
void check_basis_header(const std::vector<unsigned char>& bytes, const BasisFile& f, bool mirror,
                        std::uint32_t side) {
  const PngHeader png = png_header_or_throw(bytes, f.field, f.path);
  if (png.colour_type != 0) {
    static constexpr const char* kTypes[] = {"grey",         "?", "RGB", "palette",
                                             "grey + alpha", "?", "RGBA"};
    const char* type = png.colour_type <= 6 ? kTypes[png.colour_type] : "unknown";
    throw SceneError(f.path, "scene: " + f.field + " has colour type " +
                                 std::to_string(png.colour_type) + " (" + type +
                                 "); allowed: a grey PNG with one channel (colour type 0)");
  }
  if (png.bit_depth != 8 && png.bit_depth != 16) {
    throw SceneError(f.path, "scene: " + f.field + " has " + std::to_string(png.bit_depth) +
                                 " bits per channel; allowed: 8 or 16");
  }
  const std::uint32_t lo = limits::kMinLatticeSize;
  const std::uint32_t hi = limits::kMaxLatticeSize / (mirror ? 2 : 1);
  if (png.width != png.height || !std::has_single_bit(png.width) || png.width < lo ||
      png.width > hi) {
    throw SceneError(f.path, "scene: " + f.field + " is " + std::to_string(png.width) + "x" +
                                 std::to_string(png.height) +
                                 " texels; allowed: square, a power of two from " +
                                 std::to_string(lo) + " to " + std::to_string(hi) +
                                 (mirror ? " (mirrored into twice that)" : ""));
  }
  if (side != 0 && png.width != side) {
    throw SceneError(f.path, "scene: " + f.field + " is " + std::to_string(png.width) + "x" +
                                 std::to_string(png.height) +
                                 " texels, but terrain.basis.images[0].image is " +
                                 std::to_string(side) + "x" + std::to_string(side) +
                                 "; allowed: every image and weight image of the same size");
  }
}

std::vector<unsigned char> read_basis_png(const BasisFile& f, bool mirror, std::uint32_t side) {
  if (f.name.rfind(kBuiltin, 0) == 0) {
    const std::span<const unsigned char> png =
        builtin_sketch_png(std::string_view(f.name).substr(kBuiltin.size()));
    if (png.empty() || f.name.rfind("builtin:basis/", 0) != 0) {
      throw SceneError(f.path,
                       "scene: " + f.field +
                           " names no built-in basis image; allowed: builtin:basis/craters, "
                           "builtin:basis/dunes, builtin:basis/ridges, or a PNG file");
    }
    std::vector<unsigned char> bytes(png.begin(), png.end());
    check_basis_header(bytes, f, mirror, side);
    return bytes;
  }
  return read_png_file(f.name, f.field, f.path, [&](const std::vector<unsigned char>& header) {
    check_basis_header(header, f, mirror, side);
  });
}

// The grey levels mapped to [0, 1] (exact in double: v / 65535, stb scaling 8-bit values by
// 257).
GreyGrid decode_basis_png(const std::vector<unsigned char>& bytes, const BasisFile& f) {
  const Grey16Image grey = decode_grey16_png(bytes, f.field, f.path);
  GreyGrid image;
  image.side = grey.width;
  image.values.resize(grey.levels.size());
  for (std::size_t k = 0; k < image.values.size(); ++k) {
    image.values[k] = double(grey.levels[k]) / 65535.0;
  }
  return image;
}

// Every file of the basis decoded, in basis_files order, the first one's side enforced.
std::vector<GreyGrid> decode_basis_files(const BasisSettings& basis,
                                         const std::vector<BasisFile>& files) {
  const bool mirror = basis.wrap == BasisWrap::kMirror;
  std::vector<GreyGrid> grids;
  std::uint32_t side = 0;
  for (const BasisFile& f : files) {
    grids.push_back(decode_basis_png(read_basis_png(f, mirror, side), f));
    side = std::uint32_t(grids.front().side);
  }
  return grids;
}

std::string measure_text(double v, int digits = 3) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

}  // namespace

std::optional<NoiseLattice> load_basis_grid(const Scene& scene, std::vector<std::string>* notes) {
  if (!scene.terrain.basis) {
    return std::nullopt;
  }
  const BasisSettings& basis = *scene.terrain.basis;
  const bool mirror = basis.wrap == BasisWrap::kMirror;
  const std::vector<BasisFile> files = basis_files(basis);
  std::vector<GreyGrid> grids = decode_basis_files(basis, files);
  const int source_side = grids.front().side;
  const int side = mirror ? 2 * source_side : source_side;
  if (side * basis.upsample > limits::kMaxLatticeSize) {
    throw SceneError(
        "terrain.basis.upsample",
        "scene: terrain.basis.upsample = " + std::to_string(basis.upsample) + " refines the " +
            std::to_string(side) + "-texel grid to " + std::to_string(side * basis.upsample) +
            " texels a side, more than " + std::to_string(limits::kMaxLatticeSize) +
            "; allowed terrain.basis.upsample <= " +
            std::to_string(std::max(1, limits::kMaxLatticeSize / side)) + " for this grid");
  }
  std::vector<BasisTerm> terms;
  std::size_t at = 0;
  for (std::size_t k = 0; k < basis.images.size(); ++k) {
    const BasisImageSettings& settings = basis.images[k];
    const std::string path = "terrain.basis.images[" + std::to_string(k) + "]";
    GreyGrid& image = grids[at];
    if (!mirror && notes != nullptr) {
      const double seam = seam_measure(image);
      if (seam > limits::kMaxBasisSeam) {
        notes->push_back(files[at].field + " does not tile: its seam measure is " +
                         measure_text(seam) +
                         " (steps across the wrap against steps inside, RMS; " +
                         measure_text(limits::kMaxBasisSeam) +
                         " at most for an image that tiles); set terrain.basis.wrap = \"mirror\", "
                         "or hide the seam with terrain.r and terrain.warp (§3)");
      }
    }
    if (mirror) {
      image = mirror_grid(image);
    }
    for (const auto& [sigma, name] :
         {std::pair{settings.low_pass, ".low_pass"}, std::pair{settings.high_pass, ".high_pass"}}) {
      if (sigma > side / 2.0) {
        throw SceneError(path + name, "scene: " + path + name + " = " + measure_text(sigma) +
                                          " texels is more than half the grid's side " +
                                          std::to_string(side) + "; allowed 0 <= " + path + name +
                                          " <= " + std::to_string(side / 2));
      }
    }
    filter_basis_image(image, settings, files[at].path);
    BasisTerm term{&image, nullptr, settings.weight};
    ++at;
    if (!settings.weight_image.empty()) {
      GreyGrid& weight = grids[at++];
      if (mirror) {
        weight = mirror_grid(weight);
      }
      term.weight_image = &weight;
    }
    terms.push_back(term);
  }
  if (notes != nullptr && scene.terrain.horizontal_scale != TerrainSettings{}.horizontal_scale) {
    // Stage 3's P is the composed grid's side after mirroring and refinement (stage3_terrain,
    // core/basis_images.h), and its octave-0 cell tile_size / P.
    const int composed_side = side * basis.upsample;
    notes->push_back(
        "terrain.horizontal_scale = " + measure_text(scene.terrain.horizontal_scale, 9) +
        " is not used with terrain.basis: the octave-0 cell is "
        "terrain.basis.tile_size / P = " +
        measure_text(basis.tile_size, 9) + " / " + std::to_string(composed_side) + " = " +
        measure_text(basis.tile_size / double(composed_side), 9) +
        " world units, P the composed grid's side (" + std::to_string(source_side) +
        "-texel images" + (mirror ? ", mirrored" : "") +
        (basis.upsample > 1 ? ", refined " + std::to_string(basis.upsample) + " times"
                            : std::string()) +
        ")");
  }
  return compose_basis(terms, source_side, basis.upsample);
}

std::vector<double> basis_seam_measures(const Scene& scene) {
  std::vector<double> measures;
  if (!scene.terrain.basis) {
    return measures;
  }
  const std::vector<BasisFile> files = basis_files(*scene.terrain.basis);
  const std::vector<GreyGrid> grids = decode_basis_files(*scene.terrain.basis, files);
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (files[k].path.ends_with(".image")) {
      measures.push_back(seam_measure(grids[k]));
    }
  }
  return measures;
}

std::uintmax_t basis_memory_bytes(const Scene& scene) {
  if (!scene.terrain.basis) {
    return 0;
  }
  const bool mirror = scene.terrain.basis->wrap == BasisWrap::kMirror;
  std::uintmax_t files_bytes = 0, side = 0, count = 0;
  for (const BasisFile& f : basis_files(*scene.terrain.basis)) {
    const PngPeek peek = peek_png(f.name);
    const std::optional<PngHeader>& png = peek.header;
    files_bytes += peek.file_bytes;
    if (!png || png->width > std::uint32_t(limits::kMaxLatticeSize)) {
      return 0;
    }
    side = std::max<std::uintmax_t>(side, png->width);
    ++count;
  }
  const std::uintmax_t texels = side * side;
  const std::uintmax_t grid = (mirror ? 4 : 1) * texels;
  const std::uintmax_t factor = std::uintmax_t(scene.terrain.basis->upsample);
  const std::uintmax_t fine = grid * factor * factor;
  // Per file: its bytes, stb's 16-bit decode (2 a texel) and the doubles (8 a grid texel);
  // one filter at a time: the FFT's complex grid (16) and the blurred copy (8); the composed
  // doubles, their refinement along x and then y (8 each), and the float grid.
  return files_bytes + count * (2 * texels + 8 * grid) + grid * (16 + 8) +
         8 * (grid + grid * factor + fine) + 4 * fine;
}

}  // namespace relief
