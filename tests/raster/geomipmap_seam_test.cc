// The seam test of GeoMipMapping (core/heightfield/geomipmap.h): over a sweep of cameras, the
// stitched mesh of the tiles the quadtree keeps, at the levels de Boer's rule picks, drawn by
// Relief's rasteriser (GL's rules), leaves no pixel uncovered whose ray must meet the terrain.
//
// Which pixels must be covered, independently of the mesh: the camera is above the field's
// highest vertex and over the field, so a ray that reaches the plane of its lowest vertex
// inside the field's extent crosses the surface on the way (the surface is continuous over the
// extent and lies between the two planes). The same tiles each stitched alone (no neighbour
// known: T-junctions wherever levels differ) must leave holes, or the test could not see one.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <catch2/catch.hpp>

#include "core/camera.h"
#include "core/heightfield/geomipmap.h"
#include "raster/rasterize.h"

namespace relief::geomipmap {
namespace {

constexpr int kTiles = 16, kTileCells = 16, kSide = kTiles * kTileCells + 1;
constexpr double kHalfExtent = 2000.0;

// Ridges at several scales and a little noise: levels differ between neighbours everywhere.
std::vector<float> seam_field() {
  std::vector<float> h(static_cast<std::size_t>(kSide) * kSide);
  for (int r = 0; r < kSide; ++r) {
    for (int c = 0; c < kSide; ++c) {
      std::uint64_t x = static_cast<std::uint64_t>(r) * 7919u + static_cast<std::uint64_t>(c);
      x = (x ^ (x >> 31)) * 0xbf58476d1ce4e5b9ull;
      x ^= x >> 29;
      const double noise = static_cast<double>(x % 4096) / 4096.0 - 0.5;
      h[static_cast<std::size_t>(r) * kSide + c] =
          static_cast<float>(120.0 * std::sin(0.031 * c) * std::cos(0.027 * r) +
                             35.0 * std::sin(0.19 * c + 0.11 * r) + 4.0 * noise);
    }
  }
  return h;
}

struct Frame {
  std::uint64_t must_cover = 0, holes = 0;
  raster::VisibilityBuffer visibility;
};

Frame draw(const FieldLattice& lattice, const Mesh& mesh, const CameraFrame& cam, int width,
           int height, double lowest) {
  std::vector<float> x(mesh.vertex_column.size()), y(x.size()), z(x.size()), w(x.size());
  for (std::size_t v = 0; v < x.size(); ++v) {
    const int c = mesh.vertex_column[v], r = mesh.vertex_row[v];
    const glm::dvec2 p = lattice.position(c, r);
    const glm::dvec3 d =
        glm::dvec3(p.x, lattice.heights[static_cast<std::size_t>(r) * lattice.columns + c], p.y) -
        cam.position;
    // Reverse-Z with an infinite far plane: clip (x / tan_x, y / tan_y, near, depth).
    x[v] = static_cast<float>(glm::dot(d, cam.right) / cam.tan_half_fov_x);
    y[v] = static_cast<float>(glm::dot(d, cam.up) / cam.tan_half_fov_y);
    z[v] = static_cast<float>(cam.near);
    w[v] = static_cast<float>(glm::dot(d, cam.forward));
  }
  raster::RasterState state;
  state.width = width;
  state.height = height;
  state.viewport = {0.0, 0.0, double(width), double(height)};
  Frame frame;
  raster::VisibilityBuffer& visibility = frame.visibility;
  raster::rasterize(state, raster::ClipVertices{x, y, z, w}, raster::IndexedTriangles{mesh.indices},
                    visibility);
  for (int py = 0; py < height; ++py) {
    for (int px = 0; px < width; ++px) {
      const double ndc_x = (px + 0.5) / width * 2 - 1, ndc_y = (py + 0.5) / height * 2 - 1;
      const glm::dvec3 ray = cam.forward + ndc_x * cam.tan_half_fov_x * cam.right +
                             ndc_y * cam.tan_half_fov_y * cam.up;
      if (!(ray.y < 0))
        continue;
      const double t = (lowest - cam.position.y) / ray.y;  // ray.y < 0: the plane below
      const glm::dvec3 hit = cam.position + t * ray;
      const double margin = 1e-6 * kHalfExtent;
      if (std::abs(hit.x) >= kHalfExtent - margin || std::abs(hit.z) >= kHalfExtent - margin) {
        continue;
      }
      ++frame.must_cover;
      if (visibility.primitive[visibility.index(px, py)] == raster::kNoPrimitive)
        ++frame.holes;
    }
  }
  return frame;
}

// Each drawn tile stitched alone, its lattice points merged: T-junctions where levels differ.
Mesh unstitched_mesh(const GeoMipMap& map, const Selection& selection) {
  Mesh all;
  std::unordered_map<std::uint64_t, std::uint32_t> ids;
  for (std::size_t t = 0; t < selection.level.size(); ++t) {
    if (!selection.drawn[t])
      continue;
    Selection alone;
    alone.level.assign(selection.level.size(), 0);  // neighbours finest: its own spacing
    alone.drawn.assign(selection.level.size(), 0);
    alone.level[t] = selection.level[t];
    alone.drawn[t] = 1;
    const Mesh tile = stitched_mesh(map, alone);
    for (const std::uint32_t i : tile.indices) {
      const std::uint64_t key = (static_cast<std::uint64_t>(tile.vertex_row[i]) << 32) |
                                static_cast<std::uint32_t>(tile.vertex_column[i]);
      const auto [it, inserted] = ids.try_emplace(key, static_cast<std::uint32_t>(ids.size()));
      if (inserted) {
        all.vertex_column.push_back(tile.vertex_column[i]);
        all.vertex_row.push_back(tile.vertex_row[i]);
      }
      all.indices.push_back(it->second);
    }
  }
  return all;
}

// Which tile and which of its triangles drew each pixel (-1: none).
std::vector<std::int64_t> tile_triangles(const Mesh& mesh, const raster::VisibilityBuffer& v) {
  std::vector<std::int64_t> out(v.primitive.size(), -1);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const std::uint32_t id = v.primitive[k];
    if (id == raster::kNoPrimitive)
      continue;
    const auto next =
        std::upper_bound(mesh.tile_first_triangle.begin(), mesh.tile_first_triangle.end(), id);
    const auto slot = static_cast<std::size_t>(next - mesh.tile_first_triangle.begin()) - 1;
    out[k] =
        (static_cast<std::int64_t>(mesh.tiles[slot]) << 32) | (id - mesh.tile_first_triangle[slot]);
  }
  return out;
}

// The seam tests' view of a camera: 320 x 240 pixels, the near and far planes set.
View view_of(CameraSettings settings, double pixel_error) {
  ViewportSettings viewport;
  viewport.width = 320;
  viewport.height = 240;
  settings.near = 0.5;
  settings.far = 60000.0;
  View view;
  view.camera = make_camera_frame(settings, viewport);
  view.width = viewport.width;
  view.height = viewport.height;
  view.pixel_error = pixel_error;
  return view;
}

struct Drawn {
  Selection selection;
  Mesh mesh;
  Frame frame;
};

// The view drawn with occlusion culling, and checked against the same view without it: the
// same levels, the same depth and the same tile's same triangle in every pixel.
Drawn draw_checking_occlusion(const FieldLattice& lattice, const GeoMipMap& map, View view) {
  const double lowest = map.quadtree.back()[0].low;
  Drawn d;
  d.selection = select_levels(map, view);
  d.mesh = stitched_mesh(map, d.selection);
  d.frame = draw(lattice, d.mesh, view.camera, view.width, view.height, lowest);
  view.occlusion = false;
  const Selection frustum_only = select_levels(map, view);
  REQUIRE(d.selection.level == frustum_only.level);
  const Mesh all = stitched_mesh(map, frustum_only);
  const Frame reference = draw(lattice, all, view.camera, view.width, view.height, lowest);
  CHECK(d.frame.visibility.depth == reference.visibility.depth);
  CHECK(tile_triangles(d.mesh, d.frame.visibility) == tile_triangles(all, reference.visibility));
  return d;
}

TEST_CASE("geomipmapSeamsShowNoBackgroundOverACameraSweep", "[geomipmap][raster]") {
  const std::vector<float> heights = seam_field();
  FieldLattice lattice;
  lattice.columns = lattice.rows = kSide;
  lattice.extent = {-kHalfExtent, -kHalfExtent, kHalfExtent, kHalfExtent};
  lattice.heights = heights;
  const GeoMipMap map = build_geomipmap(lattice, kTileCells);
  const double lowest = map.quadtree.back()[0].low, highest = map.quadtree.back()[0].high;
  std::uint64_t checked = 0, unstitched_holes = 0, coarse_tiles = 0, culled = 0, occluded = 0;
  for (int view_index = 0; view_index < 40; ++view_index) {
    CameraSettings settings;
    const double a = 0.7 * view_index;
    settings.position = {1500.0 * std::sin(a), highest + 20.0 + 37.0 * (view_index % 9),
                         1500.0 * std::cos(1.3 * a)};
    settings.yaw_deg = 23.0 * view_index;
    settings.pitch_deg = -25.0 - 2.0 * (view_index % 30);
    if (view_index >= 32) {  // low, grazing views: the ground hides ground
      settings.position[1] = highest + 5.0 + 10.0 * (view_index - 32);
      settings.pitch_deg = -4.0 - (view_index - 32);
    }
    const View view = view_of(settings, 0.5 + (view_index % 4) * 1.5);
    INFO("view " << view_index);
    const Drawn d = draw_checking_occlusion(lattice, map, view);
    for (int l = 1; l < map.levels; ++l)
      coarse_tiles += d.selection.counts.tiles_per_level[l];
    culled += d.selection.counts.tiles_culled;
    occluded += d.selection.counts.tiles_occluded;
    INFO(d.frame.holes << " of " << d.frame.must_cover
                       << " pixels that must show the terrain show the background");
    CHECK(d.frame.holes == 0);
    checked += d.frame.must_cover;
    unstitched_holes += draw(lattice, unstitched_mesh(map, d.selection), view.camera, view.width,
                             view.height, lowest)
                            .holes;
  }
  CHECK(checked > 40u * 320u * 240u / 3);  // most pixels are checked
  CHECK(coarse_tiles > 0);                 // levels differ, so seams exist
  CHECK(culled > 0);                       // the quadtree culls
  CHECK(occluded > 0);                     // and so does occlusion
  CHECK(unstitched_holes > 0);             // without stitching the test sees cracks
}

// A plateau 200 m high across the middle of the field, lowland before and behind it: from just
// above the plateau, looking across it, the lowland behind is hidden, and occlusion culling
// must remove those tiles without changing a pixel.
TEST_CASE("occlusionCullingHidesTheLowlandBehindAPlateauAndChangesNoPixel", "[geomipmap][raster]") {
  std::vector<float> heights(static_cast<std::size_t>(kSide) * kSide);
  for (int r = 0; r < kSide; ++r) {
    for (int c = 0; c < kSide; ++c) {
      const bool plateau = r >= 64 && r <= 192;
      heights[static_cast<std::size_t>(r) * kSide + c] =
          static_cast<float>((plateau ? 200.0 : 0.0) + 3.0 * std::sin(0.21 * c + 0.17 * r));
    }
  }
  FieldLattice lattice;
  lattice.columns = lattice.rows = kSide;
  lattice.extent = {-kHalfExtent, -kHalfExtent, kHalfExtent, kHalfExtent};
  lattice.heights = heights;
  const GeoMipMap map = build_geomipmap(lattice, kTileCells);
  std::uint64_t occluded = 0;
  for (int view_index = 0; view_index < 4; ++view_index) {
    CameraSettings settings;
    settings.position = {-600.0 + 240.0 * view_index, 215.0 + 5.0 * view_index, 900.0};
    settings.yaw_deg = -20.0 + 8.0 * view_index;  // across the plateau, towards -z
    settings.pitch_deg = -1.0 - 0.5 * view_index;
    INFO("view " << view_index);
    const Drawn d = draw_checking_occlusion(lattice, map, view_of(settings, 1.0));
    CHECK(d.selection.counts.tiles_occluded > 0);  // every view hides some lowland
    occluded += d.selection.counts.tiles_occluded;
  }
  CHECK(occluded > 0);
}

}  // namespace
}  // namespace relief::geomipmap
