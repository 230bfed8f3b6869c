// Water (§4.3; core/water.cc), operation for operation: the waves' normal, the reflected sky
// (through the cloud layer: clouds.glsl), the refracted ground and the body colour.

vec3 wave_normal(float x, float z, float strength, float footprint) {
  precise float gx = 0.0, gz = 0.0;
  for (int o = 0; o < kWaveOctaves; ++o) {
    const float inv = P.wave_inv_length[o];
    precise float fade = clamp01(1.0 - 2.0 * footprint * inv);
    if (fade == 0.0) {
      continue;
    }
    float dx, dz;
    // The coordinates in precise variables, not as call arguments: a * b + c unfused there on
    // every compiler, not only on one that carries `precise` through inlining.
    precise float px = P.wave_offset_x[o] + x * inv, pz = P.wave_offset_z[o] + z * inv;
    lattice_gradient_quintic(px, pz, dx, dz);
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
  vec3 sky = sky_radiance(reflected);
  if (P.clouds != 0) {  // from the surface point, to the sky
    sky = clouds_over_from(sky, s, surface_distance, reflected, kMaxCameraRelativeDistance);
  }

  precise float eta = kRelativeIndex;
  precise float k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
  precise vec3 t = view * eta + n * (eta * cos_i - square_root(k));
  precise float path = divide(depth, max_cpp(abs(t.y), kMinTransmittedCosine));
  const vec3 e = f3(P.extinction_log2);
  precise vec3 transmitted =
      vec3(exp2_det(-e.x * path), exp2_det(-e.y * path), exp2_det(-e.z * path));

  // The sun's part through the cloud layer above the surface point, where there is one (no
  // cast shadow on the GL side: water.cc's sun_share is 1, and x 1 changes no bit).
  precise vec3 sun_part = f3(P.sun) * (0.5 * max_cpp(0.0, P.sun_direction.y));
  if (P.clouds != 0) {
    sun_part = sun_part * cloud_sun_share(s, footprint);
  }
  precise vec3 body_light = f3(P.sky_light) + sun_part;
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
