#include "core/clouds.h"

#include <algorithm>
#include <cmath>

#include "core/cloud_plan.h"
#include "core/det_math.h"
#include "core/interpolant.h"
#include "core/limits.h"
#include "core/sky.h"

namespace relief {

namespace {

// clamp(2 - 2 footprint / cell, 0, 1) of an octave with `inv_cell` cells per world unit.
template <class Real>
Real octave_fade(Real footprint, Real inv_cell) {
  return std::min(Real(1), std::max(Real(0), Real(2) - Real(2) * footprint * inv_cell));
}

// The mean density over p.cloud_steps points of `path` from `origin` along unit `dir`
// (camera-relative; the view ray's origin is the camera), `horizontal` the length of dir's
// (x, z). The footprint at distance t along the path is footprint_at(t), widened to a
// quarter of the horizontal span each point stands for (kCloudSpanFootprint): an octave whose
// cells the path crosses by the dozen averages out along it (to its mean, 0), so it fades as
// under a wide pixel, and a long slanted path tends to the layer's mean instead of reading one
// cell's all-or-nothing. Not the whole span: fading octaves out of the fBm is not averaging
// the clamped density, and by the whole span the frame moved away from the ground truth
// (docs/stages.md, "Clouds").
template <class Real, class Footprint>
Real path_density(const ShadeParams<Real>& p, const NoiseLattice& lattice, const Vec3<Real>& origin,
                  const Vec3<Real>& dir, Real horizontal, const CloudPath<Real>& path,
                  const Footprint& footprint_at, ShadeWork& work) {
  const Real inv_steps = Real(1) / Real(p.cloud_steps);  // cloud_steps >= 1
  const Real span = path.length * horizontal * inv_steps * Real(kCloudSpanFootprint);
  Real sum = Real(0);
  for (int k = 0; k < p.cloud_steps; ++k) {
    const Real t = path.start + path.length * ((Real(k) + Real(0.5)) * inv_steps);
    sum = sum + cloud_density(p, lattice, origin.x + t * dir.x, origin.z + t * dir.z,
                              std::max(footprint_at(t), span), work);
  }
  return sum * inv_steps;
}

// The length of unit d's horizontal part (domain: a sum of squares, >= 0).
template <class Real>
Real horizontal_length(const Vec3<Real>& d) {
  return std::sqrt(d.x * d.x + d.z * d.z);
}

}  // namespace

template <class Real>
CloudPath<Real> cloud_path(const ShadeParams<Real>& p, Real y0, Real dy, Real end) {
  const Real slope = Real(kCloudMinSlope);
  const Real safe_dy = dy >= Real(0) ? std::max(dy, slope) : std::min(dy, -slope);
  const Real t_bottom = (p.cloud_bottom - y0) / safe_dy;  // |safe_dy| >= 1e-4: finite
  const Real t_top = (p.cloud_top - y0) / safe_dy;
  const Real start = std::max(Real(0), std::min(t_bottom, t_top));
  const Real stop = std::min(end, std::max(t_bottom, t_top));
  return {start, std::max(Real(0), stop - start)};
}

template <class Real>
Real cloud_density(const ShadeParams<Real>& p, const NoiseLattice& lattice, Real x, Real z,
                   Real footprint, ShadeWork& work) {
  const Real fade0 = octave_fade(footprint, p.cloud_inv_scale[0]);
  if (!(fade0 > Real(0))) {
    return p.cloud_mean_density;
  }
  Real warp_x = Real(0), warp_z = Real(0);
  if (p.cloud_warped) {
    const Real inv = p.cloud_inv_scale[0];
    warp_x = sample_lattice<Interpolant::kCubic>(lattice, p.cloud_warp_offset[0] + x * inv,
                                                 p.cloud_warp_offset[1] + z * inv);
    warp_z = sample_lattice<Interpolant::kCubic>(lattice, p.cloud_warp_offset[2] + x * inv,
                                                 p.cloud_warp_offset[3] + z * inv);
    work.cloud_lookups += 2;
  }
  Real n = Real(0);
  for (int i = 0; i < p.cloud_octaves; ++i) {
    const Real inv = p.cloud_inv_scale[i];
    const Real fade = octave_fade(footprint, inv);
    if (!(fade > Real(0))) {
      break;  // each later octave's cell is smaller still
    }
    const Real u = (p.cloud_offset_x[i] + x * inv) + warp_x * p.cloud_warp_gain[i];
    const Real v = (p.cloud_offset_z[i] + z * inv) + warp_z * p.cloud_warp_gain[i];
    n = n + (p.cloud_amplitude[i] * fade) * sample_lattice<Interpolant::kCubic>(lattice, u, v);
    ++work.cloud_lookups;
  }
  const Real density =
      std::min(Real(1), std::max(Real(0), (n - p.cloud_threshold) * p.cloud_sharpness));
  return p.cloud_mean_density + (density - p.cloud_mean_density) * fade0;
}

template <class Real>
Real cloud_sun_share(const ShadeParams<Real>& p, const NoiseLattice& lattice,
                     const Vec3<Real>& position, Real footprint, ShadeWork& work) {
  const Vec3<Real>& s = p.sun_direction;
  if (!(s.y > Real(0))) {
    return Real(1);  // the sun's ray goes down: it meets no layer above (and lights nothing)
  }
  // A grazing sun's path is taken at kCloudMinSunSine (the layer's light floors it too):
  // 1 / sin e would carry the point past float's resolution of its own position.
  const CloudPath<Real> path = cloud_path(p, position.y, std::max(s.y, Real(kCloudMinSunSine)),
                                          Real(limits::kMaxCameraRelativeDistance));
  if (!(path.length > Real(0))) {
    return Real(1);
  }
  ++work.cloud_sun_paths;
  const Real density = path_density(
      p, lattice, position, s, horizontal_length(s), path, [&](Real) { return footprint; }, work);
  return exp2_det(-(p.cloud_extinction_log2 * density * path.length));
}

template <class Real>
Vec3<Real> clouds_over_from(const ShadeParams<Real>& p, const NoiseLattice& lattice,
                            const Vec3<Real>& radiance, const Vec3<Real>& origin,
                            Real origin_distance, const Vec3<Real>& d, Real end, ShadeWork& work) {
  const CloudPath<Real> path = cloud_path(p, origin.y, d.y, end);
  if (!(path.length > Real(0))) {
    return radiance;
  }
  ++work.cloud_view_paths;
  // The footprint on the layer: the water's rule (shade.cc, surface_footprint), at the
  // distance from the camera.
  const Real stretch = p.pixel_angle / std::max(std::abs(d.y), Real(0.05));
  const Real density = path_density(
      p, lattice, origin, d, horizontal_length(d), path,
      [&](Real t) { return (origin_distance + t) * stretch; }, work);
  const Real transmittance = exp2_det(-(p.cloud_extinction_log2 * density * path.length));
  // The layer's light: the sky's, and the sun's dimmed by the cloud above the point.
  const Vec3<Real> light =
      p.cloud_sky_light + p.cloud_sun_light * exp2_det(-(density * p.cloud_sun_depth_log2));
  const Real middle = origin_distance + (path.start + path.length * Real(0.5));
  const Vec3<Real> seen = p.fog_enabled ? apply_fog(p, light, d, middle) : light;
  return radiance * transmittance + seen * (Real(1) - transmittance);
}

template <class Real>
Vec3<Real> clouds_over(const ShadeParams<Real>& p, const NoiseLattice& lattice,
                       const Vec3<Real>& radiance, const Vec3<Real>& d, Real end, ShadeWork& work) {
  return clouds_over_from(p, lattice, radiance, Vec3<Real>{0, 0, 0}, Real(0), d, end, work);
}

template CloudPath<float> cloud_path<float>(const ShadeParams<float>&, float, float, float);
template CloudPath<double> cloud_path<double>(const ShadeParams<double>&, double, double, double);
template float cloud_density<float>(const ShadeParams<float>&, const NoiseLattice&, float, float,
                                    float, ShadeWork&);
template double cloud_density<double>(const ShadeParams<double>&, const NoiseLattice&, double,
                                      double, double, ShadeWork&);
template float cloud_sun_share<float>(const ShadeParams<float>&, const NoiseLattice&,
                                      const Vec3<float>&, float, ShadeWork&);
template double cloud_sun_share<double>(const ShadeParams<double>&, const NoiseLattice&,
                                        const Vec3<double>&, double, ShadeWork&);
template Vec3<float> clouds_over<float>(const ShadeParams<float>&, const NoiseLattice&,
                                        const Vec3<float>&, const Vec3<float>&, float, ShadeWork&);
template Vec3<float> clouds_over_from<float>(const ShadeParams<float>&, const NoiseLattice&,
                                             const Vec3<float>&, const Vec3<float>&, float,
                                             const Vec3<float>&, float, ShadeWork&);
template Vec3<double> clouds_over_from<double>(const ShadeParams<double>&, const NoiseLattice&,
                                               const Vec3<double>&, const Vec3<double>&, double,
                                               const Vec3<double>&, double, ShadeWork&);
template Vec3<double> clouds_over<double>(const ShadeParams<double>&, const NoiseLattice&,
                                          const Vec3<double>&, const Vec3<double>&, double,
                                          ShadeWork&);

}  // namespace relief
