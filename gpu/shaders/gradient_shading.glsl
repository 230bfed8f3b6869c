// Stage 8 in shading.mode = gradient (core/gradient_shade.h): castledragmire's height gradient
// per pixel, and the Gouraud light: the per-vertex Lambert term GL interpolated (terrain.vert)
// and the hemisphere from the interpolated normal's y. Operation by operation as the C++.

vec3 gradient_albedo(float h) {
  vec3 color = f3(P.gradient_color[0]);
  for (int i = 0; i + 1 < P.gradient_count; ++i) {
    if (!(h >= P.gradient_height[i])) {
      continue;
    }
    precise float t = 1.0;
    if (!(h >= P.gradient_height[i + 1])) {
      precise float ramp = (h - P.gradient_height[i]) * P.gradient_inv_span[i];
      t = ramp < 1.0 ? ramp : 1.0;
    }
    const vec3 low = f3(P.gradient_color[i]);
    precise vec3 segment = low + (f3(P.gradient_color[i + 1]) - low) * t;
    color = segment;
  }
  return color;
}

// `sun_share`: what the cloud layer passes (1 without one); no cast shadows or sky light on
// the GL side, so the C++'s sky share is 1 (x 1 changes no bit).
vec3 gouraud_light(vec3 albedo, float lambert, float ny, float sun_share) {
  precise float sunlit = lambert * sun_share;
  precise float up = 0.5 + 0.5 * ny;
  const vec3 hemisphere = lerp3(f3(P.ground_light), f3(P.sky_light), up);
  const float ambient = P.ambient;
  precise vec3 radiance = albedo * (f3(P.sun) * sunlit + hemisphere + vec3(ambient));
  return radiance;
}
