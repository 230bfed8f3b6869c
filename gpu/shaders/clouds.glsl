// The cloud layer (castledragmire's and Miller's fractal cloud layers; core/clouds.cc,
// docs/stages.md, "Clouds"), operation for operation: a band
// of heights [cloud_bottom, cloud_top] whose density over (x, z) is domain-warped fBm of the
// terrain's own lattice (sample_lattice_cubic), read at cloud_steps points of a path through
// it, and the light behind it dimmed by Beer-Lambert's e^-tau (exp2_det of tau / ln 2).
// Every std::max and std::min is max_cpp and min_cpp: their first argument unless the
// comparison says otherwise, as in C++.

struct CloudPath {
  float start;
  float length;  // 0: the path misses the layer
};

// clouds.cc, cloud_path: where a path from height y0 along a unit direction of vertical part
// dy, from 0 to `end`, lies in the layer; |dy| floored at kCloudMinSlope (sign kept), so both
// crossings are finite.
CloudPath cloud_path(float y0, float dy, float end) {
  const float slope = kCloudMinSlope;
  const float safe_dy = dy >= 0.0 ? max_cpp(dy, slope) : min_cpp(dy, -slope);
  precise float t_bottom = divide(P.cloud_bottom - y0, safe_dy);
  precise float t_top = divide(P.cloud_top - y0, safe_dy);
  const float start = max_cpp(0.0, min_cpp(t_bottom, t_top));
  const float stop = min_cpp(end, max_cpp(t_bottom, t_top));
  precise float length = stop - start;
  CloudPath path;
  path.start = start;
  path.length = max_cpp(0.0, length);
  return path;
}

// clouds.cc, octave_fade: clamp(2 - 2 footprint / cell, 0, 1) of an octave with `inv_cell`
// cells per world unit.
float cloud_octave_fade(float footprint, float inv_cell) {
  precise float ramp = 2.0 - 2.0 * footprint * inv_cell;
  return min_cpp(1.0, max_cpp(0.0, ramp));
}

// clouds.cc, cloud_density: D in [0, 1] at camera-relative (x, z) for a footprint there.
float cloud_density(float x, float z, float footprint) {
  const float fade0 = cloud_octave_fade(footprint, P.cloud_inv_scale[0]);
  if (!(fade0 > 0.0)) {
    return P.cloud_mean_density;
  }
  precise float warp_x = 0.0, warp_z = 0.0;
  if (P.cloud_warped != 0) {
    const float inv = P.cloud_inv_scale[0];
    precise float wx0 = P.cloud_warp_offset[0] + x * inv, wz0 = P.cloud_warp_offset[1] + z * inv;
    precise float wx1 = P.cloud_warp_offset[2] + x * inv, wz1 = P.cloud_warp_offset[3] + z * inv;
    warp_x = sample_lattice_cubic(wx0, wz0);
    warp_z = sample_lattice_cubic(wx1, wz1);
  }
  precise float n = 0.0;
  for (int i = 0; i < P.cloud_octaves; ++i) {
    const float inv = P.cloud_inv_scale[i];
    const float fade = cloud_octave_fade(footprint, inv);
    if (!(fade > 0.0)) {
      break;  // each later octave's cell is smaller still
    }
    precise float u = (P.cloud_offset_x[i] + x * inv) + warp_x * P.cloud_warp_gain[i];
    precise float v = (P.cloud_offset_z[i] + z * inv) + warp_z * P.cloud_warp_gain[i];
    n = n + (P.cloud_amplitude[i] * fade) * sample_lattice_cubic(u, v);
  }
  precise float raw = (n - P.cloud_threshold) * P.cloud_sharpness;
  const float density = min_cpp(1.0, max_cpp(0.0, raw));
  precise float r = P.cloud_mean_density + (density - P.cloud_mean_density) * fade0;
  return r;
}

// clouds.cc, path_density: the mean density over cloud_steps points of `path` from `origin`
// along unit `dir`, `horizontal` the length of dir's (x, z). The footprint at distance t is
// `footprint` where `from_camera` is false (a point's ray toward the sun), else
// (origin_distance + t) x stretch (a view ray); either widened to kCloudSpanFootprint of the
// horizontal span each point stands for.
float cloud_path_density(vec3 origin, vec3 dir, float horizontal, CloudPath path,
                         bool from_camera, float footprint, float origin_distance,
                         float stretch) {
  precise float inv_steps = divide(1.0, float(P.cloud_steps));  // cloud_steps >= 1
  precise float span = path.length * horizontal * inv_steps * kCloudSpanFootprint;
  precise float sum = 0.0;
  for (int k = 0; k < P.cloud_steps; ++k) {
    precise float t = path.start + path.length * ((float(k) + 0.5) * inv_steps);
    precise float at = from_camera ? (origin_distance + t) * stretch : footprint;
    precise float x = origin.x + t * dir.x, z = origin.z + t * dir.z;
    sum = sum + cloud_density(x, z, max_cpp(at, span));
  }
  precise float mean = sum * inv_steps;
  return mean;
}

// The length of unit d's horizontal part (a sum of squares: the root's domain).
float cloud_horizontal_length(vec3 d) {
  precise float sum = d.x * d.x + d.z * d.z;
  return square_root(sum);
}

// clouds.cc, cloud_sun_share: the share of the sun's light that passes the layer on its way to
// the camera-relative `position`, whose pixel's footprint is `footprint`.
float cloud_sun_share(vec3 position, float footprint) {
  const vec3 s = f3(P.sun_direction);
  if (!(s.y > 0.0)) {
    return 1.0;
  }
  const CloudPath path =
      cloud_path(position.y, max_cpp(s.y, kCloudMinSunSine), kMaxCameraRelativeDistance);
  if (!(path.length > 0.0)) {
    return 1.0;
  }
  const float density = cloud_path_density(position, s, cloud_horizontal_length(s), path, false,
                                           footprint, 0.0, 0.0);
  precise float depth = P.cloud_extinction_log2 * density * path.length;
  return exp2_det(-depth);
}

// clouds.cc, clouds_over_from: `radiance` (already fogged) seen along unit `d` from the
// camera-relative `origin`, which the camera sees `origin_distance` away, up to `end`.
vec3 clouds_over_from(vec3 radiance, vec3 origin, float origin_distance, vec3 d, float end) {
  const CloudPath path = cloud_path(origin.y, d.y, end);
  if (!(path.length > 0.0)) {
    return radiance;
  }
  // The footprint on the layer: the water's rule (surface_footprint), from the camera.
  precise float stretch = divide(P.pixel_angle, max_cpp(abs(d.y), kMinGrazingSine));
  const float density = cloud_path_density(origin, d, cloud_horizontal_length(d), path, true,
                                           0.0, origin_distance, stretch);
  precise float depth = P.cloud_extinction_log2 * density * path.length;
  const float transmittance = exp2_det(-depth);
  precise float sun_depth = density * P.cloud_sun_depth_log2;
  precise vec3 light = f3(P.cloud_sky_light) + f3(P.cloud_sun_light) * exp2_det(-sun_depth);
  precise float middle = origin_distance + (path.start + path.length * 0.5);
  const vec3 seen = P.fog_enabled != 0 ? apply_fog(light, d, middle) : light;
  precise vec3 r = radiance * transmittance + seen * (1.0 - transmittance);
  return r;
}

// clouds.cc, clouds_over: from the camera (origin 0, distance 0).
vec3 clouds_over(vec3 radiance, vec3 d, float end) {
  return clouds_over_from(radiance, vec3(0.0), 0.0, d, end);
}
