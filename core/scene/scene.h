// The scene: everything a frame is rendered from. Plain data with the built-in defaults as
// member initialisers; scene_json.h loads, validates and prints it. docs/scene-reference.md
// lists every field with its range.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/interpolant.h"

namespace relief {

using Vec2d = std::array<double, 2>;
using Vec3d = std::array<double, 3>;

struct CameraSettings {
  // World: right-handed, y up. Position in double (docs/architecture.md): only camera-relative
  // offsets are ever stored in float.
  Vec3d position = {0.0, 700.0, 0.0};
  // Yaw about +y in degrees: 0 looks along -z, 90 along +x. Pitch: positive looks up.
  double yaw_deg = 30.0;
  double pitch_deg = -8.0;
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

// How a layer's proto-texture is filtered between mip levels (GL 4.5 §8.14.2).
enum class TextureFilter {
  kTrilinear,  // GL_LINEAR_MIPMAP_LINEAR: the two levels around lambda, blended
  kBilinear,   // GL_LINEAR_MIPMAP_NEAREST: the level nearest lambda alone (one fetch, not two)
};

struct LodSettings {
  LodCriterion criterion = LodCriterion::kAmplitude;
  double bias = 0.0;  // octaves added to (or, negative, removed from) the criterion's count
  // §4.1 geomorphing: the octave after floor(nu) weighted by nu's fraction (true), or whole
  // octaves only, nu rounded up (false: cheaper to reason about, but octaves pop in and out
  // as the camera moves).
  bool fractional = true;
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

// §3's low-frequency base: a coarse grey-scale height sketch over a world rectangle, added to
// the fractal (core/height_sketch.h), so that a designer places mountains, valleys and seas and
// the fractal supplies the detail.
struct SketchSettings {
  // A PNG file (1 channel, 8 or 16 bits), absolute or relative to the scene file, or
  // "builtin:NAME" for a sketch shipped inside the binary (island).
  std::string image;
  std::array<double, 4> extent = {-10000.0, -10000.0, 10000.0, 10000.0};  // [x0, z0, x1, z1]
  Vec2d height = {0.0, 1000.0};  // world heights of black and of white
};

// A finite height field as the terrain (core/height_sketch.h samples it as it samples §3's
// sketch): real elevation data or a `relief generate` map. A sketch that may be large and come
// in any height format, with the fractal off unless `fractal` asks for its detail on top.
// GeoMipMapping (de Boer 2000, as Scape draws a finite field): the field drawn as a stitched
// mesh of tiles at levels of detail chosen per frame by screen-space error, culled by a quadtree
// of bounding boxes and by occlusion (core/heightfield/geomipmap.h), in place of the projected
// grid. The mesh's vertices are the field's surface at its sample positions.
struct GeoMipMapSettings {
  int tile_cells = 32;       // T: cells a tile spans a side, a power of two from 2 to 256
  double pixel_error = 1.0;  // tau: the largest screen-space error a level may make, pixels
  bool occlusion = true;     // tiles hidden behind nearer ground are not drawn (bit-identical)
};

struct HeightFieldSettings : SketchSettings {
  // `image` (the scene key "file"): a grey PNG (8 or 16 bits), a one-channel PFM (float), or
  // RAW16 (.r16, .raw: little-endian 16-bit levels, top row first, no header).
  // RAW16's samples per row; 0: the file is square and its size gives the side.
  int raw_width = 0;
  // Whether the paper's fractal adds its detail (terrain.amplitude and the octaves) on top;
  // false: stage 3 sums no octave and the terrain is base_height plus the field.
  bool fractal = false;
  // Without the fractal: whether each vertex reads the field filtered to its grid spacing
  // (levels of detail, geomorphed; core/height_sketch.h); false: the samples themselves. Off by
  // default: on the measured scenes it sat farther from the ground truth (docs/heightfields.md).
  bool level_of_detail = false;
  // Whether the surface passes through every sample (point heights: a DEM, a `relief export`
  // map), the samples prefiltered into the cubic B-spline's coefficients once on loading
  // (core/field_prefilter.h); false: the B-spline of the samples themselves, which smooths them
  // (a peak keeps 4/9 of its height above its neighbours).
  bool interpolating = false;
  // Whether a GeoTIFF's own placement (ModelPixelScale and ModelTiePoint, projected metres or
  // feet) gives the extent, which is then not read (pipeline/geotiff_reference.h).
  bool georeferenced = false;
  // Drawn by GeoMipMapping instead of the projected grid; nullopt: the projected grid.
  std::optional<GeoMipMapSettings> geomipmap;
};

// §3 Eq. 2: the auxiliary function S as a convex combination of grey-scale basis images,
// S = sum_i w_i I_i / sum_i w_i, composed once per scene into the periodic grid that takes the
// noise lattice's place in stage 3 (core/basis_images.h, docs/terrain-spec.md section 12).
struct BasisImageSettings {
  // A grey PNG (8 or 16 bits), absolute or relative to the scene file, or "builtin:basis/NAME"
  // (craters, ridges, dunes: shipped inside the binary).
  std::string image;
  double weight = 1.0;       // the constant weight (>= 0), used when weight_image is empty
  std::string weight_image;  // a grey PNG of the image's size: the weight per texel instead
  double low_pass = 0.0;     // Gaussian blur, sigma in texels; 0: off
  double high_pass = 0.0;    // the image minus its Gaussian blur of this sigma; 0: off
  bool normalize = false;    // to zero mean and unit variance (the N(0,1) lattice's statistics)
};

enum class BasisWrap {
  kRepeat,  // the image tiles as it is
  kMirror,  // the image mirrored into 2W x 2W first: any image then tiles (C0 at the seams)
};

struct BasisSettings {
  double tile_size = 24000.0;  // world units one image tile spans at octave 0
  BasisWrap wrap = BasisWrap::kRepeat;
  // The composed grid refined this many times per side (1, 2, 4 or 8) by the periodic cubic
  // B-spline (core/basis_images.h): stage 3's interpolants have zero slope at every texel, so
  // a smooth image shows one terrace per texel; refined and sampled with the linear
  // interpolant it does not.
  int upsample = 1;
  std::vector<BasisImageSettings> images;  // 1 to limits::kMaxBasisImages
};

// §4.1's spherical domain (docs/planet.md): the base domain warped around a sphere of this
// radius whose surface lies at terrain.base_height.
struct PlanetSettings {
  double radius = 0.0;   // world units; 0: the plane
  double horizon = 0.0;  // artificial horizon, arc length along the datum; 0: the geometric one
  // Camera altitudes (above terrain.base_height) over which the projected grid on the sphere
  // blends into equal-angle sampling; nullopt: the plain projected grid at every altitude.
  std::optional<Vec2d> equal_angle;
};

struct TerrainSettings {
  std::uint64_t seed = 1;
  int lattice_size = 256;  // P
  Interpolant interpolant = Interpolant::kQuintic;
  double r = 2.0;        // lacunarity (Eq. 1)
  double H = 0.85;       // Hurst exponent, H = 3 - D (Eq. 1)
  int first_octave = 0;  // k0 (Eq. 1): the global structure
  int last_octave = 14;  // the finest octave the LOD may ever add
  LodSettings lod;
  WarpSettings warp;
  // World units spanned by one lattice cell of octave 0: the size of the largest features.
  double horizontal_scale = 3000.0;
  double base_height = 100.0;  // world height of the base domain (fBm value 0)
  double amplitude = 360.0;    // world units per unit of fBm (the N(0,1) lattice)
  // Water surface height; nullopt: no water (the water pass is skipped).
  std::optional<double> water_level = 0.0;
  // The low-frequency base; nullopt: none (the fractal alone).
  std::optional<SketchSettings> sketch;
  // A finite height field as the terrain; nullopt: none. At most one of sketch and heightfield.
  std::optional<HeightFieldSettings> heightfield;
  // §3 Eq. 2's basis images in place of the noise lattice in stage 3; nullopt: the lattice.
  // With them, stage 3's P is the composed grid's side and its octave-0 cell is
  // basis.tile_size / P: lattice_size sizes only the shading's noise, horizontal_scale is unused.
  std::optional<BasisSettings> basis;
  // §4.1's spherical domain; nullopt (or radius 0): the plane.
  std::optional<PlanetSettings> planet;
};

// The field stage 3 adds to the fractal: terrain.sketch or terrain.heightfield (a scene has at
// most one), or null.
inline const SketchSettings* added_height_field(const TerrainSettings& terrain) {
  if (terrain.heightfield) {
    return &*terrain.heightfield;
  }
  return terrain.sketch ? &*terrain.sketch : nullptr;
}

// Whether stage 3 sums the fractal's octaves: off only for a height field without `fractal`.
inline bool fractal_enabled(const TerrainSettings& terrain) {
  return !terrain.heightfield || terrain.heightfield->fractal;
}

// One proto-texture layer (§4.2) with the height/slope ranges of Scape's layers.
struct MaterialLayer {
  std::string name;
  // "builtin:NAME" (sand, grass, rock, snow, bed, basalt, dune: synthesised at start-up) or a
  // PNG file: square, a power of two from 4 to 4096 pixels, 8-bit RGB or RGBA (alpha ignored).
  std::string texture;
  double tile_size = 40.0;                // world units per repeat of the texture
  Vec2d height = {-1e7, 1e7};             // world heights where the layer is present
  bool height_relative_to_water = false;  // height range measured from terrain.water_level
  Vec2d slope_deg = {0.0, 90.0};          // slope angles where the layer is present (atan |grad h|)
  double height_spread = 25.0;            // half-width of the height transitions, world units
  double slope_spread_deg = 4.0;          // half-width of the slope transitions, degrees
  double specular = 0.0;                  // Phong specular strength in [0, 1]
};

// How the terrain gets its colour: the paper's proto-textures (§4.2), or castledragmire's
// height-to-colour gradient lit per vertex (Gouraud shading).
enum class ShadingMode { kTextures, kGradient };

// One colour stop of the height gradient: at `at` (0 at the gradient's low height, 1 at its
// high one) the colour is `color` (linear RGB). Two stops at the same height make a step.
struct GradientStop {
  double at = 0.0;
  Vec3d color = {0.0, 0.0, 0.0};
};

struct GradientSettings {
  // World heights of at = 0 and at = 1; none: the terrain's height bounds (core/height_bounds.h).
  std::optional<Vec2d> range;
  std::vector<GradientStop> stops;  // at non-decreasing; the default set is in scene_defaults.cc
};

struct ShadingSettings {
  ShadingMode mode = ShadingMode::kTextures;
  GradientSettings gradient;          // read where mode is kGradient
  std::vector<MaterialLayer> layers;  // the default set is in scene_defaults.cc
  int texture_size = 256;             // side of the built-in textures, power of two
  double mip_blend = 0.3;  // §4.2: each mip level blended this far toward the mean colour
  bool triplanar = true;   // Mekala, Scape: three projections weighted by squared normals
  // The nearest level by default: as close to the ground truth as trilinear, one fetch
  // instead of two (docs/using-relief.md, "Time against error").
  TextureFilter texture_filter = TextureFilter::kBilinear;
  double dither = 0.6;        // Scape: transition dithering, in units of each layer's spreads
  double dither_scale = 9.0;  // world units per lattice cell of the dithering noise
};

struct LightingSettings {
  double sun_azimuth_deg = 230.0;  // 0: the sun stands toward -z, 90: toward +x
  double sun_elevation_deg = 24.0;
  Vec3d sun_color = {1.0, 0.93, 0.82};
  double sun_intensity = 1.8;
  Vec3d sky_color = {0.42, 0.58, 0.85};     // hemispherical light from above (Scape)
  Vec3d ground_color = {0.22, 0.20, 0.16};  // and from below
  double sky_intensity = 0.25;
  double ambient = 0.03;
  double shininess = 48.0;  // Phong exponent of the layers' specular term
  double exposure = 0.75;   // linear radiance scale before sRGB encoding
  // Cast shadows: the terrain's horizon toward the sun (core/sun_horizons.h); off: the paper's
  // image, no shadow pass at all.
  bool shadows = false;
  int shadow_resolution = 256;  // samples per side of each level of the horizon cache
  // Sky light: the hemispherical light's sky share scaled by the sky the terrain leaves open
  // above each point, from horizons in four directions on the same cache
  // (core/sky_horizons.h); off: the paper's image, no sky pass at all.
  bool sky_occlusion = false;
};

// §4.3 water; the level is terrain.water_level.
struct WaterSettings {
  Vec3d shallow_color = {0.08, 0.30, 0.28};
  Vec3d deep_color = {0.015, 0.09, 0.085};  // "deep oceans get the green-ish hue"
  Vec3d extinction = {0.42, 0.11, 0.075};   // per world unit of transmitted path, RGB
  double full_depth = 14.0;                 // depth at which water looks deep and reflects fully
  double wave_length = 7.0;                 // world units, the largest wave of the normal map
  double wave_strength = 0.2;               // slope of the wave normal map in deep water
  double wave_speed = 1.2;                  // world units per second
  // The terrain reflected in the water (Miller): the reflected ray marched over the shadows'
  // horizon cache (core/water_reflection.h); off: the paper's sky alone, no reflection pass.
  bool reflect_terrain = false;
};

// A skybox (Mekala): six square PNG faces in place of the sky gradient, sampled as GL samples a
// cube map (core/skybox.h).
struct SkyboxSettings {
  // +x, -x, +y, -y, +z, -z: GL's cube-map faces in their order, each a path like a layer's
  // texture (square, 8-bit, a power of two from 4 to kMaxSkyboxSize, all six of one size).
  std::array<std::string, 6> faces;
  double intensity = 1.0;  // linear radiance of a white texel
  bool sun_disc = true;    // the sun's disc and halo drawn over the faces
};

// Aerial perspective and sky from one scattering of the sun's light in an exponential
// atmosphere (Bruneton & Neyret 2008's single scattering, in closed form over flat ground:
// core/atmosphere.h). Coefficients per world unit at height 0; the air thins by e every
// scale_height. Replaces the gradient and the fog where given.
struct AtmosphereSettings {
  double scale_height = 8000.0;                      // world units
  Vec3d rayleigh = {5.8e-6, 13.5e-6, 33.1e-6};       // molecules' scattering (Bruneton's)
  double mie = 3.2e-6;                               // haze's scattering, grey; extinction / 0.9
  Vec3d absorption = {0.65e-6, 1.881e-6, 0.085e-6};  // ozone's (Bruneton's), no scattering
  double mie_g = 0.76;                               // haze's forward lobe (Cornette-Shanks g)
  double intensity = 20.0;                           // the sun in the sky's light, x lighting's sun
};

// A fractal cloud layer (castledragmire's and Miller's cloud layers): the heights
// [altitude, altitude + thickness] hold cloud whose density over (x, z) is domain-warped fBm
// of the terrain's own noise lattice (core/clouds.h). It covers the sky and the terrain behind
// it, seen from above, below or inside, and shadows the ground.
struct CloudSettings {
  double altitude = 2400.0;  // world height of the layer's bottom
  double thickness = 300.0;  // world units
  double coverage = 0.45;    // the share of the layer's area holding cloud: 0 none, 1 overcast
  double density = 0.006;    // extinction per world unit where the cloud is full
  double scale = 2500.0;     // world units per lattice cell of the largest octave
  int octaves = 5;           // each twice the frequency and half the amplitude of the last
  double warp = 0.5;         // lattice cells of the domain warp (0: none)
  Vec3d color = {0.9, 0.9, 0.92};  // albedo: the sun's and the sky's light it returns
};

struct SkySettings {
  Vec3d zenith_color = {0.17, 0.33, 0.70};
  Vec3d horizon_color = {0.66, 0.75, 0.86};
  double sun_disc_deg = 0.6;                     // angular radius of the sun disc
  double fog_density = 2.2e-5;                   // per world unit: fog = 1 - exp(-density distance)
  std::optional<SkyboxSettings> skybox;          // nullopt: the gradient
  std::optional<AtmosphereSettings> atmosphere;  // nullopt: the gradient and the fog
  std::optional<CloudSettings> clouds;           // nullopt: a clear sky
};

struct OutputSettings {
  std::string image = "relief.png";
  std::string stages_dir = "stages";
  std::optional<std::string> float_image;  // linear radiance as PFM; nullopt: none
};

struct Scene {
  CameraSettings camera;
  ViewportSettings viewport;
  GridSettings grid;
  TerrainSettings terrain;
  ShadingSettings shading = default_shading();
  LightingSettings lighting;
  WaterSettings water;
  SkySettings sky;
  double time = 0.0;  // seconds: animates the water's wave normal map
  OutputSettings output;

  static ShadingSettings default_shading();
};

}  // namespace relief
