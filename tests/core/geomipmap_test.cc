// GeoMipMapping's tiles, quadtree culling, levels and stitched mesh (core/heightfield/geomipmap.h),
// each against an independent check: the mesh's edges counted (watertight: no crack, no
// T-junction), its area summed, culled boxes tested point by point against the camera's own
// frustum, and the levels against de Boer's rule recomputed.
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "core/camera.h"
#include "core/heightfield/geomipmap.h"

namespace relief::geomipmap {
namespace {

// A rough field: hashed heights (a 64-bit mix of the index) plus a slope and waves of `waves`
// metres (their curvature makes each level's error about four times the one below).
std::vector<float> rough_heights(int columns, int rows, double amplitude, double waves = 0) {
  std::vector<float> h(static_cast<std::size_t>(columns) * rows);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      std::uint64_t x = static_cast<std::uint64_t>(r) * 1000003u + static_cast<std::uint64_t>(c);
      x ^= x >> 33;
      x *= 0xff51afd7ed558ccdull;
      x ^= x >> 33;
      const double noise = static_cast<double>(x % 10007) / 10007.0 - 0.5;
      h[static_cast<std::size_t>(r) * columns + c] = static_cast<float>(
          amplitude * noise + 3.0 * c - 2.0 * r + waves * std::sin(0.35 * c) * std::cos(0.27 * r));
    }
  }
  return h;
}

struct Field {
  std::vector<float> heights;
  FieldLattice lattice;
};

Field make_field(int tiles_x, int tiles_z, int tile_cells, double amplitude, double waves = 0) {
  Field f;
  const int columns = tiles_x * tile_cells + 1, rows = tiles_z * tile_cells + 1;
  f.heights = rough_heights(columns, rows, amplitude, waves);
  f.lattice.columns = columns;
  f.lattice.rows = rows;
  f.lattice.extent = {-1000.0, -800.0, 1000.0, 800.0};
  f.lattice.heights = f.heights;
  return f;
}

// Every undirected edge of the mesh and how many triangles use it; every triangle's doubled
// signed area in lattice steps (positive: counter-clockwise seen from +y).
void require_watertight(const GeoMipMap& map, const Selection& selection, const Mesh& mesh) {
  std::map<std::pair<std::uint64_t, std::uint64_t>, int> edges;
  const auto key = [&](std::uint32_t i) {
    return (static_cast<std::uint64_t>(mesh.vertex_row[i]) << 32) |
           static_cast<std::uint32_t>(mesh.vertex_column[i]);
  };
  long long doubled_area = 0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t v[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const long long ax = mesh.vertex_column[v[0]], az = mesh.vertex_row[v[0]];
    const long long cross_y = (mesh.vertex_row[v[1]] - az) * (mesh.vertex_column[v[2]] - ax) -
                              (mesh.vertex_column[v[1]] - ax) * (mesh.vertex_row[v[2]] - az);
    REQUIRE(cross_y > 0);  // counter-clockwise from above, never degenerate
    doubled_area += cross_y;
    for (int e = 0; e < 3; ++e) {
      std::uint64_t a = key(v[e]), b = key(v[(e + 1) % 3]);
      if (b < a)
        std::swap(a, b);
      ++edges[{a, b}];
    }
  }
  std::uint64_t drawn = 0;
  for (const std::uint8_t d : selection.drawn)
    drawn += d;
  const long long T = map.tile_cells;
  CHECK(doubled_area == static_cast<long long>(drawn) * 2 * T * T);  // covered once, no overlap
  const auto drawn_tile = [&](long long tx, long long tz) {
    return tx >= 0 && tz >= 0 && tx < map.tiles_x && tz < map.tiles_z &&
           selection.drawn[static_cast<std::size_t>(tz * map.tiles_x + tx)] != 0;
  };
  for (const auto& [edge, count] : edges) {
    INFO("edge (" << (edge.first & 0xffffffffu) << ", " << (edge.first >> 32) << ") - ("
                  << (edge.second & 0xffffffffu) << ", " << (edge.second >> 32) << ")");
    REQUIRE(count <= 2);
    if (count == 2)
      continue;
    // Used once: it must lie on a tile boundary with a drawn tile on one side only.
    const long long c0 = edge.first & 0xffffffffu, r0 = edge.first >> 32;
    const long long c1 = edge.second & 0xffffffffu, r1 = edge.second >> 32;
    if (r0 == r1) {
      REQUIRE(r0 % T == 0);
      const long long tx = std::min(c0, c1) / T;
      REQUIRE(drawn_tile(tx, r0 / T - 1) != drawn_tile(tx, r0 / T));
    } else {
      REQUIRE(c0 == c1);
      REQUIRE(c0 % T == 0);
      const long long tz = std::min(r0, r1) / T;
      REQUIRE(drawn_tile(c0 / T - 1, tz) != drawn_tile(c0 / T, tz));
    }
  }
}

TEST_CASE("geomipmapErrorsVanishOnAPlaneAndTheRootHoldsTheFieldsRange", "[geomipmap]") {
  Field rough = make_field(3, 2, 16, 40.0);
  const GeoMipMap map = build_geomipmap(rough.lattice, 16);
  REQUIRE(map.levels == 5);
  REQUIRE(map.quadtree.back().size() == 1);
  for (const TileBounds& t : map.tiles) {
    CHECK(t.error[1] > 0.0);  // the bound itself: stitchedMeshesStayWithinTheirLevelsErrors
  }
  // A plane is reproduced exactly by every level's triangles.
  Field plane = make_field(2, 2, 8, 0.0);
  const GeoMipMap flat = build_geomipmap(plane.lattice, 8);
  for (const TileBounds& t : flat.tiles) {
    for (const double e : t.error)
      CHECK(e <= 1e-9);
  }
  // The quadtree's root holds the whole field's range.
  const auto [lo, hi] = std::minmax_element(rough.heights.begin(), rough.heights.end());
  CHECK(map.quadtree.back()[0].low == *lo);
  CHECK(map.quadtree.back()[0].high == *hi);
}

TEST_CASE("geomipmapRefusesLatticesThatDoNotFitItsTiles", "[geomipmap]") {
  Field f = make_field(2, 2, 8, 1.0);
  CHECK_THROWS_WITH(build_geomipmap(f.lattice, 12), Catch::Contains("a power of two"));
  CHECK_THROWS_WITH(build_geomipmap(f.lattice, 512), Catch::Contains("[2, 256]"));
  CHECK_THROWS_WITH(build_geomipmap(f.lattice, 32), Catch::Contains("allowed k 32 + 1"));
  f.heights[5] = std::nanf("");
  CHECK_THROWS_WITH(build_geomipmap(f.lattice, 8), Catch::Contains("column 5, row 0"));
  f.heights[5] = 0;
  f.lattice.extent = {1, 0, 0, 1};
  CHECK_THROWS_WITH(build_geomipmap(f.lattice, 8), Catch::Contains("x1 > x0"));
}

// Each drawn triangle against its tile's error at its level: every lattice point inside it
// lies within error[level] of its plane (recomputed here in double), whatever the neighbours.
void require_within_errors(const GeoMipMap& map, const Field& f, const Selection& selection,
                           const Mesh& mesh) {
  std::uint64_t points = 0, beyond = 0;
  for (std::size_t k = 0; k + 1 < mesh.tile_first_triangle.size(); ++k) {
    const std::uint32_t tile = mesh.tiles[k];
    const double bound = map.tiles[tile].error[static_cast<std::size_t>(selection.level[tile])];
    for (std::uint32_t t = mesh.tile_first_triangle[k]; t < mesh.tile_first_triangle[k + 1]; ++t) {
      long long c[3], r[3];
      double h[3];
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t v = mesh.indices[3 * t + i];
        c[i] = mesh.vertex_column[v];
        r[i] = mesh.vertex_row[v];
        h[i] = f.heights[static_cast<std::size_t>(r[i] * f.lattice.columns + c[i])];
      }
      const auto side = [&](int i, long long pc, long long pr) {  // >= 0: inside edge i
        const int j = (i + 1) % 3;
        return (r[j] - r[i]) * (pc - c[i]) - (c[j] - c[i]) * (pr - r[i]);
      };
      const double area = static_cast<double>(side(0, c[2], r[2]));
      REQUIRE(area > 0);
      for (long long pr = std::min({r[0], r[1], r[2]}); pr <= std::max({r[0], r[1], r[2]}); ++pr) {
        for (long long pc = std::min({c[0], c[1], c[2]}); pc <= std::max({c[0], c[1], c[2]});
             ++pc) {
          const long long w0 = side(1, pc, pr), w1 = side(2, pc, pr), w2 = side(0, pc, pr);
          if (w0 < 0 || w1 < 0 || w2 < 0)
            continue;
          const double plane = (w0 * h[0] + w1 * h[1] + w2 * h[2]) / area;
          const double exact = f.heights[static_cast<std::size_t>(pr * f.lattice.columns + pc)];
          ++points;
          if (!(std::abs(exact - plane) <= bound * (1 + 1e-12) + 1e-9))
            ++beyond;
        }
      }
    }
  }
  CHECK(points > 0);
  CHECK(beyond == 0);  // lattice points farther from their triangle than the level's error
}

TEST_CASE("stitchedGeomipmapMeshesAreWatertightAndWithinTheirLevelsErrors", "[geomipmap]") {
  // Tile sizes from the smallest to the largest, fields of a few tiles.
  const int shapes[][3] = {{5, 4, 16}, {6, 5, 2}, {4, 4, 4}, {3, 3, 32}, {2, 1, 256}};
  for (const auto& [tiles_x, tiles_z, tile_cells] : shapes) {
    const Field f = make_field(tiles_x, tiles_z, tile_cells, 10.0, 30.0);
    const GeoMipMap map = build_geomipmap(f.lattice, tile_cells);
    // Assignments of levels (culled tiles included) from a fixed sequence: neighbours from
    // equal to every level apart.
    for (int trial = 0; trial < 40; ++trial) {
      Selection s;
      s.level.resize(map.tiles.size());
      s.drawn.resize(map.tiles.size());
      for (std::size_t t = 0; t < s.level.size(); ++t) {
        const std::uint64_t x = (t + 1) * 2654435761u + static_cast<std::uint64_t>(trial) * 40503u;
        s.level[t] = static_cast<int>((x >> 7) % static_cast<std::uint64_t>(map.levels));
        s.drawn[t] = (x >> 13) % 6 != 0 ? 1 : 0;  // a sixth culled
      }
      if (trial < 2)
        std::fill(s.drawn.begin(), s.drawn.end(), std::uint8_t{1});
      if (trial == 0)
        std::fill(s.level.begin(), s.level.end(), 0);
      if (trial == 1)
        std::fill(s.level.begin(), s.level.end(), map.levels - 1);
      INFO("T " << tile_cells << ", trial " << trial);
      require_watertight(map, s, stitched_mesh(map, s));  // any levels
      // Neighbours within one level (as select_levels leaves them): lower the coarser.
      for (bool changed = true; changed;) {
        changed = false;
        for (int t = 0; t < static_cast<int>(s.level.size()); ++t) {
          const int tx = t % map.tiles_x, tz = t / map.tiles_x;
          for (const auto& [nx, nz] : {std::pair{tx - 1, tz}, std::pair{tx + 1, tz},
                                       std::pair{tx, tz - 1}, std::pair{tx, tz + 1}}) {
            if (nx < 0 || nz < 0 || nx >= map.tiles_x || nz >= map.tiles_z)
              continue;
            const int n = s.level[static_cast<std::size_t>(nz * map.tiles_x + nx)];
            if (s.level[static_cast<std::size_t>(t)] > n + 1) {
              s.level[static_cast<std::size_t>(t)] = n + 1;
              changed = true;
            }
          }
        }
      }
      const Mesh mesh = stitched_mesh(map, s);
      require_watertight(map, s, mesh);
      require_within_errors(map, f, s, mesh);
      // Each lattice point once.
      std::map<std::pair<int, int>, int> points;
      std::size_t repeated = 0;
      for (std::size_t v = 0; v < mesh.vertex_column.size(); ++v)
        repeated += ++points[{mesh.vertex_column[v], mesh.vertex_row[v]}] > 1 ? 1 : 0;
      CHECK(repeated == 0);
    }
  }
}

TEST_CASE("geomipmapRefusesSelectionsAndViewsItCannotUse", "[geomipmap]") {
  const Field f = make_field(2, 2, 8, 1.0);
  const GeoMipMap map = build_geomipmap(f.lattice, 8);
  Selection s;
  s.level.assign(map.tiles.size(), 0);
  s.drawn.assign(map.tiles.size(), 1);
  s.level[1] = map.levels;
  CHECK_THROWS_WITH(stitched_mesh(map, s), Catch::Contains("selection level 4; allowed [0, 3]"));
  s.level[1] = -1;
  CHECK_THROWS_WITH(stitched_mesh(map, s), Catch::Contains("selection level -1"));
  s.level.pop_back();
  CHECK_THROWS_WITH(stitched_mesh(map, s), Catch::Contains("selection of 3 tiles"));
  View view;
  view.camera = make_camera_frame(CameraSettings{}, ViewportSettings{});
  CHECK_THROWS_WITH(select_levels(map, view), Catch::Contains("positive sizes"));
  view.width = view.height = 64;
  view.occlusion_cell = 0;
  CHECK_THROWS_WITH(select_levels(map, view), Catch::Contains("a cell of 1 ... 4096"));
  view.occlusion_cell = 8;
  view.pixel_error = std::nan("");
  CHECK_THROWS(select_levels(map, view));
  CHECK_THROWS_WITH(select_levels(GeoMipMap{}, view), Catch::Contains("without tiles"));
  view.pixel_error = 1;
  view.camera.near = 0;
  CHECK_THROWS_WITH(select_levels(map, view), Catch::Contains("allowed 0 < near < far"));
  view.camera.near = 0.5;
  view.camera.position.y = std::nan("");
  CHECK_THROWS_WITH(select_levels(map, view), Catch::Contains("position: not finite"));
  view.camera.position.y = HUGE_VAL;
  CHECK_THROWS_WITH(select_levels(map, view), Catch::Contains("position: not finite"));
  Field wide = make_field(1, 1, 8, 1.0);
  wide.lattice.extent = {-1.5e308, -1.0, 1.5e308, 1.0};
  CHECK_THROWS_WITH(build_geomipmap(wide.lattice, 8), Catch::Contains("finite spans"));
}

// Whether a world point is inside the camera's view frustum, from the camera's own vectors
// (core/camera.h), not from the planes the selection used.
bool in_view(const CameraFrame& cam, glm::dvec3 p) {
  const glm::dvec3 d = p - cam.position;
  const double depth = glm::dot(d, cam.forward);
  if (depth < cam.near || depth > cam.far)
    return false;
  return std::abs(glm::dot(d, cam.right)) <= cam.tan_half_fov_x * depth &&
         std::abs(glm::dot(d, cam.up)) <= cam.tan_half_fov_y * depth;
}

TEST_CASE("geomipmapCullsOnlyTilesOutsideTheFrustumAndPicksDeBoersLevels", "[geomipmap]") {
  const Field f = make_field(16, 12, 8, 0.2, 25.0);
  const GeoMipMap map = build_geomipmap(f.lattice, 8);
  const double tile_x = 2000.0 / 16, tile_z = 1600.0 / 12;
  std::uint64_t culled_somewhere = 0, seen_culled = 0, limited_by_error = 0;
  std::uint64_t drawn_at_level[4] = {};
  for (int view_index = 0; view_index < 24; ++view_index) {
    CameraSettings settings;
    settings.position = {-900.0 + 80.0 * view_index, 150.0 + 20.0 * (view_index % 5),
                         700.0 - 50.0 * view_index};
    settings.yaw_deg = 15.0 * view_index;
    settings.pitch_deg = -10.0 - 3.0 * (view_index % 7);
    settings.far = 900.0 + 100.0 * (view_index % 4);
    ViewportSettings viewport;
    viewport.width = 640;
    viewport.height = 480;
    const CameraFrame cam = make_camera_frame(settings, viewport);
    View view;
    view.camera = cam;
    view.width = viewport.width;
    view.height = viewport.height;
    view.pixel_error = 6.0;
    view.occlusion = false;  // the frustum alone here; occlusion: geomipmap_seam_test.cc
    const double ppt = viewport.height / (2 * cam.tan_half_fov_y);
    const Selection s = select_levels(map, view);
    INFO("view " << view_index);
    REQUIRE(s.counts.tiles_drawn + s.counts.tiles_culled == map.tiles.size());
    culled_somewhere += s.counts.tiles_culled;
    for (int l = 0; l < 4; ++l)
      drawn_at_level[l] += s.counts.tiles_per_level[l];
    for (int tz = 0; tz < map.tiles_z; ++tz) {
      for (int tx = 0; tx < map.tiles_x; ++tx) {
        const int level = s.level[static_cast<std::size_t>(tz) * map.tiles_x + tx];
        const bool drawn = s.drawn[static_cast<std::size_t>(tz) * map.tiles_x + tx] != 0;
        const TileBounds& t = map.tiles[static_cast<std::size_t>(tz) * map.tiles_x + tx];
        const glm::dvec3 low(-1000.0 + tile_x * tx, t.low, -800.0 + tile_z * tz);
        const glm::dvec3 high(low.x + tile_x, t.high, low.z + tile_z);
        if (!drawn) {
          // No point of a culled tile's box is in view (a 9 x 5 x 9 lattice of points).
          for (int i = 0; i <= 8; ++i) {
            for (int j = 0; j <= 4; ++j) {
              for (int k = 0; k <= 8; ++k) {
                const glm::dvec3 p = low + (high - low) * glm::dvec3(i / 8.0, j / 4.0, k / 8.0);
                seen_culled += in_view(cam, p) ? 1 : 0;
              }
            }
          }
        }
        // de Boer, for every tile (culled ones too: their neighbours stitch to their level): the
        // coarsest level whose error, seen from the box's nearest point, is at most tau pixels.
        const glm::dvec3 nearest = glm::clamp(cam.position, low, high);
        const double distance = glm::length(nearest - cam.position);
        const auto fits = [&](int l) { return t.error[l] * ppt <= view.pixel_error * distance; };
        CHECK((level == 0 || fits(level)));  // level 0 is the finest there is
        // Neighbours within one level; a tile kept below the coarsest level that fits has a
        // neighbour one level finer that holds it there.
        int finest_neighbour = map.levels;
        for (const auto& [nx, nz] : {std::pair{tx - 1, tz}, std::pair{tx + 1, tz},
                                     std::pair{tx, tz - 1}, std::pair{tx, tz + 1}}) {
          if (nx < 0 || nz < 0 || nx >= map.tiles_x || nz >= map.tiles_z)
            continue;
          const int n = s.level[static_cast<std::size_t>(nz) * map.tiles_x + nx];
          CHECK(std::abs(n - level) <= 1);
          finest_neighbour = std::min(finest_neighbour, n);
        }
        if (level + 1 < map.levels && fits(level + 1))
          CHECK(finest_neighbour == level - 1);
        if (level + 1 < map.levels && !fits(level + 1))
          ++limited_by_error;
      }
    }
    require_watertight(map, s, stitched_mesh(map, s));
  }
  CHECK(culled_somewhere > 0);
  CHECK(seen_culled == 0);      // points of culled boxes inside the camera's frustum
  CHECK(limited_by_error > 0);  // de Boer's rule, not only the neighbours, sets levels
  for (int l = 0; l < 4; ++l)
    CHECK(drawn_at_level[l] > 0);  // every level chosen somewhere
}

}  // namespace
}  // namespace relief::geomipmap
