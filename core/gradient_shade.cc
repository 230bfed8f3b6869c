#include "core/gradient_shade.h"

namespace relief {

template <class Real>
Vec3<Real> gradient_albedo(const ShadeParams<Real>& p, Real h) {
  Vec3<Real> color = p.gradient_color[0];
  for (int i = 0; i + 1 < p.gradient_count; ++i) {
    if (!(h >= p.gradient_height[i])) {
      continue;
    }
    Real t = Real(1);
    if (!(h >= p.gradient_height[i + 1])) {
      const Real ramp = (h - p.gradient_height[i]) * p.gradient_inv_span[i];
      t = ramp < Real(1) ? ramp : Real(1);
    }
    const Vec3<Real>& low = p.gradient_color[i];
    color = low + (p.gradient_color[i + 1] - low) * t;
  }
  return color;
}

template <class Real>
Vec3<Real> gouraud_light(const ShadeParams<Real>& p, const Vec3<Real>& albedo, Real lambert,
                         Real ny, Real sun_share, Real sky_share) {
  const Real sunlit = lambert * sun_share;
  const Vec3<Real> hemisphere =
      mix(p.ground_light, p.sky_light, (Real(0.5) + Real(0.5) * ny) * sky_share);
  const Real ambient = p.ambient;
  return albedo * (p.sun * sunlit + hemisphere + Vec3<Real>{ambient, ambient, ambient});
}

template Vec3<float> gradient_albedo<float>(const ShadeParams<float>&, float);
template Vec3<double> gradient_albedo<double>(const ShadeParams<double>&, double);
template Vec3<float> gouraud_light<float>(const ShadeParams<float>&, const Vec3<float>&, float,
                                          float, float, float);
template Vec3<double> gouraud_light<double>(const ShadeParams<double>&, const Vec3<double>&, double,
                                            double, double, double);

}  // namespace relief
