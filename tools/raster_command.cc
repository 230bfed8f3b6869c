#include <cstring>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/counter_hash.h"
#include "core/scene/json_input.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "pipeline/job_memory.h"
#include "pipeline/tile_pass.h"
#include "raster/rasterize.h"
#include "raster/resolve.h"
#include "tools/atomic_file.h"
#include "tools/cli.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/distinct_paths.h"
#include "tools/soup.h"

namespace relief {

namespace {

raster::CullMode cull_mode(const std::string& name) {
  return name == "back"    ? raster::CullMode::kBack
         : name == "front" ? raster::CullMode::kFront
                           : raster::CullMode::kNone;
}

raster::DepthTest depth_test(const std::string& name) {
  if (name == "gequal")
    return raster::DepthTest::kGreaterEqual;
  if (name == "less")
    return raster::DepthTest::kLess;
  if (name == "lequal")
    return raster::DepthTest::kLessEqual;
  if (name == "equal")
    return raster::DepthTest::kEqual;
  if (name == "always")
    return raster::DepthTest::kAlways;
  if (name == "never")
    return raster::DepthTest::kNever;
  return raster::DepthTest::kGreater;
}

std::span<const unsigned char> bytes_of(const std::string& text) {
  return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

}  // namespace

int run_raster_command(const RasterOptions& options, std::ostream& out) {
  // An output named like the soup (relief raster s.json --out s) would replace it.
  std::vector<CommandPath> paths = {{"FILE", options.soup, false}};
  for (const char* suffix :
       {".primitive.bin", ".depth.pfm", ".barycentric.pfm", ".coverage.png", ".json"}) {
    paths.push_back({"--out's " + std::string(suffix + 1), options.prefix + suffix});
  }
  if (const std::optional<std::string> conflict = same_file_conflict(paths)) {
    throw SoupError(*conflict);
  }
  const TriangleSoup soup = read_triangle_soup(options.soup, [&](std::uintmax_t file_bytes) {
    check_memory(estimate_soup_memory(file_bytes), options.budget, "reading this soup",
                 "Split the soup");
  });
  MemoryEstimate estimate = estimate_raster_memory(soup.triangle_count(), soup.width, soup.height);
  const char* advice = "Lower the framebuffer size or the number of triangles";
  check_memory(estimate, options.budget, "rasterising this soup", advice);
  const raster::RasterLimits limits{memory_left(estimate, options.budget)};
  raster::RasterState state;
  state.width = soup.width;
  state.height = soup.height;
  state.viewport = {0.0, 0.0, double(soup.width), double(soup.height)};
  if (!options.viewport.empty() && !soup.clip_coordinates) {
    throw SoupError("--viewport applies to clip-coordinate soups, and " + brief_text(options.soup) +
                    " has window coordinates (already in pixels)");
  }
  if (!options.viewport.empty()) {
    state.viewport = {options.viewport[0], options.viewport[1], options.viewport[2],
                      options.viewport[3]};
  }
  state.cull = cull_mode(options.cull);
  state.front_face = options.front_face == "cw" ? raster::FrontFace::kClockwise
                                                : raster::FrontFace::kCounterClockwise;
  state.depth_test = depth_test(options.depth_test);
  state.depth_clear = state.depth_test == raster::DepthTest::kLess ||
                              state.depth_test == raster::DepthTest::kLessEqual
                          ? 1.0f
                          : 0.0f;

  const raster::IndexedTriangles triangles{soup.indices};
  const raster::TileRasterizer tiles = options.simd ? &rasterize_tile_simd : nullptr;
  raster::VisibilityBuffer visibility;
  raster::RasterStats stats;
  raster::VertexPositions positions;
  if (soup.clip_coordinates) {
    const raster::ClipVertices clip{soup.x, soup.y, soup.z, soup.w};
    stats = raster::rasterize(state, clip, triangles, visibility, limits, tiles);
    positions = raster::VertexPositions::from_clip(clip, state.viewport);
  } else {
    const raster::WindowVertices window{soup.x, soup.y, soup.z};
    stats = raster::rasterize(state, window, triangles, visibility, limits, tiles);
    positions = raster::VertexPositions::from_window(window);
  }
  if (stats.bins_refused) {
    estimate.add("rasteriser bins", stats.bin_bytes);
    check_memory(estimate, options.budget, "rasterising this soup", advice);
  }
  raster::ResolvedFrame resolved;
  raster::resolve(visibility, positions, triangles, {}, 0, resolved);

  OutputDirectory directory(std::filesystem::path(options.prefix).parent_path());
  const std::size_t pixels = visibility.primitive.size();
  std::vector<unsigned char> ids(pixels * 4);
  std::memcpy(ids.data(), visibility.primitive.data(), ids.size());  // little-endian host
  std::vector<float> barycentric(pixels * 3);
  std::vector<std::uint8_t> coverage(pixels * 3, 0);
  std::size_t covered = 0;
  for (std::size_t k = 0; k < pixels; ++k) {
    barycentric[3 * k] = resolved.b0[k];
    barycentric[3 * k + 1] = resolved.b1[k];
    barycentric[3 * k + 2] = resolved.b2[k];
    if (visibility.primitive[k] != raster::kNoPrimitive) {
      ++covered;
      const std::uint64_t h = mix64(visibility.primitive[k] + kGoldenGamma);
      coverage[3 * k] = static_cast<std::uint8_t>(64 + (h & 0xbf));
      coverage[3 * k + 1] = static_cast<std::uint8_t>(64 + ((h >> 8) & 0xbf));
      coverage[3 * k + 2] = static_cast<std::uint8_t>(64 + ((h >> 16) & 0xbf));
    }
  }
  const std::string p = options.prefix;
  OutputSet files;  // the five files appear together or not at all
  files.add(p + ".primitive.bin", ids);
  files.add(p + ".depth.pfm", encode_pfm(soup.width, soup.height, 1, visibility.depth,
                                         static_cast<std::size_t>(soup.width)));
  files.add(p + ".barycentric.pfm", encode_pfm(soup.width, soup.height, 3, barycentric,
                                               static_cast<std::size_t>(soup.width) * 3));
  // No scene made a soup: the picture carries the software alone (image_metadata.h).
  files.add(p + ".coverage.png",
            encode_png_rgb(soup.width, soup.height, coverage, software_metadata()));
  const nlohmann::json manifest = {
      {"width", soup.width},
      {"height", soup.height},
      {"triangles", soup.triangle_count()},
      {"pieces_after_clipping_and_culling", stats.setup},
      {"covered_pixels", covered},
      {"files",
       {{"primitive", p + ".primitive.bin: uint32 little-endian per pixel, rows bottom to top, "
                          "4294967295 where uncovered"},
        {"depth", p + ".depth.pfm: window depth of the winning triangle (the clear value where "
                      "uncovered)"},
        {"barycentric", p + ".barycentric.pfm: perspective-correct barycentrics of the winning "
                            "triangle, 0 where uncovered"},
        {"coverage", p + ".coverage.png: a colour per primitive, black where uncovered"}}}};
  files.add(
      p + ".json",
      bytes_of(manifest.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n"));
  files.commit();
  directory.keep();
  out << soup.triangle_count() << " triangles (" << stats.setup << " pieces after clipping and "
      << "culling), " << covered << " of " << pixels << " pixels covered\nwrote " << p
      << ".{primitive.bin,depth.pfm,barycentric.pfm,coverage.png,json}\n";
  return kExitOk;
}

CLI::App* add_raster_command(CLI::App& app, RasterOptions& raster_options) {
  CLI::App* raster_cmd = app.add_subcommand(
      "raster",
      "Rasterise a triangle soup (docs/rasteriser.md, 'Triangle soups') and write the primitive "
      "id, depth and barycentric buffers, for comparison with a GPU.");
  raster_cmd->add_option("FILE", raster_options.soup, "Triangle soup text file")->required();
  raster_cmd
      ->add_option("--out", raster_options.prefix,
                   "Output prefix: writes PREFIX.primitive.bin, PREFIX.depth.pfm, "
                   "PREFIX.barycentric.pfm, PREFIX.coverage.png, PREFIX.json")
      ->required();
  raster_cmd->add_option("--cull", raster_options.cull, "Face culling: none (default), back, front")
      ->check(CLI::IsMember({"none", "back", "front"}));
  raster_cmd
      ->add_option("--front-face", raster_options.front_face,
                   "Front-facing winding in GL window coordinates: ccw (default) or cw")
      ->check(CLI::IsMember({"ccw", "cw"}));
  raster_cmd
      ->add_option("--depth-test", raster_options.depth_test,
                   "Depth test: greater (default, reverse-Z; depth cleared to 0), gequal, "
                   "less, lequal (cleared to 1), equal, always, never")
      ->check(CLI::IsMember({"greater", "gequal", "less", "lequal", "equal", "always", "never"}));
  raster_cmd
      ->add_option("--viewport", raster_options.viewport,
                   "glViewport X Y WIDTH HEIGHT for clip-coordinate soups (default: the "
                   "framebuffer); may exceed the framebuffer")
      ->expected(4)
      ->check(kFiniteViewportValue);
  return raster_cmd;
}

}  // namespace relief
