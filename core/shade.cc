#include "core/shade.h"

#include <algorithm>
#include <cmath>

#include "core/det_math.h"
#include "core/interpolant.h"
#include "core/layer_weights.h"
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
Vec3<Real> vec(const glm::dvec3& v) {
  return {Real(v.x), Real(v.y), Real(v.z)};
}

template <class Real>
Vec3<Real> sample(const ProtoTexture& t, Real u, Real v, Real dudx, Real dvdx, Real dudy,
                  Real dvdy) {
  const int size = t.levels[0].size;
  const float lod = texture_lod(size, float(dudx), float(dvdx), float(dudy), float(dvdy));
  const Rgb c = sample_trilinear(t, float(u), float(v), lod);
  return {Real(c[0]), Real(c[1]), Real(c[2])};
}

// The layer's albedo at the pixel: planar from above, or triplanar.
template <class Real>
Vec3<Real> layer_albedo(const ShadingPlan& plan, const LayerPlan& l, const ShadingInputs& in,
                        std::size_t k, Real relative_y, const Vec3<Real>& n) {
  const Real inv = Real(l.inv_tile);
  const Real x = Real(l.offset_x) + in.dx[k] * inv, z = Real(l.offset_z) + in.dz[k] * inv;
  const Real y = Real(l.offset_y) + relative_y * inv;
  const Real xdx = in.dx_ddx[k] * inv, xdy = in.dx_ddy[k] * inv;
  const Real zdx = in.dz_ddx[k] * inv, zdy = in.dz_ddy[k] * inv;
  const Real ydx = in.height_ddx[k] * inv, ydy = in.height_ddy[k] * inv;
  if (!plan.triplanar) {
    return sample<Real>(*l.texture, x, z, xdx, zdx, xdy, zdy);
  }
  // Squared-normal weights (Mekala; Scape): they sum to one for a unit normal.
  Real w[3] = {n.x * n.x, n.y * n.y, n.z * n.z};
  Real used = Real(0);
  for (Real& weight : w) {
    weight = weight < Real(kMinProjectionWeight) ? Real(0) : weight;
    used = used + weight;
  }
  Vec3<Real> sum{0, 0, 0};
  if (w[0] > Real(0)) {
    sum = sum + sample<Real>(*l.texture, z, y, zdx, ydx, zdy, ydy) * w[0];
  }
  if (w[1] > Real(0)) {
    sum = sum + sample<Real>(*l.texture, x, z, xdx, zdx, xdy, zdy) * w[1];
  }
  if (w[2] > Real(0)) {
    sum = sum + sample<Real>(*l.texture, x, y, xdx, ydx, xdy, ydy) * w[2];
  }
  return sum * (Real(1) / used);  // domain: used >= 1/3 - 2% for a unit normal
}

// Sun (Lambert, Phong), hemispherical sky light and ambient.
template <class Real>
Vec3<Real> light(const ShadingPlan& plan, const Vec3<Real>& albedo, const Vec3<Real>& n,
                 const Vec3<Real>& view, Real specular) {
  const LightPlan& l = plan.light;
  const Vec3<Real> to_sun = vec<Real>(l.sun_direction);
  const Vec3<Real> sun = vec<Real>(l.sun);
  const Real ndl = std::max(Real(0), dot(n, to_sun));
  const Vec3<Real> hemisphere =
      mix(vec<Real>(l.ground), vec<Real>(l.sky), Real(0.5) + Real(0.5) * n.y);
  const Real ambient = Real(l.ambient);
  Vec3<Real> radiance = albedo * (sun * ndl + hemisphere + Vec3<Real>{ambient, ambient, ambient});
  if (specular > Real(0) && ndl > Real(0)) {
    const Vec3<Real> reflected = n * (Real(2) * ndl) - to_sun;
    const Real rv = -dot(reflected, view);
    if (rv > Real(0)) {  // log's domain
      radiance = radiance + sun * (specular * exp2_det(Real(l.shininess) * log2_det(rv)));
    }
  }
  return radiance;
}

// The pixel's extent on the water surface at `distance` along unit `view`: the pixel's angle
// times the distance, stretched by the grazing incidence (|view.y| floored at 0.05 for the
// division's domain). Smooth across pixels, unlike the ground's per-triangle derivatives.
template <class Real>
Real surface_footprint(const ShadingPlan& plan, Real distance, const Vec3<Real>& view) {
  return distance * Real(plan.pixel_angle) / std::max(std::abs(view.y), Real(0.05));
}

template <class Real>
Vec3<Real> terrain_radiance(const ShadingPlan& plan, const ShadingInputs& in, std::size_t k) {
  const Real relative_y = Real(in.height[k]);  // camera-relative (stage 3)
  const Vec3<Real> p{Real(in.dx[k]), relative_y, Real(in.dz[k])};
  const Real distance = std::sqrt(dot(p, p));
  const Vec3<Real> forward = vec<Real>(plan.camera.forward);
  const Vec3<Real> view = normalize_or(p, forward);
  const Vec3<Real> n = normalize_or(Vec3<Real>{Real(in.nx[k]), Real(in.ny[k]), Real(in.nz[k])},
                                    Vec3<Real>{Real(0), Real(1), Real(0)});

  // Scape's dithered transitions: the terrain's own noise lattice, its own scale. The noise
  // has no level of detail: where the pixel's footprint (distance x pixel angle) exceeds half a
  // noise cell it only aliases, so it fades out linearly until the footprint is a whole cell.
  // Sampled only nearer than that, its coordinates stay below 1 / pixel_angle < 2^20 cells,
  // exact in float for any dither_scale.
  Real dither_offset = Real(0);
  const Real inv = Real(plan.dither.inv_scale);
  const Real dither_fade =
      std::min(Real(1), Real(2) - Real(2) * distance * Real(plan.pixel_angle) * inv);
  if (plan.dither.amount > 0.0 && dither_fade > Real(0)) {
    const Real noise = sample_lattice<Interpolant::kCubic>(
        *plan.dither.lattice, Real(plan.dither.offset_x) + in.dx[k] * inv,
        Real(plan.dither.offset_z) + in.dz[k] * inv);
    dither_offset = Real(0.5 * plan.dither.amount) * noise * dither_fade;
  }
  Real weights[limits::kMaxMaterialLayers];
  layer_weights(plan, relative_y, Real(in.slope[k]), dither_offset, weights);
  Vec3<Real> albedo{0, 0, 0};
  Real specular = Real(0), used = Real(0);
  for (std::size_t layer = 0; layer < plan.layers.size(); ++layer) {
    if (weights[layer] < Real(kMinLayerWeight)) {
      continue;
    }
    albedo = albedo + layer_albedo(plan, plan.layers[layer], in, k, relative_y, n) * weights[layer];
    specular = specular + Real(plan.layers[layer].specular) * weights[layer];
    used = used + weights[layer];
  }
  // Domain: the largest weight is >= 1/8 > kMinLayerWeight, so used > 0.
  albedo = albedo * (Real(1) / used);
  Vec3<Real> radiance = light(plan, albedo, n, view, specular / used);

  Real fog_distance = distance;
  const WaterPlan& w = plan.water;
  if (w.enabled && relative_y < Real(w.level) && view.y < Real(0)) {
    // The view ray meets the surface before the ground (the camera is above the water).
    const Real surface = Real(w.level) / view.y;  // both negative: surface > 0
    const Real footprint = surface_footprint(plan, surface, view);
    radiance = shade_water(plan, view, surface, std::max(Real(0), Real(in.water_depth[k])),
                           radiance, footprint);
    fog_distance = surface;
  }
  return apply_fog(plan, radiance, view, fog_distance);
}

// No terrain at this pixel: the sky above the horizon; below it, open water if the camera is
// above the water, else the fog colour (terrain beyond the far distance).
template <class Real>
Vec3<Real> background_radiance(const ShadingPlan& plan, int px, int py) {
  const CameraFrame& c = plan.camera;
  const double ndc_x = 2.0 * (px + 0.5) / plan.width - 1.0;
  const double ndc_y = 2.0 * (py + 0.5) / plan.height - 1.0;
  const glm::dvec3 ray =
      c.forward + ndc_x * c.tan_half_fov_x * c.right + ndc_y * c.tan_half_fov_y * c.up;
  const Vec3<Real> d = normalize_or(vec<Real>(ray), vec<Real>(c.forward));
  const WaterPlan& w = plan.water;
  if (d.y < Real(0)) {
    if (w.enabled) {
      const Real surface = Real(w.level) / d.y;
      const Real footprint = surface_footprint(plan, surface, d);
      const Vec3<Real> open =
          shade_water(plan, d, surface, Real(1e6), Vec3<Real>{0, 0, 0}, footprint);
      return apply_fog(plan, open, d, surface);
    }
    return fog_color(plan, d);
  }
  return sky_radiance(plan, d);
}

}  // namespace

template <class Real>
void shade_pixels(const ShadingPlan& plan, const ShadingInputs& in, RowRange rows,
                  std::span<Real> rgb) {
  const Real exposure = Real(plan.light.exposure);
  for (int py = rows.begin; py < rows.end; ++py) {
    for (int px = 0; px < plan.width; ++px) {
      const std::size_t k = static_cast<std::size_t>(py) * plan.width + px;
      const Vec3<Real> radiance = in.primitive[k] != 0xffffffffu
                                      ? terrain_radiance<Real>(plan, in, k)
                                      : background_radiance<Real>(plan, px, py);
      rgb[3 * k] = radiance.x * exposure;
      rgb[3 * k + 1] = radiance.y * exposure;
      rgb[3 * k + 2] = radiance.z * exposure;
    }
  }
}

template void shade_pixels<float>(const ShadingPlan&, const ShadingInputs&, RowRange,
                                  std::span<float>);
template void shade_pixels<double>(const ShadingPlan&, const ShadingInputs&, RowRange,
                                   std::span<double>);

}  // namespace relief
