// ShadeParams<float> (core/stage_params.h) as its bytes lie in C++: a std430 storage block
// whose members follow the struct field by field. Under std430 a scalar aligns to 4, a double
// to 8, and a struct or array to its largest member, as on x86-64 in C++; only vec3 differs
// (16-byte alignment), so Vec3<float> is mirrored by Float3, a struct of three floats
// (12 bytes, alignment 4). tests/gl_shading_test.cc compares every member's GL_OFFSET with
// offsetof(). docs/gl-shading.md, "The layout rule".
struct Float3 {
  float x, y, z;
};

struct Ramp {
  float start;
  float end;
  int open;
};

struct Layer {
  float inv_tile;
  float offset_x, offset_y, offset_z;
  Ramp height_up, height_down;
  Ramp slope_up, slope_down;
  float specular;
};

layout(std430, binding = 0) readonly buffer ShadeParamsBlock {
  int width, height;
  int layer_count;
  int triplanar;
  Layer layers[kMaxLayers];
  Float3 sun_direction, sun, sky_light, ground_light;
  float ambient, shininess, exposure;
  Float3 zenith, horizon;
  float sun_cos_inner, sun_cos_outer, fog_density_log2;
  int water_enabled;
  float water_level;
  Float3 shallow, deep, extinction_log2;
  float inv_full_depth, wave_strength;
  float wave_inv_length[kWaveOctaves], wave_offset_x[kWaveOctaves];
  float wave_offset_z[kWaveOctaves], wave_amplitude[kWaveOctaves];
  int dither_enabled;
  float dither_half_amount;
  float dither_inv_scale, dither_offset_x, dither_offset_z;
  float pixel_angle;
  int fog_enabled;
  int terrain_water;
  int always_specular;
  int skip_zero_weights;
  int nearest_mip;
  int reserved[3];
  Float3 camera_forward;
  double forward[3], right[3], up[3];
  double tan_half_fov_x, tan_half_fov_y;
  double planet_center_distance, planet_limb_angle, planet_water_c, planet_datum_c;
}
P;

vec3 f3(Float3 v) { return vec3(v.x, v.y, v.z); }
