// Stage 8 per pixel (§4.2, §4.3; core/shade.cc, core/layer_weights.cc): the radiance of a
// covered pixel from its resolved attributes, and of an uncovered one (sky, fog, open water).

// What stage 7 resolved at a covered pixel (core/shade.h, PixelAttributes).
struct Attributes {
  float dx, dz, height;
  float dx_ddx, dx_ddy, dz_ddx, dz_ddy, height_ddx, height_ddy;
  float nx, ny, nz;
  float slope;
  float water_depth;
  float drop;     // a planet's curvature drop (core/planet_bend.h); 0 on the plane
  float lambert;  // gradient mode's interpolated per-vertex Lambert term (terrain.vert)
};

float ramp_weight(Ramp ramp, float x, float dither_offset) {
  if (!(ramp.end > ramp.start)) {
    return x >= ramp.start ? 1.0 : 0.0;
  }
  precise float t = divide(x - ramp.start, ramp.end - ramp.start) + dither_offset;
  return smooth01(t);
}

float rising(Ramp ramp, float x, float d) { return ramp.open != 0 ? 1.0 : ramp_weight(ramp, x, d); }

float falling(Ramp ramp, float x, float d) {
  precise float r = 1.0 - ramp_weight(ramp, x, d);
  return ramp.open != 0 ? 1.0 : r;
}

void layer_weights(float height, float slope, float d, out float weights[kMaxLayers]) {
  const int count = P.layer_count;
  precise float sum = 0.0;
  for (int k = 0; k < count; ++k) {
    precise float w = rising(P.layers[k].height_up, height, d) *
                      falling(P.layers[k].height_down, height, d) *
                      rising(P.layers[k].slope_up, slope, d) *
                      falling(P.layers[k].slope_down, slope, d);
    weights[k] = w;
    sum = sum + w;
  }
  if (sum > kMinWeightSum) {
    precise float inv = divide(1.0, sum);
    for (int k = 0; k < count; ++k) {
      precise float w = weights[k] * inv;
      weights[k] = w;
    }
  } else {
    precise float share = divide(1.0, float(count));
    for (int k = 0; k < count; ++k) {
      weights[k] = share;
    }
  }
}

// The layer's albedo: planar from above, or triplanar weighted by the squared normal.
vec3 layer_albedo(int layer, Attributes a, vec3 n) {
  const float inv = P.layers[layer].inv_tile;
  precise float x = P.layers[layer].offset_x + a.dx * inv;
  precise float z = P.layers[layer].offset_z + a.dz * inv;
  precise float y = P.layers[layer].offset_y + a.height * inv;
  precise float xdx = a.dx_ddx * inv, xdy = a.dx_ddy * inv;
  precise float zdx = a.dz_ddx * inv, zdy = a.dz_ddy * inv;
  precise float ydx = a.height_ddx * inv, ydy = a.height_ddy * inv;
  if (P.triplanar == 0) {
    return sample_layer(layer, P.nearest_mip != 0, x, z, xdx, zdx, xdy, zdy);
  }
  precise float w0 = n.x * n.x, w1 = n.y * n.y, w2 = n.z * n.z;
  w0 = w0 < kMinProjectionWeight ? 0.0 : w0;
  w1 = w1 < kMinProjectionWeight ? 0.0 : w1;
  w2 = w2 < kMinProjectionWeight ? 0.0 : w2;
  precise float used = 0.0;
  used = used + w0;
  used = used + w1;
  used = used + w2;
  precise vec3 sum = vec3(0.0);
  if (w0 > 0.0 || P.skip_zero_weights == 0) {
    sum = sum + sample_layer(layer, P.nearest_mip != 0, z, y, zdx, ydx, zdy, ydy) * w0;
  }
  if (w1 > 0.0 || P.skip_zero_weights == 0) {
    sum = sum + sample_layer(layer, P.nearest_mip != 0, x, z, xdx, zdx, xdy, zdy) * w1;
  }
  if (w2 > 0.0 || P.skip_zero_weights == 0) {
    sum = sum + sample_layer(layer, P.nearest_mip != 0, x, y, xdx, ydx, xdy, ydy) * w2;
  }
  precise vec3 r = sum * divide(1.0, used);
  return r;
}

// The normal the light sees: where the interpolated normal faces away from the eye, its part
// perpendicular to the view ray, normalised (shade.cc, facing_normal).
vec3 facing_normal(vec3 n, vec3 view) {
  precise float away = dot3(n, view);
  if (!(away > 0.0)) {
    return n;
  }
  precise vec3 perpendicular = n - view * away;
  return normalize_or(perpendicular, -view);
}

// Sun (Lambert, Phong) times the share `sun_share` of it the cloud layer passes (1 without
// one; no cast shadows on the GL side, and x 1 changes no bit), hemispherical sky light and
// ambient (Scape). shade.cc, light, with its sky share 1.
vec3 light(vec3 albedo, vec3 n, vec3 view, float specular, float sun_share) {
  const vec3 to_sun = f3(P.sun_direction);
  const vec3 sun = f3(P.sun);
  precise float ndl = max_cpp(0.0, dot3(n, to_sun));
  precise float sunlit = ndl * sun_share;
  precise float up = 0.5 + 0.5 * n.y;
  const vec3 hemisphere = lerp3(f3(P.ground_light), f3(P.sky_light), up);
  const float ambient = P.ambient;
  precise vec3 radiance = albedo * (sun * sunlit + hemisphere + vec3(ambient));
  if ((specular > 0.0 || P.always_specular != 0) && sunlit > 0.0) {
    precise vec3 reflected = n * (2.0 * ndl) - to_sun;
    precise float rv = -dot3(reflected, view);
    if (rv > 0.0) {
      precise float power = exp2_det(P.shininess * log2_det(rv));
      radiance = radiance + sun * ((specular * sun_share) * power);
    }
  }
  return radiance;
}

// §4.2's proto-texture shading (shading.mode = textures, shade.cc's textured_radiance).
vec3 textured_radiance(Attributes a, float distance, vec3 view, float sun_share) {
  const float relative_y = a.height;
  const vec3 n = normalize_or(vec3(a.nx, a.ny, a.nz), vec3(0.0, 1.0, 0.0));

  // Scape's dithered transitions, faded out where the noise would alias (shade.cc).
  precise float dither_offset = 0.0;
  const float inv = P.dither_inv_scale;
  precise float dither_fade = min_cpp(1.0, 2.0 - 2.0 * distance * P.pixel_angle * inv);
  if (P.dither_enabled != 0 && dither_fade > 0.0) {
    precise float px = P.dither_offset_x + a.dx * inv;
    precise float pz = P.dither_offset_z + a.dz * inv;
    precise float noise = sample_lattice_cubic(px, pz);
    dither_offset = P.dither_half_amount * noise * dither_fade;
  }
  float weights[kMaxLayers];
  layer_weights(relative_y, a.slope, dither_offset, weights);
  precise vec3 albedo = vec3(0.0);
  precise float specular = 0.0, used = 0.0;
  for (int layer = 0; layer < P.layer_count; ++layer) {
    if (weights[layer] < kMinLayerWeight) {
      weights[layer] = 0.0;
      if (P.skip_zero_weights != 0) {
        continue;
      }
    }
    albedo = albedo + layer_albedo(layer, a, n) * weights[layer];
    specular = specular + P.layers[layer].specular * weights[layer];
    used = used + weights[layer];
  }
  albedo = albedo * divide(1.0, used);
  precise float shininess_weight = divide(specular, used);
  return light(albedo, facing_normal(n, view), view, shininess_weight, sun_share);
}

vec3 terrain_radiance(Attributes a) {
  const float relative_y = a.height;
  // On a planet (dx, dz) are the bent position's and the height lies a.drop above it (shade.cc;
  // x - 0 is x: the plane's bits are unchanged).
  precise float position_y = relative_y - a.drop;
  const vec3 position = vec3(a.dx, position_y, a.dz);
  precise float distance = square_root(dot3(position, position));
  const vec3 view = normalize_or(position, f3(P.camera_forward));
  // shade.cc, lit_terrain: the cloud layer's shadow, the sun's share passed through it at the
  // pixel's footprint.
  float sun_share = 1.0;
  if (P.clouds != 0) {
    precise float footprint = distance * P.pixel_angle;
    sun_share = cloud_sun_share(position, footprint);
  }
  precise vec3 radiance;
  if (P.gradient_enabled != 0) {  // gradient_shading.glsl
    radiance = gouraud_light(gradient_albedo(relative_y), a.lambert, a.ny, sun_share);
  } else {
    radiance = textured_radiance(a, distance, view, sun_share);
  }

  precise float fog_distance = distance;
  if (P.water_enabled != 0 && P.terrain_water != 0 && relative_y < P.water_level && view.y < 0.0) {
    // On a planet the water surface lies a.drop lower too (locally flat).
    precise float surface = divide(P.water_level - a.drop, view.y);
    vec3 water_view = view;
    if (P.planet_center_distance > 0.0LF) {  // shaded in the local frame of the point
      const float center_y = float(P.planet_center_distance);
      precise float up_y = position.y + center_y;
      const vec3 up = normalize_or(vec3(position.x, up_y, position.z), vec3(0.0, 1.0, 0.0));
      water_view = to_local_frame(view, up);
    }
    const float footprint = surface_footprint(surface, water_view);
    radiance =
        shade_water(water_view, surface, max_cpp(0.0, a.water_depth), radiance, footprint);
    fog_distance = surface;
  }
  if (P.fog_enabled != 0) {
    radiance = apply_fog(radiance, view, fog_distance);
  }
  if (P.clouds != 0) {
    return clouds_over(radiance, view, fog_distance);
  }
  return radiance;
}

// No terrain at pixel (px, py): the view ray in double, rounded once (shade.cc).
vec3 background_radiance(int px, int py) {
  precise double ndc_x = 2.0LF * (double(px) + 0.5LF) / double(P.width) - 1.0LF;
  precise double ndc_y = 2.0LF * (double(py) + 0.5LF) / double(P.height) - 1.0LF;
  precise double sx = ndc_x * P.tan_half_fov_x, sy = ndc_y * P.tan_half_fov_y;
  precise double r0 = (P.forward[0] + sx * P.right[0]) + sy * P.up[0];
  precise double r1 = (P.forward[1] + sx * P.right[1]) + sy * P.up[1];
  precise double r2 = (P.forward[2] + sx * P.right[2]) + sy * P.up[2];
  const vec3 d = normalize_or(vec3(float(r0), float(r1), float(r2)), f3(P.camera_forward));
  if (P.planet_center_distance > 0.0LF) {
    return planet_background(r0, r1, r2, d);
  }
  // The sky and the fog lie beyond every distance; open water at its surface; terrain past
  // the far distance no lower than the frame's lowest (cloud_ground, where there are clouds).
  precise float end = kMaxCameraRelativeDistance;
  precise vec3 radiance;
  if (d.y < 0.0 && P.water_enabled != 0) {
    end = divide(P.water_level, d.y);
    const float footprint = surface_footprint(end, d);
    radiance = shade_water(d, end, kOpenWaterDepth, vec3(0.0), footprint);
    if (P.fog_enabled != 0) {
      radiance = apply_fog(radiance, d, end);
    }
  } else if (d.y < 0.0) {
    radiance = fog_color(d);
    if (P.clouds != 0) {
      end = min_cpp(end, divide(P.cloud_ground, d.y));  // d.y < 0
    }
  } else {
    radiance = sky_radiance(d);
  }
  if (P.clouds != 0) {
    return clouds_over(radiance, d, end);
  }
  return radiance;
}

// Stage 9 (core/srgb.h, srgb_byte): the number of decision points t_k at or below x, from
// the least float >= each t_k (a float is >= the double t_k exactly when it is >= that float).
layout(std430, binding = 2) readonly buffer SrgbBlock {
  float srgb_step[255];
};

uint srgb_byte(float x) {
  if (!(x > 0.0)) {
    return 0u;
  }
  if (x >= 1.0) {
    return 255u;
  }
  int lo = 0, hi = 255;  // steps below lo are <= x, steps from hi on are > x
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (x >= srgb_step[mid]) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return uint(lo);
}
