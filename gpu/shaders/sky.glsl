// Sky, fog and atmosphere (core/sky.cc, core/atmosphere.cc), operation for operation.

// ((1 + c) / 2)^(2^n) by repeated squaring.
float power_of_half_cosine(float c, int squarings) {
  precise float x = clamp01((1.0 + c) * 0.5);
  for (int k = 0; k < squarings; ++k) {
    x = x * x;
  }
  return x;
}

// The skybox's faces (core/skybox.h): layer f of a GL_RGB32F array texture holds face f
// (+x, -x, +y, -y, +z, -z), row 0 its image's top row; filtered by hand like the proto-textures
// (texelFetch of the CPU's own texels), not by GL's cube-map sampler, whose filter weights have
// an unspecified precision.
layout(binding = RELIEF_SKYBOX_UNIT) uniform sampler2DArray skybox_faces;

// skybox.cc: cube_face_coordinate (Table 8.19, ties to x then y), then skybox_radiance.
vec3 skybox_radiance(vec3 d) {
  precise float ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
  int face;
  precise float sc, tc, major;
  if (ax >= ay && ax >= az) {
    face = d.x < 0.0 ? 1 : 0;
    sc = face == 0 ? -d.z : d.z;
    tc = -d.y;
    major = ax;
  } else if (ay >= az) {
    face = d.y < 0.0 ? 3 : 2;
    sc = d.x;
    tc = face == 2 ? d.z : -d.z;
    major = ay;
  } else {
    face = d.z < 0.0 ? 5 : 4;
    sc = face == 4 ? d.x : -d.x;
    tc = -d.y;
    major = az;
  }
  // skybox.cc's domain (0 < major <= FLT_MAX, |sc|, |tc| <= major); infinities and NaNs do not
  // reach here (d is a unit vector), and GLSL need not honour them.
  if (!(major > 0.0 && major <= 3.4028234663852886e38 && abs(sc) <= major && abs(tc) <= major)) {
    face = 0;
    sc = 0.0;
    tc = 0.0;
    major = 1.0;
  }
  precise float s = (divide(sc, major) + 1.0) * 0.5;
  precise float t = (divide(tc, major) + 1.0) * 0.5;
  const int size = textureSize(skybox_faces, 0).x;
  precise float n = float(size);
  precise float x = s * n - 0.5, y = t * n - 0.5;
  precise float fx = floor(x), fy = floor(y);
  precise float a = x - fx, b = y - fy;
  // A division that is not correctly rounded may put s a little outside [0, 1]: the clamp
  // keeps every fetch on the face.
  const int i0 = clamp(int(fx), 0, size - 1), i1 = clamp(int(fx) + 1, 0, size - 1);
  const int j0 = clamp(int(fy), 0, size - 1), j1 = clamp(int(fy) + 1, 0, size - 1);
  const vec3 p00 = texelFetch(skybox_faces, ivec3(i0, j0, face), 0).rgb;
  const vec3 p10 = texelFetch(skybox_faces, ivec3(i1, j0, face), 0).rgb;
  const vec3 p01 = texelFetch(skybox_faces, ivec3(i0, j1, face), 0).rgb;
  const vec3 p11 = texelFetch(skybox_faces, ivec3(i1, j1, face), 0).rgb;
  precise vec3 bottom = p00 + a * (p10 - p00);
  precise vec3 top = p01 + a * (p11 - p01);
  precise vec3 r = bottom + b * (top - bottom);
  return r;
}

// atmosphere.cc, column_growth: phi(z) = (1 - e^-z) / z given e = e^-z.
float column_growth(float z, float e) {
  if (abs(z) < kGrowthSeriesLimit) {
    precise float series = kGrowthSeries[kGrowthTerms - 1];
    for (int k = kGrowthTerms - 2; k >= 0; --k) {
      series = kGrowthSeries[k] + z * series;
    }
    return series;
  }
  precise float quotient = divide(1.0 - e, z);
  return quotient;
}

// atmosphere.cc, scatter: per channel the in-scattered light of a ray whose column is
// `column` and whose end has the sun's column `end_sun_column` above it, and where
// `with_transmittance` its transmittance.
void atmosphere_scatter(vec3 d, float column, float end_sun_column, bool with_transmittance,
                        out vec3 transmittance, out vec3 inscatter) {
  precise float c = dot3(d, f3(P.sun_direction));
  precise float one_plus_c2 = 1.0 + c * c;
  precise float q = P.atmosphere_mie_a - P.atmosphere_mie_b * c;  // >= 0.0025
  precise float mie_phase = divide(one_plus_c2, q * square_root(q));
  const vec3 extinction = f3(P.atmosphere_extinction_log2);
  const vec3 camera_sun = f3(P.atmosphere_camera_sun_depth_log2);
  const vec3 rayleigh = f3(P.atmosphere_rayleigh_sun);
  const vec3 mie = f3(P.atmosphere_mie_sun);
  transmittance = vec3(1.0);
  for (int k = 0; k < 3; ++k) {
    precise float view = extinction[k] * column;
    if (with_transmittance) {
      transmittance[k] = exp2_det(-view);
    }
    precise float a = camera_sun[k];
    precise float b = view + extinction[k] * end_sun_column;
    precise float z = abs(a - b);
    precise float integral =
        exp2_det(-min_cpp(a, b)) * (column * column_growth(z * kLn2, exp2_det(-z)));
    precise float s = (rayleigh[k] * one_plus_c2 + mie[k] * mie_phase) * integral;
    inscatter[k] = s;
  }
}

// atmosphere.cc, atmosphere_over.
vec3 atmosphere_over(vec3 radiance, vec3 d, float distance_in) {
  precise float ray_distance = min_cpp(distance_in, kMaxCameraRelativeDistance);
  precise float w = d.y * ray_distance * P.atmosphere_inv_scale_height;
  precise float rise = abs(w);
  precise float fall = exp2_det(-rise * kLog2e);
  precise float ray_length = ray_distance * column_growth(rise, fall);
  precise float dense = exp2_det(P.atmosphere_log2_density + max_cpp(-w * kLog2e, 0.0));
  precise float sun_length =
      w > 0.0 ? P.atmosphere_sun_slope_length * fall : P.atmosphere_sun_slope_length;
  precise float density = min_cpp(dense, divide(kMaxOpticalDepth, max_cpp(ray_length, sun_length)));
  vec3 transmittance, inscatter;
  atmosphere_scatter(d, density * ray_length, density * sun_length, true, transmittance, inscatter);
  precise vec3 r = radiance * transmittance + inscatter;
  return r;
}

// atmosphere.cc, atmosphere_sky.
vec3 atmosphere_sky(vec3 d) {
  precise float mu = max_cpp(d.y, 0.0);
  precise float slope = 0.5 * (mu + square_root(mu * mu + P.atmosphere_grazing_term));
  precise float column =
      min_cpp(P.atmosphere_density * divide(P.atmosphere_scale_height, slope), kMaxOpticalDepth);
  vec3 unused, inscatter;
  atmosphere_scatter(d, column, 0.0, false, unused, inscatter);
  return inscatter;
}

// sky.cc, sun_light: the disc and its halo (no halo under the atmosphere).
vec3 sun_light(vec3 d) {
  precise float c = dot3(d, f3(P.sun_direction));
  const float inner = P.sun_cos_inner, outer = P.sun_cos_outer;
  precise float disc =
      inner > outer ? smooth01(divide(c - outer, inner - outer)) : (c >= inner ? 1.0 : 0.0);
  if (P.atmosphere != 0) {
    precise vec3 a = f3(P.sun) * (20.0 * disc);
    return a;
  }
  precise float halo = kHaloWeight * power_of_half_cosine(c, 5);
  precise vec3 r = f3(P.sun) * (20.0 * disc + halo);
  return r;
}

vec3 sky_radiance(vec3 d) {
  if (P.skybox != 0) {
    const vec3 color = skybox_radiance(d);
    if (P.skybox_sun == 0) {
      return color;
    }
    precise vec3 lit = color + sun_light(d);
    return lit;
  }
  if (P.atmosphere != 0) {
    precise vec3 air = atmosphere_sky(d) + sun_light(d);
    return air;
  }
  const vec3 horizon = f3(P.horizon);
  precise vec3 color = horizon;
  if (d.y > 0.0) {
    color = lerp3(horizon, f3(P.zenith), square_root(d.y));
  }
  precise vec3 r = color + sun_light(d);
  return r;
}

vec3 fog_color(vec3 d) {
  if (P.atmosphere != 0) {
    return atmosphere_over(vec3(0.0), d, kMaxCameraRelativeDistance);
  }
  precise float c = dot3(d, f3(P.sun_direction));
  precise vec3 r = f3(P.horizon) + f3(P.sun) * (kFogSunWeight * power_of_half_cosine(c, 3));
  return r;
}

vec3 apply_fog(vec3 radiance, vec3 d, float distance) {
  if (P.atmosphere != 0) {
    return atmosphere_over(radiance, d, distance);
  }
  precise float clear = exp2_det(-P.fog_density_log2 * distance);
  if (!(clear < 1.0)) {
    return radiance;
  }
  return lerp3(fog_color(d), radiance, clear);
}

