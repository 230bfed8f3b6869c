// A wide-angle panorama of any scene (Miller's "wide-angle panorama rendered through an
// intermediate viewing sphere", here a cube of six views): the scene's camera turned to face
// the four horizontal directions, up and down, each view rendered with a margin of a few pixels
// beyond its 90 degrees, then resampled into an equirectangular image. Every direction takes the
// view it is most central in (the cube face), bilinearly from its linear radiance; where a
// neighbouring view also holds the direction (its margin), the two are compared: the seams'
// figures.
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/scene/scene.h"

namespace relief {

// A face view's margin beyond its 90 degrees, in pixels on each side: bilinear sampling reads
// one pixel past the cube edge, the seam comparison the next.
inline constexpr int kPanoramaFaceMargin = 2;

// The six views of a panorama from `camera`: yaw + 0, 90, 180, 270 degrees level, then up and
// down (pitch +-90, the horizontal yaw the scene's), each side x side pixels wide with a
// field of view of 2 atan(side / (side - 2 margin)) both ways. Precondition: side > 2 margin.
struct PanoramaViews {
  std::vector<CameraSettings> cameras;
  ViewportSettings viewport;
};
PanoramaViews panorama_views(const CameraSettings& camera, int side);

// One rendered view: its camera and its linear radiance, 3 floats a pixel, row 0 at the bottom.
struct PanoramaFace {
  CameraFrame camera;
  int side = 0;
  std::vector<float> linear;
};

struct PanoramaSeams {
  std::uint64_t directions = 0;  // output pixels a second view also holds
  double mean_codes = 0;         // mean over them of the largest channel difference, sRGB codes
  int max_codes = 0;             // the largest
};

// The equirectangular image: width x height (height = width / 2) sRGB bytes, row 0 at the
// bottom (latitude -90 to 90 from the bottom, longitude -180 to 180 from the left around the
// scene camera's yaw, its view direction at the centre).
struct Panorama {
  int width = 0, height = 0;
  std::vector<std::uint8_t> srgb;
  PanoramaSeams seams;
};

// Precondition: six faces as panorama_views makes them, width even and >= 4.
Panorama resample_panorama(const std::vector<PanoramaFace>& faces, double yaw_deg, int width);

}  // namespace relief
