#include "core/shade.h"

#include <algorithm>
#include <cmath>

#include "core/clouds.h"
#include "core/det_math.h"
#include "core/gradient_shade.h"
#include "core/interpolant.h"
#include "core/layer_weights.h"
#include "core/planet_shading.h"
#include "core/proto_texture.h"
#include "core/sky.h"
#include "core/vec3.h"
#include "core/water.h"

namespace relief {

namespace {

// Triplanar projections whose weight is below this are skipped (and the rest renormalised):
// at 1% the side projections of flat ground cost nothing and change nothing visible.
constexpr double kMinProjectionWeight = 0.01;
// Layers below this weight are not sampled (their weight goes to the others).
constexpr double kMinLayerWeight = 1e-3;

template <class Real>
Vec3<Real> sample(const ProtoTexture& t, bool nearest_mip, Real u, Real v, Real dudx, Real dvdx,
                  Real dudy, Real dvdy) {
  const int size = t.levels[0].size;
  float lod = texture_lod(size, float(dudx), float(dvdx), float(dudy), float(dvdy));
  if (nearest_mip) {
    lod = nearest_mip_lod(lod);
  }
  const Rgb c = sample_trilinear(t, float(u), float(v), lod);
  return {Real(c[0]), Real(c[1]), Real(c[2])};
}

// The layer's albedo at the pixel: planar from above, or triplanar.
template <class Real>
Vec3<Real> layer_albedo(const ShadeParams<Real>& p, const LayerParams<Real>& l,
                        const ProtoTexture& texture, const PixelAttributes<Real>& a,
                        const Vec3<Real>& n, ShadeWork& work) {
  const Real inv = l.inv_tile;
  const Real x = l.offset_x + a.dx * inv, z = l.offset_z + a.dz * inv;
  const Real y = l.offset_y + a.height * inv;
  const Real xdx = a.dx_ddx * inv, xdy = a.dx_ddy * inv;
  const Real zdx = a.dz_ddx * inv, zdy = a.dz_ddy * inv;
  const Real ydx = a.height_ddx * inv, ydy = a.height_ddy * inv;
  if (!p.triplanar) {
    ++work.texture_fetches;
    return sample<Real>(texture, p.nearest_mip != 0, x, z, xdx, zdx, xdy, zdy);
  }
  // Squared-normal weights (Mekala; Scape): they sum to one for a unit normal.
  Real w[3] = {n.x * n.x, n.y * n.y, n.z * n.z};
  Real used = Real(0);
  for (Real& weight : w) {
    weight = weight < Real(kMinProjectionWeight) ? Real(0) : weight;
    used = used + weight;
  }
  // A projection of weight zero adds zero: skipped (p.skip_zero_weights) it costs no fetch.
  const auto used_projection = [&](int axis) {
    const bool sampled = w[axis] > Real(0) || !p.skip_zero_weights;
    work.texture_fetches += sampled;
    return sampled;
  };
  Vec3<Real> sum{0, 0, 0};
  if (used_projection(0)) {
    sum = sum + sample<Real>(texture, p.nearest_mip != 0, z, y, zdx, ydx, zdy, ydy) * w[0];
  }
  if (used_projection(1)) {
    sum = sum + sample<Real>(texture, p.nearest_mip != 0, x, z, xdx, zdx, xdy, zdy) * w[1];
  }
  if (used_projection(2)) {
    sum = sum + sample<Real>(texture, p.nearest_mip != 0, x, y, xdx, ydx, xdy, ydy) * w[2];
  }
  return sum * (Real(1) / used);  // domain: used >= 1/3 - 2% for a unit normal
}

// Sun (Lambert, Phong) times the share of its disc the terrain leaves visible (`sun_share`,
// sun_visibility.h; 1 without cast shadows, which leaves every bit as it was), hemispherical
// sky light whose sky part is scaled by the sky the terrain leaves open (`sky_share`,
// sky_horizons.h: the hidden part sees the terrain, lit like the ground colour; 1 without sky
// light, every bit as it was), and ambient.
template <class Real>
Vec3<Real> light(const ShadeParams<Real>& p, const Vec3<Real>& albedo, const Vec3<Real>& n,
                 const Vec3<Real>& view, Real specular, Real sun_share, Real sky_share,
                 ShadeWork& work) {
  const Vec3<Real>& to_sun = p.sun_direction;
  const Vec3<Real>& sun = p.sun;
  const Real ndl = std::max(Real(0), dot(n, to_sun));
  const Real sunlit = ndl * sun_share;
  const Vec3<Real> hemisphere =
      mix(p.ground_light, p.sky_light, (Real(0.5) + Real(0.5) * n.y) * sky_share);
  const Real ambient = p.ambient;
  Vec3<Real> radiance =
      albedo * (sun * sunlit + hemisphere + Vec3<Real>{ambient, ambient, ambient});
  if ((specular > Real(0) || p.always_specular) && sunlit > Real(0)) {
    ++work.specular_pixels;
    const Vec3<Real> reflected = n * (Real(2) * ndl) - to_sun;
    const Real rv = -dot(reflected, view);
    if (rv > Real(0)) {  // log's domain
      radiance = radiance + sun * ((specular * sun_share) * exp2_det(p.shininess * log2_det(rv)));
    }
  }
  return radiance;
}

// The pixel's extent on the water surface at `distance` along unit `view`: the pixel's angle
// times the distance, stretched by the grazing incidence (|view.y| floored at 0.05 for the
// division's domain). Smooth across pixels, unlike the ground's per-triangle derivatives.
template <class Real>
Real surface_footprint(const ShadeParams<Real>& p, Real distance, const Vec3<Real>& view) {
  return distance * p.pixel_angle / std::max(std::abs(view.y), Real(0.05));
}

// Open water in the background (no ground in view below it: depth 1e6), `surface` along the
// view ray `d` (> 0), seen as `view` in the water's own frame (d itself on the plane; the
// local frame of the hit on a planet), then fogged along d.
template <class Real>
Vec3<Real> open_water(const ShadeParams<Real>& p, const ShadeResources& r, const Vec3<Real>& view,
                      const Vec3<Real>& d, Real surface, ShadeWork& work) {
  const Real footprint = surface_footprint(p, surface, view);
  // No cast shadow: the horizon cache ends with the terrain drawn (docs/stages.md, "Cast
  // shadows", "On the water").
  const Vec3<Real> zero{0, 0, 0};
  const Vec3<Real> open = shade_water(p, *r.lattice, r.skybox, view, surface, Real(1e6), zero,
                                      footprint, Real(1), zero, Real(0), work);
  ++work.water_pixels;
  if (!p.fog_enabled) {
    return open;
  }
  ++work.fogged_pixels;
  return apply_fog(p, open, d, surface);
}

// A planet's background (planet_shading.h): the water sphere, else the datum sphere's fog,
// else the sky. `ray`: the view ray in double, `d`: it normalised in Real.
template <class Real>
Vec3<Real> planet_background(const ShadeParams<Real>& p, const ShadeResources& r,
                             const double ray[3], const Vec3<Real>& d, ShadeWork& work) {
  const PlanetBackgroundRay<Real> hit =
      planet_background_ray<Real>(ray, p.water_enabled != 0, p.planet_center_distance,
                                  p.planet_water_c, p.planet_datum_c, p.planet_limb_angle);
  if (hit.kind == PlanetBackgroundKind::kWater) {
    return open_water(p, r, to_local_frame(d, hit.up), d, hit.surface, work);
  }
  if (hit.kind == PlanetBackgroundKind::kGround) {
    return fog_color(p, d);
  }
  return sky_radiance(p, r.skybox, hit.sky);
}

}  // namespace

template <class Real>
Vec3<Real> facing_normal(const Vec3<Real>& n, const Vec3<Real>& view, ShadeWork& work) {
  const Real away = dot(n, view);
  if (!(away > Real(0))) {
    return n;
  }
  ++work.facing_normals;
  return normalize_or(n - view * away, view * Real(-1));
}

namespace {

// §4.2's proto-texture shading of a covered pixel (shading.mode = textures): the layers'
// albedo, lit per pixel (Scape). `distance` and unit `view`: the pixel's from the camera.
template <class Real>
Vec3<Real> textured_radiance(const ShadeParams<Real>& p, const ShadeResources& r,
                             const PixelAttributes<Real>& a, Real distance, const Vec3<Real>& view,
                             ShadeWork& work) {
  const Real relative_y = a.height;  // camera-relative (stage 3)
  const Vec3<Real> n =
      normalize_or(Vec3<Real>{a.nx, a.ny, a.nz}, Vec3<Real>{Real(0), Real(1), Real(0)});

  // Scape's dithered transitions: the terrain's own noise lattice, its own scale. The noise
  // has no level of detail: where the pixel's footprint (distance x pixel angle) exceeds half a
  // noise cell it only aliases, so it fades out linearly until the footprint is a whole cell.
  // Sampled only nearer than that, its coordinates stay below 1 / pixel_angle < 2^20 cells,
  // exact in float for any dither_scale.
  Real dither_offset = Real(0);
  const Real inv = p.dither_inv_scale;
  const Real dither_fade = std::min(Real(1), Real(2) - Real(2) * distance * p.pixel_angle * inv);
  if (p.dither_enabled && dither_fade > Real(0)) {
    const Real noise = sample_lattice<Interpolant::kCubic>(
        *r.lattice, p.dither_offset_x + a.dx * inv, p.dither_offset_z + a.dz * inv);
    dither_offset = p.dither_half_amount * noise * dither_fade;
    ++work.dither_samples;
  }
  Real weights[limits::kMaxMaterialLayers];
  layer_weights(p, relative_y, a.slope, dither_offset, weights);
  Vec3<Real> albedo{0, 0, 0};
  Real specular = Real(0), used = Real(0);
  for (int layer = 0; layer < p.layer_count; ++layer) {
    // Below kMinLayerWeight a layer's weight is zero (its share goes to the others by the
    // renormalisation below), and a zero weight adds zero: skipped, it costs no fetch.
    if (weights[layer] < Real(kMinLayerWeight)) {
      weights[layer] = Real(0);
      if (p.skip_zero_weights) {
        continue;
      }
    }
    albedo =
        albedo + layer_albedo(p, p.layers[layer], r.textures[layer], a, n, work) * weights[layer];
    specular = specular + p.layers[layer].specular * weights[layer];
    used = used + weights[layer];
  }
  // Domain: the largest weight is >= 1/8 > kMinLayerWeight, so used > 0.
  albedo = albedo * (Real(1) / used);
  return light(p, albedo, facing_normal(n, view, work), view, specular / used, a.sun, a.sky, work);
}

}  // namespace

template <class Real>
Vec3<Real> lit_terrain(const ShadeParams<Real>& p, const ShadeResources& r,
                       const PixelAttributes<Real>& a, const Vec3<Real>& position, Real distance,
                       const Vec3<Real>& view, ShadeWork& work) {
  // The cloud layer's shadow (clouds.h): the sun's share passed through it, at the pixel's
  // footprint.
  PixelAttributes<Real> lit = a;
  if (p.clouds) {
    lit.sun = a.sun * cloud_sun_share(p, *r.lattice, position, distance * p.pixel_angle, work);
  }
  return p.gradient_enabled
             ? gouraud_light(p, gradient_albedo(p, a.height), lit.lambert, lit.ny, lit.sun, lit.sky)
             : textured_radiance(p, r, lit, distance, view, work);
}

template <class Real>
Vec3<Real> terrain_radiance(const ShadeParams<Real>& p, const ShadeResources& r,
                            const PixelAttributes<Real>& a, ShadeWork& work) {
  ++work.terrain_pixels;
  const Real relative_y = a.height;  // camera-relative (stage 3)
  // On a planet the position is the bent one: (dx, dz) hold it, and the height lies a.drop
  // above it (x - 0 is x: the plane's bits are unchanged).
  const Vec3<Real> position{a.dx, relative_y - a.drop, a.dz};
  const Real distance = std::sqrt(dot(position, position));
  const Vec3<Real> view = normalize_or(position, p.camera_forward);
  Vec3<Real> radiance = lit_terrain(p, r, a, position, distance, view, work);

  Real fog_distance = distance;
  if (p.water_enabled && p.terrain_water && relative_y < p.water_level && view.y < Real(0)) {
    // The view ray meets the surface before the ground (the camera is above the water).
    // On a planet the water surface lies a.drop lower too (locally flat: the depth is small
    // beside the curvature); both negative: surface > 0.
    const Real surface = (p.water_level - a.drop) / view.y;
    Vec3<Real> water_view = view;
    if (p.planet_center_distance > 0.0) {  // shaded in the local frame of the point
      const Real center_y = Real(p.planet_center_distance);
      const Vec3<Real> up = normalize_or(Vec3<Real>{position.x, position.y + center_y, position.z},
                                         Vec3<Real>{Real(0), Real(1), Real(0)});
      water_view = to_local_frame(view, up);
    }
    const Real footprint = surface_footprint(p, surface, water_view);
    radiance = shade_water(p, *r.lattice, r.skybox, water_view, surface,
                           std::max(Real(0), a.water_depth), radiance, footprint, a.water_sun,
                           Vec3<Real>{a.reflection_r, a.reflection_g, a.reflection_b},
                           a.reflection_weight, work);
    fog_distance = surface;
    ++work.water_pixels;
  }
  if (p.fog_enabled) {
    ++work.fogged_pixels;
    radiance = apply_fog(p, radiance, view, fog_distance);
  }
  return p.clouds ? clouds_over(p, *r.lattice, radiance, view, fog_distance, work) : radiance;
}

// No terrain at this pixel: the sky above the horizon; below it, open water if the camera is
// above the water, else the fog colour (terrain beyond the far distance).
template <class Real>
Vec3<Real> background_radiance(const ShadeParams<Real>& p, const ShadeResources& r, int px, int py,
                               ShadeWork& work) {
  ++work.background_pixels;
  // The view ray in double (stage_params.h), rounded once.
  const double ndc_x = 2.0 * (px + 0.5) / p.width - 1.0;
  const double ndc_y = 2.0 * (py + 0.5) / p.height - 1.0;
  const double sx = ndc_x * p.tan_half_fov_x, sy = ndc_y * p.tan_half_fov_y;
  double ray[3];
  for (int c = 0; c < 3; ++c) {
    ray[c] = (p.forward[c] + sx * p.right[c]) + sy * p.up[c];
  }
  const Vec3<Real> d =
      normalize_or(Vec3<Real>{Real(ray[0]), Real(ray[1]), Real(ray[2])}, p.camera_forward);
  if (p.planet_center_distance > 0.0) {
    return planet_background(p, r, ray, d, work);
  }
  // The sky and the fog lie beyond every distance (kMaxCameraRelativeDistance); open water at
  // its surface.
  Real end = Real(limits::kMaxCameraRelativeDistance);
  Vec3<Real> radiance;
  if (d.y < Real(0) && p.water_enabled) {
    end = p.water_level / d.y;
    radiance = open_water(p, r, d, d, end, work);
  } else if (d.y < Real(0)) {
    radiance = fog_color(p, d);
    if (p.clouds) {  // terrain past the far distance, no lower than the frame's lowest
      end = std::min(end, p.cloud_ground / d.y);  // d.y < 0
    }
  } else {
    radiance = sky_radiance(p, r.skybox, d);
  }
  return p.clouds ? clouds_over(p, *r.lattice, radiance, d, end, work) : radiance;
}

template <class Real>
void shade_pixels(const ShadeParams<Real>& p, const ShadeResources& r, const ShadingInputs& in,
                  RowRange rows, std::span<Real> rgb) {
  const Real exposure = p.exposure;
  ShadeWork work;
  for (int py = rows.begin; py < rows.end; ++py) {
    for (int px = 0; px < p.width; ++px) {
      const std::size_t k = static_cast<std::size_t>(py) * p.width + px;
      const Vec3<Real> radiance = in.primitive[k] != 0xffffffffu
                                      ? terrain_radiance<Real>(p, r, in.at<Real>(k), work)
                                      : background_radiance<Real>(p, r, px, py, work);
      rgb[3 * k] = radiance.x * exposure;
      rgb[3 * k + 1] = radiance.y * exposure;
      rgb[3 * k + 2] = radiance.z * exposure;
    }
  }
}

template Vec3<float> facing_normal<float>(const Vec3<float>&, const Vec3<float>&, ShadeWork&);
template Vec3<double> facing_normal<double>(const Vec3<double>&, const Vec3<double>&, ShadeWork&);
template Vec3<float> lit_terrain<float>(const ShadeParams<float>&, const ShadeResources&,
                                        const PixelAttributes<float>&, const Vec3<float>&, float,
                                        const Vec3<float>&, ShadeWork&);
template Vec3<double> lit_terrain<double>(const ShadeParams<double>&, const ShadeResources&,
                                          const PixelAttributes<double>&, const Vec3<double>&,
                                          double, const Vec3<double>&, ShadeWork&);
template Vec3<float> terrain_radiance<float>(const ShadeParams<float>&, const ShadeResources&,
                                             const PixelAttributes<float>&, ShadeWork&);
template Vec3<double> terrain_radiance<double>(const ShadeParams<double>&, const ShadeResources&,
                                               const PixelAttributes<double>&, ShadeWork&);
template Vec3<float> background_radiance<float>(const ShadeParams<float>&, const ShadeResources&,
                                                int, int, ShadeWork&);
template Vec3<double> background_radiance<double>(const ShadeParams<double>&, const ShadeResources&,
                                                  int, int, ShadeWork&);
template void shade_pixels<float>(const ShadeParams<float>&, const ShadeResources&,
                                  const ShadingInputs&, RowRange, std::span<float>);
template void shade_pixels<double>(const ShadeParams<double>&, const ShadeResources&,
                                   const ShadingInputs&, RowRange, std::span<double>);

}  // namespace relief
