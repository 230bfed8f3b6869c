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
// Loaded proto-textures: square powers of two (the mip chain halves them exactly).
inline constexpr int kMinTextureSize = 4;
inline constexpr int kMaxTextureSize = 4096;

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

}  // namespace relief::limits
