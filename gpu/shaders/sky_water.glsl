// Sky, fog (core/sky.cc) and water (§4.3; core/water.cc), operation for operation.

// ((1 + c) / 2)^(2^n) by repeated squaring.
float power_of_half_cosine(float c, int squarings) {
  precise float x = clamp01((1.0 + c) * 0.5);
  for (int k = 0; k < squarings; ++k) {
    x = x * x;
  }
  return x;
}

vec3 sky_radiance(vec3 d) {
  const vec3 horizon = f3(P.horizon);
  precise vec3 color = horizon;
  if (d.y > 0.0) {
    color = lerp3(horizon, f3(P.zenith), square_root(d.y));
  }
  precise float c = dot3(d, f3(P.sun_direction));
  const float inner = P.sun_cos_inner, outer = P.sun_cos_outer;
  precise float disc =
      inner > outer ? smooth01(divide(c - outer, inner - outer)) : (c >= inner ? 1.0 : 0.0);
  precise float halo = kHaloWeight * power_of_half_cosine(c, 5);
  precise vec3 r = color + f3(P.sun) * (20.0 * disc + halo);
  return r;
}

vec3 fog_color(vec3 d) {
  precise float c = dot3(d, f3(P.sun_direction));
  precise vec3 r = f3(P.horizon) + f3(P.sun) * (kFogSunWeight * power_of_half_cosine(c, 3));
  return r;
}

vec3 apply_fog(vec3 radiance, vec3 d, float distance) {
  precise float clear = exp2_det(-P.fog_density_log2 * distance);
  if (!(clear < 1.0)) {
    return radiance;
  }
  return lerp3(fog_color(d), radiance, clear);
}

vec3 wave_normal(float x, float z, float strength, float footprint) {
  precise float gx = 0.0, gz = 0.0;
  for (int o = 0; o < kWaveOctaves; ++o) {
    const float inv = P.wave_inv_length[o];
    precise float fade = clamp01(1.0 - 2.0 * footprint * inv);
    if (fade == 0.0) {
      continue;
    }
    float dx, dz;
    lattice_gradient_quintic(P.wave_offset_x[o] + x * inv, P.wave_offset_z[o] + z * inv, dx, dz);
    precise float a = P.wave_amplitude[o] * fade;
    gx = gx + a * dx;
    gz = gz + a * dz;
  }
  precise vec3 n = vec3(-gx * strength, 1.0, -gz * strength);
  return normalize_or(n, vec3(0.0, 1.0, 0.0));
}

vec3 shade_water(vec3 view, float surface_distance, float depth, vec3 ground, float footprint) {
  precise float f = smooth01(depth * P.inv_full_depth);
  precise vec3 s = view * surface_distance;
  precise float strength = P.wave_strength * f;
  const vec3 n = wave_normal(s.x, s.z, strength, footprint);

  precise float cos_i = clamp01(-dot3(view, n));
  precise float m = 1.0 - cos_i;
  precise float fresnel = kFresnelF0 + kFresnelRest * (m * m * m * m * m);
  precise vec3 reflected = view - n * (2.0 * dot3(view, n));
  reflected.y = abs(reflected.y);
  const vec3 sky = sky_radiance(reflected);

  precise float eta = kRelativeIndex;
  precise float k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
  precise vec3 t = view * eta + n * (eta * cos_i - square_root(k));
  precise float path = divide(depth, max_cpp(abs(t.y), kMinTransmittedCosine));
  const vec3 e = f3(P.extinction_log2);
  precise vec3 transmitted =
      vec3(exp2_det(-e.x * path), exp2_det(-e.y * path), exp2_det(-e.z * path));

  precise vec3 body_light = f3(P.sky_light) + f3(P.sun) * (0.5 * max_cpp(0.0, P.sun_direction.y));
  precise vec3 body = lerp3(f3(P.shallow), f3(P.deep), f) * body_light;
  precise vec3 under = ground * transmitted + body * (vec3(1.0) - transmitted);
  precise float reflectivity = kReflectivityBase + kReflectivityDepth * f;
  return lerp3(under, sky, fresnel * reflectivity);
}

// The pixel's extent on the water surface (shade.cc, surface_footprint).
float surface_footprint(float distance, vec3 view) {
  precise float r = divide(distance * P.pixel_angle, max_cpp(abs(view.y), kMinGrazingSine));
  return r;
}
