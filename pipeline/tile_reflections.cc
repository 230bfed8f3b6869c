#include "pipeline/tile_reflections.h"

#include <algorithm>
#include <type_traits>

#include "simd/reflection_rays.h"

namespace relief {

template <class Real>
void tile_water_reflections(const TileShadows<Real>& shadows, const ShadeParams<Real>& shade,
                            const ShadeResources& resources, KernelKind kind, bool highway_shade,
                            const raster::TileVisibility& vis, TileAttributes<Real>& a,
                            ReflectionWork& work, ShadeWork& shade_work) {
  if (!shade.water_enabled || !shade.terrain_water) {
    return;  // no pixel has water in front
  }
  constexpr std::size_t kPixels = TileAttributes<Real>::kPixels;
  if (shadows.reflections == nullptr || shade.terrain_reflections == 0) {
    if (!highway_shade) {  // the portable shade reads them at every pixel with water
      for (Real* field : {a.reflection_r, a.reflection_g, a.reflection_b, a.reflection_weight}) {
        std::fill(field, field + kPixels, Real(0));
      }
    }
    return;
  }
  // The sun's and the sky's shares at the hits from the reflections' levels too.
  const ShadowParams<Real>* levels = shadows.reflections;
  const ReflectionScene<Real> scene{&shade,
                                    resources,
                                    levels,
                                    shadows.cache,
                                    shadows.maxima,
                                    shadows.params != nullptr ? levels : nullptr,
                                    shadows.sky != nullptr ? levels : nullptr};
  const Real level = shade.water_level;
  constexpr int kRow = raster::kTileSize;
  for (int py = vis.y0; py < vis.y0 + vis.height; ++py) {
    const std::size_t row = vis.index(vis.x0, py);
    // The rays of the row's pixels with water in front (the water test of core/shade.cc:
    // ground below the level; its view ray descends there, which the set-up checks again).
    ReflectionRay<Real> rays[kRow];
    bool highway = false;
    if constexpr (std::is_same_v<Real, float>) {
      if (kind == KernelKind::kHighway) {
        float sx[kRow], sz[kRow], surface[kRow], rx[kRow], ry[kRow], rz[kRow], weight[kRow];
        simd::reflection_rays(shade, *resources.lattice, vis.primitive + row, a.dx + row,
                              a.height + row, a.dz + row, a.water_depth + row, vis.width,
                              simd::ReflectionRayRow{sx, sz, surface, rx, ry, rz, weight});
        for (int i = 0; i < vis.width; ++i) {
          rays[i] = ReflectionRay<float>{
              {sx[i], level, sz[i]}, {rx[i], ry[i], rz[i]}, surface[i], weight[i]};
        }
        highway = true;
      }
    }
    for (int i = 0; !highway && i < vis.width; ++i) {
      const std::size_t k = row + std::size_t(i);
      if (vis.primitive[k] != raster::kNoPrimitive && a.height[k] < level) {
        rays[i] = reflection_ray(shade, *resources.lattice, a.dx[k], a.height[k], a.dz[k],
                                 a.water_depth[k]);
      }
    }
    for (int i = 0; i < vis.width; ++i) {
      const std::size_t k = row + std::size_t(i);
      Vec3<Real> radiance{0, 0, 0};
      Real weight = 0;
      if (vis.primitive[k] != raster::kNoPrimitive && a.height[k] < level) {
        weight = reflected_terrain(scene, rays[i], radiance, work, shade_work);
      }
      a.reflection_r[k] = radiance.x;
      a.reflection_g[k] = radiance.y;
      a.reflection_b[k] = radiance.z;
      a.reflection_weight[k] = weight;
    }
  }
}

template void tile_water_reflections<float>(const TileShadows<float>&, const ShadeParams<float>&,
                                            const ShadeResources&, KernelKind, bool,
                                            const raster::TileVisibility&, TileAttributes<float>&,
                                            ReflectionWork&, ShadeWork&);
template void tile_water_reflections<double>(const TileShadows<double>&, const ShadeParams<double>&,
                                             const ShadeResources&, KernelKind, bool,
                                             const raster::TileVisibility&, TileAttributes<double>&,
                                             ReflectionWork&, ShadeWork&);

}  // namespace relief
