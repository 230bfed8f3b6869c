// Stage 8: proto-texture shading (docs/architecture.md; §4.2, §4.3 and the other seeds' additions),
// per pixel over rows of the image, from the resolved attributes of stage 7.
//
// Covered pixel: layer weights (layer_weights.h) from the height, the slope |grad h| and the
// dithering noise; each layer's proto-texture sampled trilinearly at the LOD of GL's formula
// from the quad derivatives of the world position, projected from above or, with triplanar
// on, from the three axes weighted by the squared normal (Mekala, Scape); lit by the sun
// (Lambert, optional Phong per layer), the hemispherical sky light and an ambient term
// (Scape); covered by water where it lies below the water level (water.h); then fogged by
// distance (sky.h). Uncovered pixel: the sky, or open water below the horizon. Result: linear
// radiance times the exposure.
#pragma once

#include <cstdint>
#include <span>

#include "core/grid_buffers.h"
#include "core/lattice.h"
#include "core/proto_texture.h"
#include "core/skybox.h"
#include "core/stage_params.h"
#include "core/vec3.h"

namespace relief {

// The scene's resources stage 8 samples: the noise lattice (dithering, waves) and one
// proto-texture per material layer, in the order of the scene's layers.
struct ShadeResources {
  const NoiseLattice* lattice = nullptr;
  std::span<const ProtoTexture> textures;
  const Skybox* skybox = nullptr;  // sky.skybox's faces; null without one
};

// What stage 8 reads at one covered pixel: the attributes stage 7 resolved there.
template <class Real>
struct PixelAttributes {
  Real dx, dz, height;  // camera-relative position (height: y)
  Real dx_ddx, dx_ddy, dz_ddx, dz_ddy, height_ddx, height_ddy;  // quad derivatives
  Real nx, ny, nz;                                              // normal (renormalised here)
  Real slope;                                                   // |grad h|
  Real water_depth;                                             // §4.3, interpolated
  Real drop;  // a planet's curvature drop below the height (planet_bend.h); 0 on the plane
  Real sun;   // the sun disc's visible share (sun_visibility.h); 1 without cast shadows
  Real sky;   // the sky's open share (sky_horizons.h); 1 without sky light
  // shading.mode = gradient: the vertices' Lambert terms interpolated (gradient_shade.h);
  // not read otherwise.
  Real lambert;
  // Where the view ray meets the water surface before this ground point: the sun disc's
  // visible share at that surface point (sun_visibility.h, water.h); 1 without cast shadows.
  // Read only there.
  Real water_sun;
  // There too, with water.reflect_terrain: the terrain the reflected ray meets, its radiance
  // and weight 1, or weight 0 where it escapes to the sky (water_reflection.h); read only
  // there, and weight 0 without reflections.
  Real reflection_r, reflection_g, reflection_b, reflection_weight;
};

// The work stage 8 did, counted per pixel (docs/stages.md, "Skipped work").
struct ShadeWork {
  std::uint64_t terrain_pixels = 0;     // covered pixels shaded as terrain
  std::uint64_t background_pixels = 0;  // sky, fog or open water
  std::uint64_t texture_fetches = 0;    // trilinear proto-texture samples
  std::uint64_t water_pixels = 0;       // pixels through the water pass
  std::uint64_t fogged_pixels = 0;      // pixels through the fog pass
  std::uint64_t dither_samples = 0;     // dithering noise lookups
  std::uint64_t specular_pixels = 0;    // pixels whose specular term was computed
  std::uint64_t facing_normals = 0;     // normals facing away from the eye, turned (shade.cc)
  std::uint64_t cloud_view_paths = 0;   // view rays through the cloud layer (clouds.h)
  std::uint64_t cloud_sun_paths = 0;    // points whose ray toward the sun crosses the layer
  std::uint64_t cloud_lookups = 0;      // the layer's lattice samples (octaves and warp)

  ShadeWork& operator+=(const ShadeWork& o) {
    terrain_pixels += o.terrain_pixels;
    background_pixels += o.background_pixels;
    texture_fetches += o.texture_fetches;
    water_pixels += o.water_pixels;
    fogged_pixels += o.fogged_pixels;
    dither_samples += o.dither_samples;
    specular_pixels += o.specular_pixels;
    facing_normals += o.facing_normals;
    cloud_view_paths += o.cloud_view_paths;
    cloud_sun_paths += o.cloud_sun_paths;
    cloud_lookups += o.cloud_lookups;
    return *this;
  }
};

// The normal the light sees (docs/stages.md, stage 8): the interpolated normal, or where it
// faces away from the eye (n . view > 0, `view` running from the eye to the pixel) its part
// perpendicular to the view ray, n - (n . view) view, normalised (-view where that part
// vanishes). A pixel on a crest's silhouette interpolates between the near slope's vertex
// normals and those of the hidden far slope; lit as the hidden slope it drew 1-px dark lines
// along ridges that the ground truth's finer grid hardly shows. Continuous in n: the
// perpendicular part of a normal that barely faces away is that normal.
// (Counted in work.facing_normals.) `n` and `view` unit vectors.
template <class Real>
Vec3<Real> facing_normal(const Vec3<Real>& n, const Vec3<Real>& view, ShadeWork& work);

// The terrain lit at camera-relative `position` (a's, less its drop), seen along unit `view`
// from `distance`: the sun (through the cloud layer's shadow), the sky and the ambient light,
// the layers' texture or the gradient; no water, fog or cloud in front (terrain_radiance adds
// those; the reflections, water_reflection.h, their own).
template <class Real>
Vec3<Real> lit_terrain(const ShadeParams<Real>& params, const ShadeResources& resources,
                       const PixelAttributes<Real>& a, const Vec3<Real>& position, Real distance,
                       const Vec3<Real>& view, ShadeWork& work);

// Radiance of a covered pixel, before the exposure; counts its work into `work`.
template <class Real>
Vec3<Real> terrain_radiance(const ShadeParams<Real>& params, const ShadeResources& resources,
                            const PixelAttributes<Real>& a, ShadeWork& work);

// Radiance of pixel (px, py) where no terrain covers it, before the exposure.
template <class Real>
Vec3<Real> background_radiance(const ShadeParams<Real>& params, const ShadeResources& resources,
                               int px, int py, ShadeWork& work);

// Per-pixel inputs of a whole image, row 0 the bottom; all spans width * height long.
struct ShadingInputs {
  std::span<const std::uint32_t> primitive;  // 0xffffffff where no terrain covers the pixel
  std::span<const float> dx, dz, height;     // camera-relative x, height (y), z
  std::span<const float> dx_ddx, dx_ddy, dz_ddx, dz_ddy, height_ddx, height_ddy;
  std::span<const float> nx, ny, nz;  // interpolated normal (renormalised here)
  std::span<const float> slope;
  std::span<const float> water_depth;     // interpolated per-vertex depth (§4.3)
  std::span<const float> drop = {};       // a planet's curvature drop; empty: 0 (the plane)
  std::span<const float> sun = {};        // the sun disc's visible share; empty: 1 (no shadows)
  std::span<const float> sky = {};        // the sky's open share; empty: 1 (no sky light)
  std::span<const float> lambert = {};    // gradient mode's interpolated Lambert term; empty: 0
  std::span<const float> water_sun = {};  // the sun's share at the water surface; empty: 1
  // The terrain reflected there (water_reflection.h); empty: none (weight 0).
  std::span<const float> reflection_r = {}, reflection_g = {}, reflection_b = {};
  std::span<const float> reflection_weight = {};

  template <class Real>
  PixelAttributes<Real> at(std::size_t k) const {
    return {Real(dx[k]),
            Real(dz[k]),
            Real(height[k]),
            Real(dx_ddx[k]),
            Real(dx_ddy[k]),
            Real(dz_ddx[k]),
            Real(dz_ddy[k]),
            Real(height_ddx[k]),
            Real(height_ddy[k]),
            Real(nx[k]),
            Real(ny[k]),
            Real(nz[k]),
            Real(slope[k]),
            Real(water_depth[k]),
            drop.empty() ? Real(0) : Real(drop[k]),
            sun.empty() ? Real(1) : Real(sun[k]),
            sky.empty() ? Real(1) : Real(sky[k]),
            lambert.empty() ? Real(0) : Real(lambert[k]),
            water_sun.empty() ? Real(1) : Real(water_sun[k]),
            reflection_weight.empty() ? Real(0) : Real(reflection_r[k]),
            reflection_weight.empty() ? Real(0) : Real(reflection_g[k]),
            reflection_weight.empty() ? Real(0) : Real(reflection_b[k]),
            reflection_weight.empty() ? Real(0) : Real(reflection_weight[k])};
  }
};

// Writes rows [rows.begin, rows.end) of `rgb` (3 values per pixel): radiance times the
// exposure. Output finite everywhere.
template <class Real>
void shade_pixels(const ShadeParams<Real>& params, const ShadeResources& resources,
                  const ShadingInputs& in, RowRange rows, std::span<Real> rgb);

}  // namespace relief
