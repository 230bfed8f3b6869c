// Every tunable limit and numeric guard of Relief, each with the reason for its value.
// Scene validation quotes these ranges in its messages, so a limit changes in one place.
#pragma once

#include <cstddef>
#include <cstdint>

namespace relief::limits {

// --- Buffers -------------------------------------------------------------------------------

// Grid rows are padded to a multiple of this many floats (64 bytes): the widest vector
// (AVX-512, 16 lanes) can always load a whole vector, and rows start on a cache line.
inline constexpr int kRowAlignFloats = 16;
inline constexpr std::size_t kBufferAlignBytes = 64;

// --- Viewport and grid ---------------------------------------------------------------------

// 16384 is the largest framebuffer side current GL implementations guarantee
// (GL_MAX_VIEWPORT_DIMS on desktop GPUs): OpenGL must be able to draw the same frame.
inline constexpr int kMaxViewportSide = 16384;
// A grid needs at least one cell; 8192 vertices a side is 64 Mi vertices, far beyond the
// paper's 512 x 512 and still addressable with 32-bit vertex indices.
inline constexpr int kMinGridSide = 2;
inline constexpr int kMaxGridSide = 8192;
// Extra rows/columns of cells projected past the covered region (stage 1 margin).
inline constexpr int kMaxGridMargin = 64;

// --- Input files and values ---------------------------------------------------------------

// The deepest legitimate scene value is 4 levels (shading.layers[k].height[0]); 16 leaves room
// and keeps every recursive walk of a parsed value shallow.
inline constexpr int kMaxJsonDepth = 16;
// A complete scene with eight layers is about 5 KiB; a file 3000 times larger is a mistake (or
// /dev/zero behind a .json name), and the DOM of a JSON text takes about 10x its size.
inline constexpr std::uintmax_t kMaxSceneFileBytes = 16u << 20;
// Paths and names: PATH_MAX on Linux.
inline constexpr std::size_t kMaxStringBytes = 4096;
// A PNG of the largest texture (4096^2 RGBA, 8 bits) stored without compression is 64 MiB plus
// 1 filter byte a row and 5 bytes of zlib framing per 64 KiB: under 65 MiB. A larger file
// cannot be a texture Relief accepts.
inline constexpr std::uintmax_t kMaxTextureFileBytes = 65u << 20;
// A triangle-soup line holds at most 12 numbers; 4096 bytes is ten times what they need.
inline constexpr std::size_t kMaxSoupLineBytes = 4096;
// A parsed triangle takes 60 bytes (3 vertices of 4 floats, 3 indices) and its text at least
// 18 ("0 0 0 0 0 0 0 0 0\n"): a 1 GiB soup may take 3.4 GiB parsed, and still has 32-bit
// vertex indices to spare.
inline constexpr std::uintmax_t kMaxSoupFileBytes = 1u << 30;

// --- Camera --------------------------------------------------------------------------------

// Beyond 1e12 a double position resolves only ~1e-4 units, coarser than any octave a
// renderer would show; the design asks for accuracy up to 1e9.
inline constexpr double kMaxCameraCoordinate = 1e12;
// The projected grid needs a finite frustum; at 170 degrees tan(fov/2) is already 11.4.
inline constexpr double kMinFovDeg = 1.0;
inline constexpr double kMaxFovDeg = 170.0;
inline constexpr double kMaxHorizontalFovDeg = 175.0;
inline constexpr double kMaxViewDistance = 1e9;

// --- Planets (§4.1, docs/planet.md) ----------------------------------------------------------

// Below 1e3 units a planet is smaller than a default mountain range; above 1e8 the arc offsets
// (up to pi R) leave the lattice coordinates float resolves at the default horizontal scale.
inline constexpr double kMinPlanetRadius = 1e3;
inline constexpr double kMaxPlanetRadius = 1e8;
// The artificial horizon (an arc length) and the equal-angle band's altitudes.
inline constexpr double kMaxPlanetLength = 1e9;
// The largest central angle a grid vertex may take: the azimuthal equidistant map is singular
// at the antipode (pi), and a terrain this far round is never seen past the limb.
inline constexpr double kMaxPlanetAngle = 0.95 * 3.14159265358979323846;

// --- Terrain -------------------------------------------------------------------------------

// Lattice sides are powers of two so that the periodic wrap is a bit mask in every path
// (scalar now; the same in the SIMD and GLSL ports to come). 4096^2 floats is 64 MiB, a sensible
// upper bound for a noise tile.
inline constexpr int kMinLatticeSize = 4;
inline constexpr int kMaxLatticeSize = 4096;
// Octave tables are fixed-size arrays; 24 octaves at r = 2 span 1:16.7 million in feature
// size, more than float camera-relative coordinates can resolve anyway.
inline constexpr int kMaxOctaves = 24;
inline constexpr int kMaxFirstOctave = 32;
// r <= 1 would not be a lacunarity (frequencies must grow); above 16 consecutive octaves
// no longer overlap in frequency and the LOD blend of one octave becomes a visible pop.
inline constexpr double kMaxLacunarity = 16.0;
// H = 3 - D for a surface of fractal dimension D in [2, 3): H in (0, 1].
inline constexpr double kMaxHurst = 1.0;
inline constexpr double kMaxLodBias = 8.0;
inline constexpr double kMaxHorizontalScale = 1e9;
inline constexpr double kMaxAmplitude = 1e7;
inline constexpr double kMaxBaseHeight = 1e7;
inline constexpr double kMaxWarpComponent = 100.0;

// --- Shading ---------------------------------------------------------------------------------

// Material layers are blended per pixel; 8 is more than any of the seeds uses (Scape: 4) and
// keeps the per-pixel weight arrays on the stack.
inline constexpr std::size_t kMaxMaterialLayers = 8;
// shading.gradient.stops: castledragmire's four bands with a shading direction each take 8
// stops; 16 leave room for finer ramps and keep the per-frame parameter arrays small.
inline constexpr std::size_t kMinGradientStops = 2;
inline constexpr std::size_t kMaxGradientStops = 16;
// Loaded proto-textures: square powers of two (the mip chain halves them exactly).
inline constexpr int kMinTextureSize = 4;
inline constexpr int kMaxTextureSize = 4096;
// A skybox's faces (sky.skybox): squares like the textures', at most 2048 a side: six faces of
// float RGB are then 288 MiB (a 4096 side would be 1.1 GiB for the background alone).
inline constexpr int kMaxSkyboxSize = 2048;
// §3's height sketch (terrain.sketch): at least 2 texels a side (the interpolation blends two),
// at most 4096 (64 MiB of float heights; a sketch is the coarse part of the terrain, the
// fractal the detail). Its file obeys kMaxTextureFileBytes (a 4096^2 16-bit grey PNG stored
// uncompressed is 32 MiB and change).
inline constexpr int kMinSketchSize = 2;
inline constexpr int kMaxSketchSize = 4096;
// Its extent's coordinates lie within the camera's range, and a side spans at least 1e-3 units:
// then the per-frame texel offset, (camera - x0) x texels / side <= 2e12 x 16385 / 1e-3 =
// 3.3e19 (a height field's largest side; a sketch's 4096 gives 8e18), and its float rounding
// stay finite (docs/scene-limits.md).
inline constexpr double kMinSketchSpan = 1e-3;
// A height field (terrain.heightfield): 2 to 16385 samples a side (2^14 + 1, the largest
// `relief generate` map), 1 GiB of float heights at most; the job's memory estimate counts it
// before anything is read. Its file: a 16385^2 16-bit PNG stored uncompressed is 16385 rows of
// 2 x 16385 + 1 bytes, 537 MB, plus zlib's and the chunks' framing (under 1 MB); a PFM is
// 4 bytes a sample plus a header line or three.
inline constexpr int kMaxHeightFieldSize = 16385;
inline constexpr std::uintmax_t kMaxHeightFieldFileBytes = 1025u << 20;
// A height field's levels of detail (core/height_sketch.h): level l + 1 has floor(n / 2) + 1
// samples a side where level l has n, so 16385 samples take 15 levels (to 2 a side).
inline constexpr int kMaxFieldLevels = 16;
// GeoMipMapping's tau (terrain.heightfield.geomipmap.pixel_error): from a hundredth of a pixel,
// below anything a rasteriser resolves, to 1000 pixels, coarser than any viewport (every tile
// then takes its coarsest level); a field's lattice is at most kMaxHeightFieldSize + 255
// vertices a side (whole tiles of 256 cells), within geomipmap::kMaxLatticeSide.
inline constexpr double kMinGeoMipMapPixelError = 0.01;
inline constexpr double kMaxGeoMipMapPixelError = 1000.0;
// Every level's samples together (under 4/3 of level 0's and a few rows) index as int32 in the
// kernels (SketchParams::level_offset, the gathers' lanes).
static_assert(4.0 / 3.0 * kMaxHeightFieldSize * kMaxHeightFieldSize +
                      16.0 * 2 * kMaxHeightFieldSize <
                  2147483647.0,
              "a height field's levels must index as int32");
// §3 Eq. 2's basis images (terrain.basis): 1 to 4 images, each of one side P, a power of two
// in the lattice's range (kMinLatticeSize..kMaxLatticeSize, after mirroring too), since the
// composed grid takes the lattice's place in stage 3. tile_size / P is the octave-0 cell, so
// the tile spans kMinHorizontalScale x 4 <= tile_size <= kMaxHorizontalScale x 4096 would
// do; the range is rounded inwards to powers of ten. Constant weights up to 1e6 (only their
// ratios matter; a bound keeps their double sum exact enough). Filter sigmas at most half
// the image's side (a wider Gaussian is the mean alone, to float precision).
inline constexpr int kMaxBasisImages = 4;
inline constexpr int kMaxBasisUpsample = 8;  // terrain.basis.upsample: 1, 2, 4 or 8
inline constexpr double kMinBasisTileSize = 1e-11;
inline constexpr double kMaxBasisTileSize = 1e9;
inline constexpr double kMaxBasisWeight = 1e6;
// The least non-zero constant weight: Eq. 2's products w I and their sums stay far from double's
// subnormals (a weight of 5e-324 made w I round to 0 or to w, and the composed grid garbage),
// and the weights' ratio (at most 1e12) far from its precision.
inline constexpr double kMinBasisWeight = 1e-6;
inline constexpr double kMaxBasisSigma = kMaxLatticeSize / 2;
// The seam measure (core/basis_images.h) above which a repeating image is said not to tile:
// the steps across its wrap twice as large (RMS) as the steps between neighbours inside it.
inline constexpr double kMaxBasisSeam = 2.0;

// --- Scene fields: ranges that keep the float pipeline meaningful --------------------------
//
// Every numeric scene field has a range; docs/scene-limits.md derives each bound from the
// stage and formula that breaks outside it, and docs/scene-reference.md quotes them.
// Derived values are rounded to the safe side (to a power of ten unless said otherwise).

// The float that every per-vertex and per-pixel quantity is stored in.
inline constexpr double kFloatMax = 3.4028234663852886e38;         // FLT_MAX
inline constexpr double kFloatMinNormal = 1.1754943508222875e-38;  // FLT_MIN = 2^-126

// The largest camera-relative distance of a vertex or a covered pixel, the yardstick of the
// bounds below. Footprints end at kMaxFootprintFactor x far x sqrt(1 + tan^2(87.5 deg) +
// tan^2(85 deg)) = 2 x 25.6 x 1e9 = 5.1e10 (the frustum's far corners, projector.cc); heights
// lie at most 25.6 x far beyond the near side of the height slab, which lies within
// +-(kMaxBaseHeight + kMaxAmplitude x 24 octaves x 12, the largest lattice value the polar
// method can draw) = +-2.9e9. So |p| <= 6e10 < 1e11.
inline constexpr double kMaxCameraRelativeDistance = 1e11;

// Angles: a full turn either way (sin and cos are taken in double: any value works).
inline constexpr double kMaxTurnDeg = 360.0;
// Pitch and sun elevation: beyond +-90 degrees the view would be upside down, which a camera
// without roll cannot express.
inline constexpr double kMaxElevationDeg = 90.0;

// camera.near: the projected grid's footprints are camera-relative floats, compared by their
// squares with the squared footprint radius max_distance_sq (projector.cc). That radius is
// twice the farthest corner of the frustum-slab polytope, at least the near-plane corner of the
// narrowest frustum (1 degree) seen straight down: tan(0.5 deg) near = 0.0087 near to the side.
// (2 x 0.0087 near)^2 stays a normal float for near >= 6.2e-18, rounded up to 1e-17; below it
// the radius underflows and every vertex is dropped (an empty image). Depth near / w (reverse
// Z) then stays a normal float, with its full 24 bits, for every w up to
// kMaxCameraRelativeDistance (near / w >= 1e-28 > FLT_MIN), so no ratio rule between near and
// far is needed. camera.far must exceed near, so it has the same lower bound.
inline constexpr double kMinNearDistance = 1e-17;

// terrain.r and terrain.H: stage 2's octave count nu = c0 - c1 log2(sigma^2) (frame_plan.cc)
// is evaluated in float, with |log2 sigma^2| < 100 (sigma^2 between kMinSpacingSq and
// kMaxCameraRelativeDistance^2). Where nu is in range the two terms nearly cancel, so its
// error is about c1 x 100 x 2^-24. Its fraction is the geomorphing weight of the last octave
// (§4.1); to keep that exact to one 8-bit step, 1/256, c1 <= 2^16 / 100 = 655. kMaxLodGain is the
// power of two below (measured: nu within 1/512 of exact at c1 = 512, 1/128 at 2048). The
// Nyquist rule has c1 = 0.5 / log2 r: r >= 2^(1/1024) = 1.00068, rounded up to 1.001. The
// amplitude rule has c1 = 0.5 / (H log2 r): H log2 r >= 2^-10 (validate_scene), which at the
// largest lacunarity (log2 16 = 4) allows H >= 2^-12 = 2.44e-4 per field, rounded up to 2.5e-4;
// at r = 2 the rule asks for H >= 2^-10. Below these, c1 grows without bound: at H = 1e-300 it
// overflows float and nu becomes NaN.
inline constexpr double kMaxLodGain = 512.0;
inline constexpr double kMinLacunarity = 1.001;
inline constexpr double kMinHurst = 0.00025;

// Lattice coordinates (terrain octaves, the dithering noise) are formed in float as
// offset (< P) + frequency x d / scale. Their rounding error is ulp(d) world units whatever
// their magnitude (they are scaled camera-relative distances), so size alone costs no accuracy;
// what breaks is integer resolution. Below 2^24 float still holds every integer, so the
// periodic wrap (interpolant.h) visits every cell; beyond it only every 2nd, 4th, ... cell, and
// from 2^24 P on a single one: the noise turns into a constant (a flat terrain, a fixed shift of
// the layer transitions). validate_scene keeps the coordinate of the farthest footprint below
// this for the coarsest terrain octave and for the dithering noise.
inline constexpr double kMaxLatticeCoordinate = 16777216.0;  // 2^24
// terrain.horizontal_scale, per field: the finest frequency (r^k <= 2^40, validate_scene) times
// kMaxCameraRelativeDistance over the scale must stay finite: 2^40 x 1e11 / FLT_MAX = 3.2e-16,
// rounded up to 1e-15. The bound that matters is the one across fields above.
inline constexpr double kMinHorizontalScale = 1e-15;
// terrain.amplitude: heights are amplitude x h in float, h the dimensionless sum of Eq. 1 whose
// smallest octave weight is r^(-kH) >= 2^-40; amplitude x 2^-40 stays a normal float for
// amplitude >= 2^-86 = 1.3e-26, rounded up to 1e-25.
inline constexpr double kMinAmplitude = 1e-25;

// shading.layers[k].tile_size: GL's LOD squares the texture-coordinate derivative in texels,
// (du/dx n)^2 with du/dx = d(world)/dx / tile_size and n <= kMaxTextureSize (proto_texture.cc).
// For footprint derivatives up to kMaxCameraRelativeDistance each square must stay below
// FLT_MAX / 2: tile_size >= 4096 x 1e11 / 1.3e19 = 3.1e-5, rounded up to 1e-4. (Finer tiles
// are minified to the texture's mean anyway: a texel of 2.4e-8 units.)
inline constexpr double kMinTileSize = 1e-4;
inline constexpr double kMaxTileSize = 1e6;
// World lengths whose inverse scales camera-relative positions in stage 8: shading.dither_scale
// (dithering noise coordinate), water.wave_length (the wave fade 2 footprint x 5.1 /
// wave_length for the shortest of the three octaves) and water.full_depth (depth / full_depth).
// The products must stay finite for lengths up to kMaxCameraRelativeDistance: 2 x 5.1 x 1e11 /
// FLT_MAX = 3e-27, rounded up to 1e-26.
inline constexpr double kMinInverseScaleLength = 1e-26;
inline constexpr double kMaxShadingLength = 1e6;
inline constexpr double kMaxDither = 4.0;  // spreads: 0.5 x 4 x 12 = 24 spreads at most

// Layer ranges: heights within the base-height range; spreads up to kMaxShadingLength world
// units (or 45 degrees: a ramp from the flat to the vertical); angles in [0, 90] degrees.
inline constexpr double kMaxSlopeDeg = 90.0;
inline constexpr double kMaxSlopeSpreadDeg = 45.0;
// Built-in textures: a power of two from 16 (four mip levels at least) to 2048 texels a side.
inline constexpr int kMinBuiltinTextureSize = 16;
inline constexpr int kMaxBuiltinTextureSize = 2048;

// Colours and intensities: linear radiance stays below 2.1e7 (the sun disc, 20 x sun colour x
// sun intensity, plus the sky) and below 2.1e10 after the exposure: far inside float.
inline constexpr double kMaxRadiance = 1000.0;
inline constexpr double kMaxExposure = 1000.0;
// lighting.exposure: the largest radiance any scene can produce is 2.1e7; a byte of the sRGB PNG
// is non-zero from linear 0.5 / (255 x 12.92) = 1.5e-4. Below 1.5e-4 / 2.1e7 = 7.2e-12 every
// PNG is black: the bound is 1e-11.
inline constexpr double kMinExposure = 1e-11;
// Phong exponent: exp2(shininess log2 r.v) is clamped by exp2_det's domain, never 0 or inf.
inline constexpr double kMinShininess = 1.0;
inline constexpr double kMaxShininess = 10000.0;

// Water: extinction up to 100 per unit (exp2 clamps to 2^-125, never 0); wave slope up to 10
// (normals stay finite: the lattice gradient is at most 1.875 x 24 per octave); wave speed in
// double.
inline constexpr double kMaxExtinction = 100.0;
inline constexpr double kMaxWaveStrength = 10.0;
inline constexpr double kMaxWaveSpeed = 1e6;

// sky.sun_disc_deg: the disc's edge is a smooth step between cos(theta) and cos(1.25 theta),
// evaluated in float next to 1, where float's spacing is 2^-24. The step needs at least 16 of
// those spacings (4 bits): 0.28 theta^2 >= 2^-20 gives theta >= 1.84e-3 rad = 0.1055 degrees,
// rounded up to 0.11. A smaller disc would be a step (or no disc at all) from rounding alone.
inline constexpr double kMinSunDiscDeg = 0.11;
inline constexpr double kMaxSunDiscDeg = 10.0;
// lighting.shadow_resolution (core/sun_horizons.h): a cache sample spans about
// 1 / ((N / 2 - 2) x pixel angle) pixels at every distance, about 7 at N = 256 for 1024 rows
// and a 60-degree field; below 128 (about 14 pixels) the shadows blur into a darkening the
// ground truth does not have (at 32 they looked like none at all). At most 1024: 24 levels of
// 1024^2 samples hold 3 values each, 288 MiB in float, 576 MiB in double.
inline constexpr int kMinShadowResolution = 128;
inline constexpr int kMaxShadowResolution = 1024;
// Fog per world unit: exp2_det clamps its argument, so any density is total; 1 per unit is
// already opaque fog one unit from the camera.
inline constexpr double kMaxFogDensity = 1.0;
// sky.atmosphere (core/atmosphere.h). Scattering per world unit: any value at most 1e-2 keeps
// every optical depth finite in float (they are capped at kMaxOpticalDepth, 1e20, where the
// transmittance of any coefficient from 1e-18 up is exp(-100) already). The scale height from
// 10 units (the camera's height is divided by it in double, the density at the camera capped
// at e^40) to 1e6. The haze's g at most 0.95: its phase function's denominator
// 1 + g^2 - 2 g cos stays at least (1 - g)^2 = 0.0025.
inline constexpr double kMaxScattering = 1e-2;
inline constexpr double kMinScaleHeight = 10.0;
inline constexpr double kMaxScaleHeight = 1e6;
inline constexpr double kMaxMieG = 0.95;
// sky.clouds (core/clouds.h). Octaves up to 8: the finest is 128 times the largest, and a cell
// of the largest spans at least one world unit, so a lattice coordinate stays below
// 128 x kMaxCameraRelativeDistance = 1.3e13, finite in float (its cell is then lost to
// rounding, but such a point lies far beyond any pixel's footprint, where the octaves fade:
// core/clouds.h). The layer at least 0.01 units thick: thinner, it is no band to hold cloud.
// The warp up to 16 cells of the largest octave.
inline constexpr int kMaxCloudOctaves = 8;
inline constexpr double kMinCloudScale = 1.0;
inline constexpr double kMinCloudThickness = 0.01;
inline constexpr double kMaxCloudWarp = 16.0;
// The ground truth's points per cloud path (pipeline/frame.h, FrameRequest::cloud_steps).
inline constexpr int kMaxCloudSteps = 256;

// time, seconds: the wave offsets (camera + speed x time) / wave_length are reduced in double.
inline constexpr double kMaxTime = 1e9;

// --- Numeric guards (each division or log in a stage names the guard it uses) -------------

// §2.2 divides by the roughness R_i, which crosses zero wherever the partial height reaches
// R0. Relief replaces 1/R by R/(R^2 + eps^2): continuous through R = 0, bounded by 1/(2 eps),
// and within eps^2/R^2 of 1/R (8% at R = R0 = 2^0.8). Its slope at R = 0 is 1/eps^2, and that
// gain feeds back into every later octave: eps = 1/8 made the lava preset chaotic (float and
// double heights 88 units apart on 1400 units of relief), eps = 1/2 keeps the median float
// error at the plain terrain's and the 99th percentile at 0.07 units (docs/paper-reading.md).
inline constexpr double kRoughnessGuard = 0.5;
// The rotation vector of §2.2 is renormalised after each octave; below this squared length
// the direction is undefined and the previous rotation is kept.
inline constexpr double kMinRotationLengthSq = 1e-12;
// Relative slack on the fBm amplitude bound: interpolation a + w (b - a) may round one ulp
// past the convex hull of the lattice values; float adds about 2^-24 per operation.
inline constexpr double kHeightBoundSlack = 1e-5;
// Grid rays whose descent is below this fraction of their length are treated as parallel
// to the base plane: they would hit it beyond any view distance Relief accepts.
inline constexpr double kMinRayDescent = 1e-7;
// Vertices whose footprint lies further than this multiple of the farthest visible
// footprint are marked invalid: they only exist because the range box is a rectangle.
inline constexpr double kMaxFootprintFactor = 2.0;
// Below this squared spacing (world units^2) the LOD log is not taken: the vertex gets
// the full octave count. FLT_MIN-sized spacings only occur for degenerate projections.
inline constexpr double kMinSpacingSq = 1e-30;
// The surface pass solves a 2x2 system whose determinant is the base-plane area spanned by
// the neighbour differences; below this fraction of |a||b| the cell is degenerate and the
// gradient is taken as zero.
inline constexpr double kMinTangentSine = 1e-6;
// Slope |grad h| is reported up to 1e6 (89.99994 degrees): steeper cells are vertical walls
// for every consumer, and the cap keeps |g| finite for cells of vanishing base-plane area.
inline constexpr double kMaxSlope = 1e6;
// A side of a vertex whose patch faces the eye less than this (the cosine between its upward
// normal and the direction to the eye) weighs less in the vertex's difference, in proportion,
// down to kHiddenSideWeight once hidden (core/surface.h, "Visible sides"). 1 / 4: the
// weight is one exact product.
inline constexpr double kSilhouetteFacing = 0.25;
// The least weight of a side (core/surface.h, "Visible sides"): a hidden side keeps this
// share, so a vertex hidden from both sides gets the central difference, continuously.
inline constexpr double kHiddenSideWeight = 1.0 / 32;

}  // namespace relief::limits
