// The portable half of the kernel table (cpu_kernels.h): the loops of core/ and raster/ in the
// backend's precision. It is the whole table of the reference backends and the fallback of
// each simd entry that has no Highway kernel.
#include <string_view>
#include <type_traits>

#include "core/height_sketch.h"
#include "core/planet_bend.h"
#include "core/planet_domain.h"
#include "core/projected_domain.h"
#include "core/vertex_culling.h"
#include "pipeline/cpu_kernels.h"

namespace relief {

template <class Real>
CpuKernels<Real> portable_kernels(bool planet) {
  CpuKernels<Real> k;
  k.project_domain = &project_domain<Real>;
  k.project_planet_domain = &project_planet_domain<Real>;
  k.vertex_outcodes = &vertex_outcodes<Real>;
  k.fractal = &evaluate_fbm<Real>;
  k.sketch = &add_sketch<Real>;
  k.bend_vertices = &bend_vertices<Real>;
  k.bend_normals = &bend_normals<Real>;
  k.surface = &surface_pass<Real>;
  k.transform = &transform_vertices<Real>;
  k.light_vertices = &light_vertices<Real>;
  k.snap = nullptr;
  k.tiles = TileKernels{};
  const KernelKind p = KernelKind::kPortable;
  k.choices = {
      {StageId::kProjectedDomain, planet ? "planet domain" : "projected domain", p, ""},
      {StageId::kOutcodes, "vertex outcodes", p, ""},
      {StageId::kFractal, "fBm", p, ""},
      {StageId::kFractal, "sketch", p, ""},
      {StageId::kDrawOutcodes, "vertex outcodes", p, ""},
      {StageId::kSurface, "surface", p, ""},
      {StageId::kShadowHeights, "fBm", p, ""},
      {StageId::kShadowHeights, "sketch", p, ""},
      {StageId::kSunHorizons, "hull sweep", p, ""},
      {StageId::kSkyHorizons, "hull sweep", p, ""},
      {StageId::kVertexTransform, "vertex transform", p, ""},
      {StageId::kVertexTransform, "vertex lighting", p, ""},
      {StageId::kTriangleSetup, "vertex snap", p, ""},
      {StageId::kTriangleSetup, "clip and edge set-up", p, ""},
      {StageId::kBinning, "binning", p, ""},
      {StageId::kTiles, "tile raster", p, ""},
      {StageId::kTiles, "tile resolve", p, ""},
      {StageId::kTiles, "sun's share", p, ""},
      {StageId::kTiles, "sky's share", p, ""},
      {StageId::kTiles, "reflected rays' set-up", p, ""},
      {StageId::kTiles, "reflected rays' march", p, ""},
      {StageId::kTiles, "tile shade", p, ""},
      {StageId::kTiles, "tile encode", p, ""},
  };
  if (planet) {  // docs/planet.md: the bend after stage 3, the normals' rotation after stage 4
    // No cast shadows, sky light or reflections on a planet (the scene refuses them): their
    // entries go.
    std::erase_if(k.choices, [](const KernelChoice& c) {
      return c.stage == StageId::kShadowHeights || c.stage == StageId::kSunHorizons ||
             c.stage == StageId::kSkyHorizons || std::string_view(c.kernel) == "sun's share" ||
             std::string_view(c.kernel) == "sky's share" ||
             std::string_view(c.kernel).starts_with("reflected rays");
    });
    k.choices.insert(k.choices.begin() + 4, {StageId::kFractal, "planet bend", p, ""});
    k.choices.insert(k.choices.begin() + 7, {StageId::kSurface, "planet normals", p, ""});
  }
  return k;
}

template CpuKernels<float> portable_kernels<float>(bool planet);
template CpuKernels<double> portable_kernels<double>(bool planet);

}  // namespace relief
