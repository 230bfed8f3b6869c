#include "pipeline/tile_reflections.h"

#include <algorithm>

namespace relief {

template <class Real>
void tile_water_reflections(const TileShadows<Real>& shadows, const ShadeParams<Real>& shade,
                            const ShadeResources& resources, bool highway_shade,
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
  for (int py = vis.y0; py < vis.y0 + vis.height; ++py) {
    for (int px = vis.x0; px < vis.x0 + vis.width; ++px) {
      const std::size_t k = vis.index(px, py);
      Vec3<Real> radiance{0, 0, 0};
      Real weight = 0;
      // The water test of the shade (core/shade.cc): ground below the level; its view ray
      // descends there (level < 0), which reflected_terrain checks again.
      if (vis.primitive[k] != raster::kNoPrimitive && a.height[k] < level) {
        weight = reflected_terrain(scene, a.dx[k], a.height[k], a.dz[k], a.water_depth[k], radiance,
                                   work, shade_work);
      }
      a.reflection_r[k] = radiance.x;
      a.reflection_g[k] = radiance.y;
      a.reflection_b[k] = radiance.z;
      a.reflection_weight[k] = weight;
    }
  }
}

template void tile_water_reflections<float>(const TileShadows<float>&, const ShadeParams<float>&,
                                            const ShadeResources&, bool,
                                            const raster::TileVisibility&, TileAttributes<float>&,
                                            ReflectionWork&, ShadeWork&);
template void tile_water_reflections<double>(const TileShadows<double>&, const ShadeParams<double>&,
                                             const ShadeResources&, bool,
                                             const raster::TileVisibility&, TileAttributes<double>&,
                                             ReflectionWork&, ShadeWork&);

}  // namespace relief
