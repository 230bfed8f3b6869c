#include "core/shading_plan.h"

#include <algorithm>
#include <cmath>

namespace relief {

namespace {

constexpr double kDegree = M_PI / 180.0;

double positive_fraction(double x) {
  return x - std::floor(x);
}

double positive_mod(double x, double period) {
  const double r = std::fmod(x, period);
  return r < 0 ? r + period : r;
}

// A ramp of width 2 spread around `edge`; `open` when the edge is the end of the domain.
Ramp make_ramp(double edge, double spread, bool open) {
  return Ramp{edge - spread, edge + spread, open};
}

// Slope ramps in tangent space: |grad h| = tan(angle); angles clamped to [0, 89.9] degrees so
// that the tangent is finite.
Ramp make_slope_ramp(double edge_deg, double spread_deg, bool open) {
  const auto tangent = [](double deg) { return std::tan(std::clamp(deg, 0.0, 89.9) * kDegree); };
  return Ramp{tangent(edge_deg - spread_deg), tangent(edge_deg + spread_deg), open};
}

glm::dvec3 vec(const Vec3d& v) {
  return {v[0], v[1], v[2]};
}

}  // namespace

ShadingPlan make_shading_plan(const Scene& scene, const FramePlan& frame, int lattice_size) {
  ShadingPlan plan;
  plan.camera = frame.camera;
  plan.width = scene.viewport.width;
  plan.height = scene.viewport.height;
  plan.pixel_angle = 2.0 * frame.camera.tan_half_fov_y / scene.viewport.height;
  plan.triplanar = scene.shading.triplanar;
  plan.nearest_mip = scene.shading.texture_filter == TextureFilter::kBilinear;
  const glm::dvec3 camera = frame.camera.position;
  const double water_level = scene.terrain.water_level.value_or(0.0);

  for (std::size_t k = 0; k < scene.shading.layers.size(); ++k) {
    const MaterialLayer& m = scene.shading.layers[k];
    LayerPlan layer;
    layer.inv_tile = 1.0 / m.tile_size;  // tile_size > 0 (validated)
    layer.offset_x = positive_fraction(camera.x * layer.inv_tile);
    layer.offset_y = positive_fraction(camera.y * layer.inv_tile);
    layer.offset_z = positive_fraction(camera.z * layer.inv_tile);
    // Ramps in the pixels' camera-relative heights, formed in double.
    const double shift = (m.height_relative_to_water ? water_level : 0.0) - camera.y;
    const double bound = limits::kMaxBaseHeight;
    layer.height_up = make_ramp(m.height[0] + shift, m.height_spread, m.height[0] <= -bound);
    layer.height_down = make_ramp(m.height[1] + shift, m.height_spread, m.height[1] >= bound);
    layer.slope_up = make_slope_ramp(m.slope_deg[0], m.slope_spread_deg, m.slope_deg[0] <= 0.0);
    layer.slope_down = make_slope_ramp(m.slope_deg[1], m.slope_spread_deg, m.slope_deg[1] >= 90.0);
    layer.specular = m.specular;
    plan.layers.push_back(layer);
  }

  GradientPlan& gradient = plan.gradient;
  gradient.enabled = scene.shading.mode == ShadingMode::kGradient;
  if (gradient.enabled) {
    const GradientSettings& g = scene.shading.gradient;
    const double low = g.range ? (*g.range)[0] : frame.bounds.world_min;
    const double high = g.range ? (*g.range)[1] : frame.bounds.world_max;
    for (const GradientStop& stop : g.stops) {
      // low + at (high - low): between low and high for at in [0, 1] (high >= low).
      gradient.height.push_back((low + stop.at * (high - low)) - camera.y);
      gradient.color.push_back(vec(stop.color));
    }
  }

  const LightingSettings& l = scene.lighting;
  const double azimuth = l.sun_azimuth_deg * kDegree, elevation = l.sun_elevation_deg * kDegree;
  plan.light.sun_direction =
      glm::dvec3(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                 -std::cos(azimuth) * std::cos(elevation));
  plan.light.sun = vec(l.sun_color) * l.sun_intensity;
  plan.light.sky = vec(l.sky_color) * l.sky_intensity;
  plan.light.ground = vec(l.ground_color) * l.sky_intensity;
  plan.light.ambient = l.ambient;
  plan.light.shininess = l.shininess;
  plan.light.exposure = l.exposure;

  plan.sky.zenith = vec(scene.sky.zenith_color);
  plan.sky.horizon = vec(scene.sky.horizon_color);
  plan.sky.sun_cos_inner = std::cos(scene.sky.sun_disc_deg * kDegree);
  plan.sky.sun_cos_outer = std::cos(scene.sky.sun_disc_deg * 1.25 * kDegree);
  plan.sky.fog_density_log2 = scene.sky.fog_density / M_LN2;
  plan.sky.skybox = scene.sky.skybox.has_value();
  plan.sky.skybox_sun = !scene.sky.skybox || scene.sky.skybox->sun_disc;
  if (scene.sky.atmosphere) {
    // The atmosphere's sun: what reaches the camera's height lights the ground (atmosphere_plan.h).
    plan.sky.atmosphere = make_atmosphere_plan(*scene.sky.atmosphere, camera.y, elevation,
                                               scene.sky.sun_disc_deg * kDegree, plan.light.sun);
    plan.light.sun = plan.sky.atmosphere.ground_sun;
  }

  if (scene.sky.clouds) {  // lit by the sun that reaches the ground (the atmosphere's, above)
    plan.clouds =
        make_cloud_plan(*scene.sky.clouds, camera, frame.bounds.world_min, plan.light.sun_direction,
                        plan.light.sun, plan.light.sky, plan.light.ambient, lattice_size);
  }

  const WaterSettings& w = scene.water;
  WaterPlan& water = plan.water;
  water.enabled = frame.water_enabled;  // one decision for every stage (frame_plan.h)
  water.level = water_level - camera.y;
  water.shallow = vec(w.shallow_color);
  water.deep = vec(w.deep_color);
  water.extinction_log2 = vec(w.extinction) / M_LN2;
  water.inv_full_depth = 1.0 / w.full_depth;
  water.strength = w.wave_strength;
  water.reflect_terrain = water.enabled && w.reflect_terrain;
  // Three octaves of waves, each shorter, weaker and travelling in its own direction.
  const double lengths[kWaveOctaves] = {1.0, 1.0 / 2.3, 1.0 / 5.1};
  const double amplitudes[kWaveOctaves] = {1.0, 0.5, 0.25};
  const double directions_deg[kWaveOctaves] = {20.0, 75.0, -40.0};
  const double period = lattice_size;
  for (int o = 0; o < kWaveOctaves; ++o) {
    const double length = w.wave_length * lengths[o];
    const double inv = 1.0 / length;
    const double distance = w.wave_speed * std::sqrt(lengths[o]) * scene.time;  // deep water:
    const double a = directions_deg[o] * kDegree;  // speed grows with sqrt(length)
    water.wave_inv_length[o] = inv;
    water.wave_amplitude[o] = amplitudes[o];
    water.wave_offset_x[o] = positive_mod((camera.x + std::cos(a) * distance) * inv, period);
    water.wave_offset_z[o] = positive_mod((camera.z + std::sin(a) * distance) * inv, period);
  }

  plan.dither.amount = scene.shading.dither;
  plan.dither.inv_scale = 1.0 / scene.shading.dither_scale;
  plan.dither.offset_x = positive_mod(camera.x * plan.dither.inv_scale + 0.5 * period, period);
  plan.dither.offset_z = positive_mod(camera.z * plan.dither.inv_scale + 0.25 * period, period);
  return plan;
}

}  // namespace relief
