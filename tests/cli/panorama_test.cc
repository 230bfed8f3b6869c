// relief panorama (tools/panorama.h): the six views' cameras, the resampling against an analytic
// radiance painted into synthetic views (every direction through the right view and pixel), the
// seams' figure, and the command's refusals and determinism.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/camera.h"
#include "core/srgb.h"
#include "image/png_header.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tools/panorama.h"

namespace relief {
namespace {

using test::require_refused;
using test::run;

// A smooth radiance over directions, different in every channel.
glm::dvec3 radiance(const glm::dvec3& d) {
  return {0.2 + 0.15 * (d.x + 1.0), 0.2 + 0.15 * (d.y + 1.0), 0.2 + 0.15 * (d.z + 1.0)};
}

// The six views of `camera`, each pixel painted with the radiance of its centre's ray
// (core/camera.h's frame, the GL pixel convention), plus `offset` in view `shifted`.
std::vector<PanoramaFace> painted_faces(const CameraSettings& camera, int side, int shifted = -1,
                                        double offset = 0.0) {
  const PanoramaViews views = panorama_views(camera, side);
  std::vector<PanoramaFace> faces;
  for (std::size_t k = 0; k < views.cameras.size(); ++k) {
    PanoramaFace face{make_camera_frame(views.cameras[k], views.viewport), side, {}};
    face.linear.resize(std::size_t(side) * std::size_t(side) * 3);
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        const double x = ((i + 0.5) / side * 2.0 - 1.0) * face.camera.tan_half_fov_x;
        const double y = ((j + 0.5) / side * 2.0 - 1.0) * face.camera.tan_half_fov_y;
        const glm::dvec3 d =
            glm::normalize(face.camera.forward + x * face.camera.right + y * face.camera.up);
        const glm::dvec3 r = radiance(d) + (int(k) == shifted ? offset : 0.0);
        for (int c = 0; c < 3; ++c) {
          face.linear[(std::size_t(j) * std::size_t(side) + std::size_t(i)) * 3 + c] = float(r[c]);
        }
      }
    }
    faces.push_back(std::move(face));
  }
  return faces;
}

TEST_CASE("panoramaViewsFaceTheCubesSixDirectionsWithAMargin", "[panorama]") {
  CameraSettings camera;
  camera.yaw_deg = 170.0;
  camera.pitch_deg = -20.0;
  const PanoramaViews views = panorama_views(camera, 68);
  REQUIRE(views.cameras.size() == 6);
  CHECK(views.viewport.width == 68);
  CHECK(views.viewport.height == 68);
  const double yaws[] = {170.0, -100.0, -10.0, 80.0, 170.0, 170.0};
  const double pitches[] = {0.0, 0.0, 0.0, 0.0, 90.0, -90.0};
  for (std::size_t k = 0; k < 6; ++k) {
    CHECK(views.cameras[k].yaw_deg == Approx(yaws[k]).margin(1e-12));
    CHECK(views.cameras[k].pitch_deg == pitches[k]);
    // The central 64 pixels span 90 degrees: tan(fov / 2) = 68 / 64.
    CHECK(std::tan(views.cameras[k].fov_y_deg * M_PI / 360.0) == Approx(68.0 / 64.0));
  }
}

TEST_CASE("panoramaResamplesEveryDirectionFromItsView", "[panorama]") {
  CameraSettings camera;
  camera.yaw_deg = 33.0;
  const int width = 256, side = width / 4 + 2 * kPanoramaFaceMargin;
  const Panorama p = resample_panorama(painted_faces(camera, side), camera.yaw_deg, width);
  REQUIRE(p.width == width);
  REQUIRE(p.height == width / 2);
  int worst = 0;
  for (int j = 0; j < p.height; ++j) {
    const double latitude = ((j + 0.5) / p.height - 0.5) * M_PI;
    for (int i = 0; i < p.width; ++i) {
      const double turn = camera.yaw_deg * M_PI / 180.0 + ((i + 0.5) / p.width - 0.5) * 2 * M_PI;
      const glm::dvec3 d(std::sin(turn) * std::cos(latitude), std::sin(latitude),
                         -std::cos(turn) * std::cos(latitude));
      const glm::dvec3 r = radiance(d);
      for (int c = 0; c < 3; ++c) {
        const int got = p.srgb[(std::size_t(j) * std::size_t(p.width) + std::size_t(i)) * 3 + c];
        worst = std::max(worst, std::abs(got - int(srgb_byte(float(r[c])))));
      }
    }
  }
  // Bilinear interpolation of a smooth radiance: within a code or two of the exact direction's.
  CHECK(worst <= 2);
  // Views that agree leave seams of rounding only; one view brighter shows on its edges.
  CHECK(p.seams.directions > 0);
  CHECK(p.seams.mean_codes <= 1.0);
  const Panorama shifted =
      resample_panorama(painted_faces(camera, side, 1, 0.1), camera.yaw_deg, width);
  CHECK(shifted.seams.directions == p.seams.directions);
  CHECK(shifted.seams.mean_codes > 5.0 * std::max(p.seams.mean_codes, 1.0));
}

TEST_CASE("panoramaCommandRefusesBadOptionsAndIsTheSameForAnyThreadCount", "[panorama]") {
  test::TempDir dir("panorama");
  const std::filesystem::path out = dir.path() / "p.png";
  for (const char* width : {"63", "8", "8194", "-4", "x"}) {
    INFO(width);
    const test::CliResult r = run({"panorama", "--width", width, "-o", out.string()});
    CHECK(r.code == kExitBadInput);
    CHECK_FALSE(std::filesystem::exists(out));
  }
  require_refused(run({"panorama", "--width", "64", "-o", (dir.path() / "p.jpg").string()}),
                  "give a file name ending in .png", dir.path() / "p.jpg");
  require_refused(run({"panorama", "--width", "64", "-o", out.string(), "--json", out.string()}),
                  "name the same file", out);
  require_refused(run({"panorama", "--width", "64", "--set", "camera.far=-1", "-o", out.string()}),
                  "camera.far", out);
  // The same file under another spelling, a missing directory, an empty --json: refused before
  // any work, nothing written.
  const std::string dotted = (dir.path() / "." / "p.png").string();
  require_refused(run({"panorama", "--width", "64", "-o", out.string(), "--json", dotted}),
                  "same file", out);
  require_refused(run({"panorama", "--width", "64", "-o", out.string(), "--json",
                       (dir.path() / "missing" / "s.json").string()}),
                  "its directory does not exist", out);
  require_refused(run({"panorama", "--width", "64", "-o", out.string(), "--json", ""}),
                  "--json is empty", out);
  const std::filesystem::path one = dir.path() / "one.png", two = dir.path() / "two.png";
  REQUIRE(run({"panorama", "lake", "--width", "96", "--threads", "1", "-o", one.string()}).code ==
          0);
  REQUIRE(run({"panorama", "lake", "--width", "96", "--threads", "2", "-o", two.string(), "--json",
               (dir.path() / "seams.json").string()})
              .code == 0);
  CHECK(test::read_bytes(one) == test::read_bytes(two));
  const std::vector<unsigned char> png = test::read_bytes(one);
  const std::optional<PngHeader> header = parse_png_header(png.data(), png.size());
  REQUIRE(header);
  CHECK(header->width == 96);
  CHECK(header->height == 48);
  CHECK(std::filesystem::exists(dir.path() / "seams.json"));
}

}  // namespace
}  // namespace relief
