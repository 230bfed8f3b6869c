// A finite height field drawn by GeoMipMapping (terrain.heightfield.geomipmap) for the frame
// tests of every backend (tests/pipeline/geomipmap_frame_test.cc, tests/gl/gl_geomipmap_test.cc):
// a 257² field of ridges or a plateau before a valley written as a PFM, cameras over it, and
// the seam criterion (which pixels a triangle must cover).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/scene/scene.h"
#include "pipeline/frame.h"
#include "raster/raster_types.h"
#include "tests/support/heightfield_files.h"
#include "tests/support/test_support.h"

namespace relief::test {

inline constexpr int kSide = 257;  // 16 tiles of 16 cells: the lattice is the texel centres
inline constexpr double kHalfExtent = 2000.0;

// Ridges at several scales and a little noise (levels differ between neighbours everywhere),
// or a plateau at 400 over z > 1000 before a valley at 0 (the plateau hides the valley from
// a camera standing on it).
inline std::vector<float> field_samples(bool plateau) {
  std::vector<float> h(std::size_t(kSide) * kSide);
  for (int r = 0; r < kSide; ++r) {
    for (int c = 0; c < kSide; ++c) {
      std::uint64_t x = std::uint64_t(r) * 7919u + std::uint64_t(c);
      x = (x ^ (x >> 31)) * 0xbf58476d1ce4e5b9ull;
      x ^= x >> 29;
      const double noise = double(x % 4096) / 4096.0 - 0.5;
      const double ridges = 120.0 * std::sin(0.031 * c) * std::cos(0.027 * r) +
                            35.0 * std::sin(0.19 * c + 0.11 * r) + 4.0 * noise;
      const double z = -kHalfExtent + (r + 0.5) * 2 * kHalfExtent / kSide;  // row 0 at z0
      h[std::size_t(r) * kSide + c] = float(plateau ? (z > 1000.0 ? 400.0 : 0.2 * ridges) : ridges);
    }
  }
  return h;
}

struct FieldScene {
  test::TempDir dir{"geomipmap-frame"};
  std::vector<float> samples;
  Scene scene;
};

inline void build(FieldScene& f, bool plateau, double pixel_error) {
  f.samples = field_samples(plateau);
  const std::filesystem::path file = f.dir.path() / "field.pfm";
  std::ofstream(file, std::ios::binary) << test::pfm_bytes(kSide, kSide, f.samples);
  HeightFieldSettings field;
  field.image = file.string();
  field.extent = {-kHalfExtent, -kHalfExtent, kHalfExtent, kHalfExtent};
  field.height = {0.0, 1.0};  // the PFM's floats are world heights
  field.geomipmap = GeoMipMapSettings{16, pixel_error, true};
  f.scene.terrain.heightfield = field;
  f.scene.terrain.base_height = 0.0;
  f.scene.terrain.water_level.reset();
  f.scene.viewport.width = 320;
  f.scene.viewport.height = 240;
  f.scene.camera.near = 0.5;
  f.scene.camera.far = 60000.0;
}

// A view from near the field's edge over its ridges: most tiles in view, at several levels.
inline void look_over_the_ridges(Scene& scene) {
  scene.camera.position = {300.0, 400.0, 1800.0};
  scene.camera.pitch_deg = -14.0;
}

inline FrameRequest geometry_request(Backend backend, FrameSkips skips = {}) {
  FrameRequest request;
  request.backend = backend;
  request.skips = skips;
  request.outputs.primitive = true;
  request.outputs.depth = true;
  request.outputs.world_height = true;
  return request;
}

// Pixels whose ray, from a camera above every sample, reaches the plane of the lowest sample
// inside the texel centres' rectangle: it crosses the surface on the way (the mesh lies between
// the lowest and the highest sample, continuous over that rectangle), so a triangle must cover
// them. Returns (must cover, holes).
inline std::pair<std::uint64_t, std::uint64_t> seam_holes(const Scene& scene, const Frame& frame,
                                                          double lowest) {
  const CameraFrame cam = make_camera_frame(scene.camera, scene.viewport);
  const int width = scene.viewport.width, height = scene.viewport.height;
  const double inner = kHalfExtent * (1.0 - 1.0 / kSide) * (1.0 - 1e-6);
  std::uint64_t must_cover = 0, holes = 0;
  for (int py = 0; py < height; ++py) {
    for (int px = 0; px < width; ++px) {
      const double ndc_x = (px + 0.5) / width * 2 - 1, ndc_y = (py + 0.5) / height * 2 - 1;
      const glm::dvec3 ray = cam.forward + ndc_x * cam.tan_half_fov_x * cam.right +
                             ndc_y * cam.tan_half_fov_y * cam.up;
      if (!(ray.y < 0)) {
        continue;
      }
      const glm::dvec3 hit = cam.position + ((lowest - cam.position.y) / ray.y) * ray;
      if (std::abs(hit.x) >= inner || std::abs(hit.z) >= inner) {
        continue;
      }
      ++must_cover;
      holes += frame.image.primitive[std::size_t(py) * width + px] == raster::kNoPrimitive;
    }
  }
  return {must_cover, holes};
}

// On the plateau (build(f, true, ...)), looking toward the valley below its edge. The
// occluders are whole tiles' floors in front of the near plane: the camera stands just inside
// the last row of tiles (lattice rows 240..256 begin at z = 1743.5), over the middle of a column
// of tiles (x from 0 to 249), so the floor of the plateau tile before it covers the valley's.
inline void look_from_the_plateau(Scene& scene) {
  scene.camera.position = {125.0, 420.0, 1752.0};
  scene.camera.yaw_deg = 0.0;
  scene.camera.pitch_deg = -2.0;
}

// View `view` (0 ... 11) of the seam tests' camera sweep over the ridges, above every sample
// (`highest`): near and far, steep and grazing, turning, tau from 0.5 to 8 pixels.
inline void sweep_view(Scene& scene, int view, double highest) {
  const double a = 0.7 * view;
  scene.camera.position = {1500.0 * std::sin(a), highest + 20.0 + 37.0 * (view % 5),
                           1500.0 * std::cos(1.3 * a)};
  scene.camera.yaw_deg = 29.0 * view;
  scene.camera.pitch_deg = view < 9 ? -25.0 - 5.0 * view : -4.0 - view;
  scene.terrain.heightfield->geomipmap->pixel_error = 0.5 + (view % 4) * 2.5;
}

}  // namespace relief::test
