// The scene: everything a frame is rendered from. Plain data with the built-in defaults as
// member initialisers; scene_json.h loads, validates and prints it. README.md's scene
// reference lists every field with its range.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "core/interpolant.h"

namespace relief {

using Vec2d = std::array<double, 2>;
using Vec3d = std::array<double, 3>;

struct CameraSettings {
  // World: right-handed, y up. Position in double (design.md): only camera-relative offsets
  // are ever stored in float.
  Vec3d position = {0.0, 420.0, 0.0};
  // Yaw about +y in degrees: 0 looks along -z, 90 along +x. Pitch: positive looks up.
  double yaw_deg = 30.0;
  double pitch_deg = -6.0;
  double fov_y_deg = 60.0;
  double near = 0.5;
  // Distance along the view direction to which terrain is generated: the far plane of the
  // projected grid's frustum (§4.1). Depth itself uses an infinite far plane.
  double far = 60000.0;
};

struct ViewportSettings {
  int width = 1280;  // the paper's viewport (§4.4)
  int height = 1024;
};

struct GridSettings {
  int width = 512;  // the paper's projected grid (§4.4)
  int height = 512;
  // Cells projected past the region that can be seen, on every side (§4.1: "the grid has to
  // be extended slightly beyond the vertices visible to avoid holes at the viewport
  // boundaries").
  int margin = 2;
};

enum class LodCriterion {
  kAmplitude,  // §4.1: the last octave is the one whose amplitude equals the spacing
  kNyquist,    // the last octave is the one whose lattice cell spans two grid spacings
};

struct LodSettings {
  LodCriterion criterion = LodCriterion::kAmplitude;
  double bias = 0.0;  // octaves added to (or, negative, removed from) the criterion's count
};

// §2.2 domain warping. Relief's reading of the garbled formulas is in docs/paper-reading.md.
struct WarpSettings {
  bool enabled = false;
  Vec2d c1 = {0.35, 0.16};   // rotation per unit roughness (Figure 3's value)
  Vec2d c2 = {-0.07, 0.13};  // constant rotation update
  Vec2d c3 = {0.11, 0.17};   // translation per unit height / roughness
  Vec2d r0 = {1.0, 0.0};     // initial rotation vector (cos a, sin a); need not be unit
  Vec2d t0 = {0.0, 0.0};     // initial displacement, base-domain lattice cells
};

struct TerrainSettings {
  std::uint64_t seed = 1;
  int lattice_size = 256;  // P
  Interpolant interpolant = Interpolant::kQuintic;
  double r = 2.0;        // lacunarity (Eq. 1)
  double H = 0.8;        // Hurst exponent, H = 3 - D (Eq. 1)
  int first_octave = 0;  // k0 (Eq. 1): the global structure
  int last_octave = 14;  // the finest octave the LOD may ever add
  LodSettings lod;
  WarpSettings warp;
  // World units spanned by one lattice cell of octave 0: the size of the largest features.
  double horizontal_scale = 2400.0;
  double base_height = 0.0;  // world height of the base domain (fBm value 0)
  double amplitude = 260.0;  // world units per unit of fBm (the N(0,1) lattice)
  // Water surface height; nullopt: no water (the water pass is skipped).
  std::optional<double> water_level = 0.0;
};

struct OutputSettings {
  std::string image = "relief.png";
  std::string stages_dir = "stages";
};

struct Scene {
  CameraSettings camera;
  ViewportSettings viewport;
  GridSettings grid;
  TerrainSettings terrain;
  OutputSettings output;
};

}  // namespace relief
