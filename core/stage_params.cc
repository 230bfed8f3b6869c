#include "core/stage_params.h"

#include "core/octave_coordinates.h"
#include "core/stage_param_fields.h"

namespace relief {

// The field lists of the structs declared by hand elsewhere (stage_param_fields.h) must name
// their members exactly: the GLSL declarations and the layout check are made from the lists.
static_assert(RELIEF_FIELDS_TILE(ProjectorRays, float, RELIEF_PROJECTOR_RAYS_FIELDS));
static_assert(RELIEF_FIELDS_TILE(PlanetParams, float, RELIEF_PLANET_PARAMS_FIELDS));
static_assert(RELIEF_FIELDS_TILE(SketchParams, float, RELIEF_SKETCH_PARAMS_FIELDS));
static_assert(RELIEF_FIELDS_TILE(Vec3, float, RELIEF_VEC3_FIELDS));
static_assert(RELIEF_FIELDS_TILE(ProjectorRays, double, RELIEF_PROJECTOR_RAYS_FIELDS));
static_assert(RELIEF_FIELDS_TILE(PlanetParams, double, RELIEF_PLANET_PARAMS_FIELDS));
static_assert(RELIEF_FIELDS_TILE(SketchParams, double, RELIEF_SKETCH_PARAMS_FIELDS));
static_assert(RELIEF_FIELDS_TILE(Vec3, double, RELIEF_VEC3_FIELDS));

namespace {

template <class Real>
Vec3<Real> rounded(const glm::dvec3& v) {
  return {Real(v.x), Real(v.y), Real(v.z)};
}

template <class Real>
RampParams<Real> rounded(const Ramp& r) {
  return {Real(r.start), Real(r.end), r.open ? 1 : 0};
}

template <class Real>
DomainParams<Real> make_domain_params(const FramePlan& plan) {
  DomainParams<Real> p{ProjectorRays<Real>(plan.projector)};
  p.y0 = Real(plan.screen.y0);
  p.step_y = Real(plan.screen.step_y);
  p.c0 = Real(plan.lod.c0);
  p.c1 = Real(plan.lod.c1);
  p.nu_max = Real(plan.lod.nu_max);
  p.min_spacing_sq = Real(limits::kMinSpacingSq);
  p.width = plan.layout.width;
  p.height = plan.layout.height;
  p.pitch = plan.layout.pitch;
  p.terrain_visible = plan.projector.terrain_visible ? 1 : 0;
  p.whole_octaves = plan.lod.whole_octaves ? 1 : 0;
  return p;
}

}  // namespace

template <class Real>
FbmParams<Real> make_fbm_params(const TerrainPlan& plan) {
  FbmParams<Real> p;
  const OctaveTable& o = plan.octaves;
  p.count = o.count;
  p.interpolant = static_cast<std::int32_t>(plan.interpolant);
  for (int n = 0; n < o.count; ++n) {
    p.frequency[n] = Real(o.frequency[n]);
    p.amplitude[n] = Real(o.amplitude[n]);
    p.offset_x[n] = Real(o.offset_x[n]);
    p.offset_z[n] = Real(o.offset_z[n]);
    p.exact_coordinates[n] = 1;
    const ScalePieces<Real> pieces = split_scale<Real>(o.scale[n]);
    for (int q = 0; q < 3; ++q) {
      p.scale_piece[q][n] = pieces.piece[q];
      p.scale_piece_hi[q][n] = pieces.hi[q];
      p.scale_piece_lo[q][n] = pieces.lo[q];
    }
  }
  p.period = Real(plan.lattice->size);
  p.inv_period = Real(1) / p.period;
  p.inv_scale = Real(plan.inv_horizontal_scale);
  p.relative_base_height = Real(plan.relative_base_height);
  p.height_scale = Real(plan.amplitude);
  const WarpPlan& w = plan.warp;
  p.warp = w.enabled ? 1 : 0;
  p.c1x = Real(w.c1x), p.c1z = Real(w.c1z), p.c2x = Real(w.c2x), p.c2z = Real(w.c2z);
  p.c3x = Real(w.c3x), p.c3z = Real(w.c3z), p.r0x = Real(w.r0x), p.r0z = Real(w.r0z);
  p.t0x = Real(w.t0x), p.t0z = Real(w.t0z);
  p.roughness0 = Real(w.roughness0);
  p.guard_sq = Real(w.guard_sq);
  p.min_rotation_sq = Real(limits::kMinRotationLengthSq);
  p.lacunarity = Real(w.lacunarity);
  return p;
}

template <class Real>
DomainRows<Real> make_domain_rows(const FramePlan& plan) {
  const std::size_t rows = static_cast<std::size_t>(plan.layout.height) + 2;
  DomainRows<Real> table{std::vector<Real>(rows), std::vector<Real>(rows), std::vector<Real>(rows)};
  for (int j = -1; j <= plan.layout.height; ++j) {
    const auto k = static_cast<std::size_t>(j + 1);
    table.descent[k] = Real(projector_descent(plan.projector, plan.screen.image_y(j)));
    table.x0[k] = Real(plan.screen.row_origin(j));
    table.step_x[k] = Real(plan.screen.row_step(j));
  }
  return table;
}

template <class Real>
TerrainParams<Real> make_terrain_params(const FramePlan& plan) {
  TerrainParams<Real> p{make_domain_params<Real>(plan),
                        make_domain_rows<Real>(plan),
                        make_fbm_params<Real>(plan.terrain),
                        make_sketch_params<Real>(plan.terrain.sketch_plan, plan.terrain.sketch),
                        {},
                        {},
                        make_planet_params<Real>(plan.planet)};
  SurfaceParams<Real>& s = p.surface;
  s.width = plan.layout.width;
  s.height = plan.layout.height;
  s.pitch = plan.layout.pitch;
  s.water_enabled = plan.water_enabled ? 1 : 0;
  s.water_level = Real(plan.relative_water_level);
  s.min_sine_sq = Real(limits::kMinTangentSine * limits::kMinTangentSine);
  s.max_slope = Real(limits::kMaxSlope);
  s.inv_silhouette_facing = Real(1.0 / limits::kSilhouetteFacing);
  s.hidden_side_weight = Real(limits::kHiddenSideWeight);
  TransformParams<Real>& t = p.transform;
  for (int c = 0; c < 3; ++c) {
    t.row_x[c] = Real(plan.clip.row_x[c]);
    t.row_y[c] = Real(plan.clip.row_y[c]);
    t.row_w[c] = Real(plan.clip.row_w[c]);
  }
  t.z_clip = Real(plan.clip.z_clip);
  return p;
}

// The gradient's stops rounded once; each segment's 1 / span from the rounded heights, so
// that a step stays a step (0) and a ramp's t = (h - height[i]) inv_span reaches 1 at its end.
template <class Real>
void add_gradient(const GradientPlan& gradient, ShadeParams<Real>& p) {
  p.gradient_enabled = gradient.enabled ? 1 : 0;
  const std::size_t count = std::min(gradient.height.size(), limits::kMaxGradientStops);
  p.gradient_count = gradient.enabled ? static_cast<std::int32_t>(count) : 0;
  for (std::size_t k = 0; k < count; ++k) {
    p.gradient_height[k] = Real(gradient.height[k]);
    p.gradient_color[k] = rounded<Real>(gradient.color[k]);
  }
  for (std::size_t k = 0; k + 1 < count; ++k) {
    const double span = double(p.gradient_height[k + 1]) - double(p.gradient_height[k]);
    p.gradient_inv_span[k] = span > 0.0 ? Real(1.0 / span) : Real(0);  // domain: span > 0
  }
}

template <class Real>
ShadeParams<Real> make_shade_params(const ShadingPlan& plan) {
  ShadeParams<Real> p;
  p.width = plan.width;
  p.height = plan.height;
  p.layer_count = static_cast<std::int32_t>(plan.layers.size());
  p.triplanar = plan.triplanar ? 1 : 0;
  p.nearest_mip = plan.nearest_mip ? 1 : 0;
  for (std::size_t k = 0; k < plan.layers.size(); ++k) {
    const LayerPlan& l = plan.layers[k];
    LayerParams<Real>& q = p.layers[k];
    q.inv_tile = Real(l.inv_tile);
    q.offset_x = Real(l.offset_x);
    q.offset_y = Real(l.offset_y);
    q.offset_z = Real(l.offset_z);
    q.height_up = rounded<Real>(l.height_up);
    q.height_down = rounded<Real>(l.height_down);
    q.slope_up = rounded<Real>(l.slope_up);
    q.slope_down = rounded<Real>(l.slope_down);
    q.specular = Real(l.specular);
  }
  add_gradient(plan.gradient, p);
  const LightPlan& light = plan.light;
  p.sun_direction = rounded<Real>(light.sun_direction);
  p.sun = rounded<Real>(light.sun);
  p.sky_light = rounded<Real>(light.sky);
  p.ground_light = rounded<Real>(light.ground);
  p.ambient = Real(light.ambient);
  p.shininess = Real(light.shininess);
  p.exposure = Real(light.exposure);
  p.zenith = rounded<Real>(plan.sky.zenith);
  p.horizon = rounded<Real>(plan.sky.horizon);
  p.sun_cos_inner = Real(plan.sky.sun_cos_inner);
  p.sun_cos_outer = Real(plan.sky.sun_cos_outer);
  p.fog_density_log2 = Real(plan.sky.fog_density_log2);
  p.skybox = plan.sky.skybox ? 1 : 0;
  p.skybox_sun = plan.sky.skybox_sun ? 1 : 0;
  const AtmospherePlan& a = plan.sky.atmosphere;
  p.atmosphere = a.enabled ? 1 : 0;
  p.atmosphere_density = Real(a.density);
  p.atmosphere_log2_density = Real(a.log2_density);
  p.atmosphere_scale_height = Real(a.scale_height);
  p.atmosphere_inv_scale_height = Real(a.inv_scale_height);
  p.atmosphere_sun_slope_length = Real(a.sun_slope_length);
  p.atmosphere_grazing_term = Real(a.grazing_term);
  p.atmosphere_mie_a = Real(a.mie_a);
  p.atmosphere_mie_b = Real(a.mie_b);
  p.atmosphere_extinction_log2 = rounded<Real>(a.extinction_log2);
  p.atmosphere_camera_sun_depth_log2 = rounded<Real>(a.camera_sun_depth_log2);
  p.atmosphere_rayleigh_sun = rounded<Real>(a.rayleigh_sun);
  p.atmosphere_mie_sun = rounded<Real>(a.mie_sun);
  const CloudPlan& cloud = plan.clouds;
  p.clouds = cloud.enabled ? 1 : 0;
  p.cloud_octaves = cloud.octaves;
  p.cloud_warped = cloud.warped ? 1 : 0;
  p.cloud_steps = cloud.steps;
  p.cloud_bottom = Real(cloud.bottom);
  p.cloud_top = Real(cloud.top);
  p.cloud_ground = Real(cloud.ground);
  p.cloud_extinction_log2 = Real(cloud.extinction_log2);
  p.cloud_sun_depth_log2 = Real(cloud.sun_depth_log2);
  p.cloud_threshold = Real(cloud.threshold);
  p.cloud_sharpness = Real(cloud.sharpness);
  p.cloud_mean_density = Real(cloud.mean_density);
  for (int o = 0; o < limits::kMaxCloudOctaves; ++o) {
    p.cloud_inv_scale[o] = Real(cloud.inv_scale[o]);
    p.cloud_offset_x[o] = Real(cloud.offset_x[o]);
    p.cloud_offset_z[o] = Real(cloud.offset_z[o]);
    p.cloud_amplitude[o] = Real(cloud.amplitude[o]);
    p.cloud_warp_gain[o] = Real(cloud.warp_gain[o]);
  }
  for (int k = 0; k < 4; ++k) {
    p.cloud_warp_offset[k] = Real(cloud.warp_offset[k]);
  }
  p.cloud_sun_light = rounded<Real>(cloud.sun_light);
  p.cloud_sky_light = rounded<Real>(cloud.sky_light);
  const WaterPlan& w = plan.water;
  p.water_enabled = w.enabled ? 1 : 0;
  p.terrain_water = p.water_enabled;  // until the frame knows the heights it draws
  p.water_level = Real(w.level);
  p.shallow = rounded<Real>(w.shallow);
  p.deep = rounded<Real>(w.deep);
  p.extinction_log2 = rounded<Real>(w.extinction_log2);
  p.inv_full_depth = Real(w.inv_full_depth);
  p.wave_strength = Real(w.strength);
  p.terrain_reflections = w.reflect_terrain ? 1 : 0;
  for (int o = 0; o < kWaveOctaves; ++o) {
    p.wave_inv_length[o] = Real(w.wave_inv_length[o]);
    p.wave_offset_x[o] = Real(w.wave_offset_x[o]);
    p.wave_offset_z[o] = Real(w.wave_offset_z[o]);
    p.wave_amplitude[o] = Real(w.wave_amplitude[o]);
  }
  p.dither_enabled = plan.dither.amount > 0.0 ? 1 : 0;
  p.dither_half_amount = Real(0.5 * plan.dither.amount);
  p.dither_inv_scale = Real(plan.dither.inv_scale);
  p.dither_offset_x = Real(plan.dither.offset_x);
  p.dither_offset_z = Real(plan.dither.offset_z);
  p.pixel_angle = Real(plan.pixel_angle);
  // The atmosphere replaces the fog: its pass runs wherever it is on.
  p.fog_enabled = a.enabled || plan.sky.fog_density_log2 > 0.0 ? 1 : 0;
  p.camera_forward = rounded<Real>(plan.camera.forward);
  for (int c = 0; c < 3; ++c) {
    p.forward[c] = plan.camera.forward[c];
    p.right[c] = plan.camera.right[c];
    p.up[c] = plan.camera.up[c];
  }
  p.tan_half_fov_x = plan.camera.tan_half_fov_x;
  p.tan_half_fov_y = plan.camera.tan_half_fov_y;
  return p;
}

template <class Real>
void add_gouraud_lighting(const ShadingPlan& plan, TransformParams<Real>& t) {
  t.gouraud = plan.gradient.enabled ? 1 : 0;
  t.sun_x = Real(plan.light.sun_direction.x);
  t.sun_y = Real(plan.light.sun_direction.y);
  t.sun_z = Real(plan.light.sun_direction.z);
}

template <class Real>
void add_planet_shading(const FramePlan& plan, double base_height, ShadeParams<Real>& p) {
  const PlanetPlan& planet = plan.planet;
  if (!planet.enabled || !(planet.center_distance > 0.0)) {
    return;
  }
  const double D = planet.center_distance;
  const double R = planet.radius;
  p.planet_center_distance = D;
  // D - R = a; D - (R + w) = -(relative water level), w the water level above the datum.
  p.planet_datum_c = planet.altitude * (D + R);
  const double water_elevation = plan.relative_water_level + plan.camera.position.y - base_height;
  p.planet_water_c = -plan.relative_water_level * (D + R + water_elevation);
  // sin = R / D, cos = sqrt(a (D + R)) / D; a camera inside the datum sees no limb.
  p.planet_limb_angle =
      planet.altitude > 0.0 ? std::atan2(R, std::sqrt(p.planet_datum_c)) : M_PI / 2;
}

template DomainRows<float> make_domain_rows<float>(const FramePlan&);
template DomainRows<double> make_domain_rows<double>(const FramePlan&);
template FbmParams<float> make_fbm_params<float>(const TerrainPlan&);
template FbmParams<double> make_fbm_params<double>(const TerrainPlan&);
template TerrainParams<float> make_terrain_params<float>(const FramePlan&);
template TerrainParams<double> make_terrain_params<double>(const FramePlan&);
template ShadeParams<float> make_shade_params<float>(const ShadingPlan&);
template ShadeParams<double> make_shade_params<double>(const ShadingPlan&);
template void add_gouraud_lighting<float>(const ShadingPlan&, TransformParams<float>&);
template void add_gouraud_lighting<double>(const ShadingPlan&, TransformParams<double>&);
template void add_planet_shading<float>(const FramePlan&, double, ShadeParams<float>&);
template void add_planet_shading<double>(const FramePlan&, double, ShadeParams<double>&);

}  // namespace relief
