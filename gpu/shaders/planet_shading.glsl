// Stage 8 on a planet (core/planet_shading.h, core/shade.cc's planet branches; docs/planet.md),
// operation for operation: the local frame of a point on the sphere, and the background ray
// against the water sphere, the datum sphere or the sky measured from the limb. The background
// works in double as the CPU does, so sin_cos_det<double> and atan2_det<double> of
// core/det_math.h are spelled out here (the constants from the prelude, as the CPU rounds them).

// `v` in the frame whose up is the unit vector `up` (to_local_frame).
vec3 to_local_frame(vec3 v, vec3 up) {
  const float c = up.y;
  if (!(c > kLocalFrameMinCos)) {
    return v;  // the division's domain: 1 + c >= 0.001
  }
  const vec3 w = vec3(-up.z, 0.0, up.x);  // up x (0, 1, 0)
  precise vec3 wv = vec3(w.y * v.z - w.z * v.y, w.z * v.x - w.x * v.z, w.x * v.y - w.y * v.x);
  precise vec3 wwv =
      vec3(w.y * wv.z - w.z * wv.y, w.z * wv.x - w.x * wv.z, w.x * wv.y - w.y * wv.x);
  precise float k = 1.0 / (1.0 + c);
  precise vec3 r = vec3(v.x + wv.x + wwv.x * k, v.y + wv.y + wwv.y * k, v.z + wv.z + wwv.z * k);
  return r;
}

// sin_cos_det<double>: Cody-Waite reduction in three pieces, the Taylor series by Horner's rule.
void sin_cos_det_d(double x, out double sine, out double cosine) {
  precise double q = x * kInvHalfPiD;
  q = q < -64.0LF ? -64.0LF : (q > 64.0LF ? 64.0LF : q);  // the conversion's domain
  precise double rounded = q < 0.0LF ? q - 0.5LF : q + 0.5LF;
  const int k = int(rounded);  // truncation toward zero, as C++'s static_cast<int>
  precise double dk = double(k);
  precise double r = ((x - dk * kHalfPiHiD) - dk * kHalfPiMidD) - dk * kHalfPiLoD;
  precise double r2 = r * r;
  precise double ps = kSinCoeffD[kSinCoeffDCount - 1];
  for (int j = kSinCoeffDCount - 2; j >= 0; --j) {
    ps = ps * r2 + kSinCoeffD[j];
  }
  precise double pc = kCosCoeffD[kCosCoeffDCount - 1];
  for (int j = kCosCoeffDCount - 2; j >= 0; --j) {
    pc = pc * r2 + kCosCoeffD[j];
  }
  precise double s = r * ps;
  const int quadrant = k & 3;  // two's complement, as C++'s k & 3
  if (quadrant == 0) {
    sine = s;
    cosine = pc;
  } else if (quadrant == 1) {
    sine = pc;
    cosine = -s;
  } else if (quadrant == 2) {
    sine = -s;
    cosine = -pc;
  } else {
    sine = -pc;
    cosine = s;
  }
}

// atan_reduced<double>: the odd series, Horner in u^2.
double atan_reduced_d(double u) {
  precise double u2 = u * u;
  precise double series = kAtanCoeffD[kAtanCoeffDCount - 1];
  for (int j = kAtanCoeffDCount - 2; j >= 0; --j) {
    series = series * u2 + kAtanCoeffD[j];
  }
  precise double result = u * series;
  return result;
}

// atan2_det<double> for y >= 0 and finite x: the angle in [0, pi] from the +x axis.
double atan2_det_d(double y, double x) {
  const double ax = x < 0.0LF ? -x : x;
  const double lo = ax < y ? ax : y;
  const double hi = ax < y ? y : ax;
  if (!(hi > 0.0LF)) {
    return 0.0LF;  // (0, 0), and the domain guard of the division below
  }
  precise double t = lo / hi;  // [0, 1]
  precise double a;
  if (t > kTanEighthPiD) {
    precise double u = (t - 1.0LF) / (t + 1.0LF);
    a = kQuarterPiD + atan_reduced_d(u);
  } else {
    a = atan_reduced_d(t);
  }
  if (y > ax) {
    a = kHalfPiD - a;
  }
  if (x < 0.0LF) {
    a = kPiD - a;
  }
  return a;
}

// Distance along the unit ray (u0, u1, u2) to the near side of the sphere centred at
// (0, -D, 0), c = (D - r)(D + r); < 0 for a miss (planet_sphere_hit; only u1 matters).
double planet_sphere_hit(double u1, double center_distance, double c) {
  precise double b = u1 * center_distance;
  precise double disc = b * b - c;
  if (!(c > 0.0LF) || !(b < 0.0LF) || !(disc >= 0.0LF)) {
    return -1.0LF;
  }
  precise double t = c / (-b + sqrt(disc));  // the stable root; domain: -b > 0
  return t;
}

// The sky gradient's direction for a ray that misses the planet: its elevation measured from
// the limb (planet_sky_direction).
vec3 planet_sky_direction(double u0, double u1, double u2, double limb_angle) {
  precise double horizontal = sqrt(u0 * u0 + u2 * u2);
  const double alpha = atan2_det_d(horizontal, -u1);
  precise double span = kPiD - limb_angle;  // > 0: limb_angle <= pi/2
  precise double t = alpha > limb_angle ? (alpha - limb_angle) / span : 0.0LF;
  double sine, cosine;
  sin_cos_det_d(t * kHalfPiD, sine, cosine);
  precise double hx = horizontal > 0.0LF ? u0 / horizontal : 0.0LF;
  precise double hz = horizontal > 0.0LF ? u2 / horizontal : -1.0LF;
  precise double x = hx * cosine, z = hz * cosine;
  return vec3(float(x), float(sine), float(z));
}

// A planet's background (shade.cc, planet_background): the view ray (r0, r1, r2) in double,
// d it normalised in float.
vec3 planet_background(double r0, double r1, double r2, vec3 d) {
  precise double length = sqrt(r0 * r0 + r1 * r1 + r2 * r2);
  precise double u0 = r0 / length, u1 = r1 / length, u2 = r2 / length;  // length >= 1
  const double center_distance = P.planet_center_distance;
  if (P.water_enabled != 0) {
    const double t = planet_sphere_hit(u1, center_distance, P.planet_water_c);
    if (t >= 0.0LF) {
      // The local up there: the hit relative to the centre, normalised.
      precise double h0 = t * u0, h1 = t * u1 + center_distance, h2 = t * u2;
      precise double radius = sqrt(h0 * h0 + h1 * h1 + h2 * h2);
      precise double up0 = h0 / radius, up1 = h1 / radius, up2 = h2 / radius;
      const vec3 view = to_local_frame(d, vec3(float(up0), float(up1), float(up2)));
      const float surface = float(t);
      const float footprint = surface_footprint(surface, view);
      const vec3 open = shade_water(view, surface, kOpenWaterDepth, vec3(0.0), footprint);
      if (P.fog_enabled == 0) {
        return open;
      }
      return apply_fog(open, d, surface);
    }
  }
  // The ground beyond the horizon; a camera below the datum has the plane's rule.
  const bool ground = P.planet_datum_c > 0.0LF
                          ? planet_sphere_hit(u1, center_distance, P.planet_datum_c) >= 0.0LF
                          : u1 < 0.0LF;
  if (ground) {
    return fog_color(d);
  }
  return sky_radiance(planet_sky_direction(u0, u1, u2, P.planet_limb_angle));
}
