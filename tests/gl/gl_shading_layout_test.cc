// The GLSL blocks that take the stage parameter structs as bytes (gpu/shaders/
// shade_params.glsl.in, terrain.vert.in, generated) must lay every member out where C++ does:
// each member's GL_OFFSET (and the
// strides of arrays) as the linked program reports them, against the member's offset in the
// C++ object. docs/gl-shading.md, "The layout rule".
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/limits.h"
#include "core/stage_params.h"
#include "gpu/gl_shading.h"
#include "tests/gl/gl_test_context.h"

namespace relief {
namespace {

struct Expected {
  int offset;
  int array_stride;  // 0: no array
};

template <class Struct>
class Offsets {
 public:
  explicit Offsets(const std::string& prefix) : prefix_(prefix) {}
  void add(const std::string& name, const void* member, int array_stride = 0) {
    const auto offset = static_cast<const char*>(member) - reinterpret_cast<const char*>(&object_);
    table_[prefix_ + name] = {static_cast<int>(offset), array_stride};
  }
  void add3(const std::string& name, const Vec3<float>& v) {
    add(name + ".x", &v.x);
    add(name + ".y", &v.y);
    add(name + ".z", &v.z);
  }
  const Struct& object() const { return object_; }
  const std::map<std::string, Expected>& table() const { return table_; }

 private:
  Struct object_{};
  std::string prefix_;
  std::map<std::string, Expected> table_;
};

// Every C++ member of ShadeParams<float>, named as GL names the block's buffer variables:
// element 0 of the top-level array of structs (GL_TOP_LEVEL_ARRAY_STRIDE gives the others).
Offsets<ShadeParams<float>> shade_offsets() {
  Offsets<ShadeParams<float>> o("ShadeParamsBlock.");
  const ShadeParams<float>& p = o.object();
  o.add("width", &p.width);
  o.add("height", &p.height);
  o.add("layer_count", &p.layer_count);
  o.add("triplanar", &p.triplanar);
  const LayerParams<float>& l = p.layers[0];
  o.add("layers[0].inv_tile", &l.inv_tile);
  o.add("layers[0].offset_x", &l.offset_x);
  o.add("layers[0].offset_y", &l.offset_y);
  o.add("layers[0].offset_z", &l.offset_z);
  const std::pair<const char*, const RampParams<float>*> ramps[] = {{"height_up", &l.height_up},
                                                                    {"height_down", &l.height_down},
                                                                    {"slope_up", &l.slope_up},
                                                                    {"slope_down", &l.slope_down}};
  for (const auto& [name, ramp] : ramps) {
    o.add(std::string("layers[0].") + name + ".start", &ramp->start);
    o.add(std::string("layers[0].") + name + ".end", &ramp->end);
    o.add(std::string("layers[0].") + name + ".open", &ramp->open);
  }
  o.add("layers[0].specular", &l.specular);
  o.add3("sun_direction", p.sun_direction);
  o.add3("sun", p.sun);
  o.add3("sky_light", p.sky_light);
  o.add3("ground_light", p.ground_light);
  o.add("ambient", &p.ambient);
  o.add("shininess", &p.shininess);
  o.add("exposure", &p.exposure);
  o.add3("zenith", p.zenith);
  o.add3("horizon", p.horizon);
  o.add("sun_cos_inner", &p.sun_cos_inner);
  o.add("sun_cos_outer", &p.sun_cos_outer);
  o.add("fog_density_log2", &p.fog_density_log2);
  o.add("water_enabled", &p.water_enabled);
  o.add("water_level", &p.water_level);
  o.add3("shallow", p.shallow);
  o.add3("deep", p.deep);
  o.add3("extinction_log2", p.extinction_log2);
  o.add("inv_full_depth", &p.inv_full_depth);
  o.add("wave_strength", &p.wave_strength);
  o.add("wave_inv_length[0]", &p.wave_inv_length[0], sizeof(float));
  o.add("wave_offset_x[0]", &p.wave_offset_x[0], sizeof(float));
  o.add("wave_offset_z[0]", &p.wave_offset_z[0], sizeof(float));
  o.add("wave_amplitude[0]", &p.wave_amplitude[0], sizeof(float));
  o.add("dither_enabled", &p.dither_enabled);
  o.add("dither_half_amount", &p.dither_half_amount);
  o.add("dither_inv_scale", &p.dither_inv_scale);
  o.add("dither_offset_x", &p.dither_offset_x);
  o.add("dither_offset_z", &p.dither_offset_z);
  o.add("pixel_angle", &p.pixel_angle);
  o.add("fog_enabled", &p.fog_enabled);
  o.add("terrain_water", &p.terrain_water);
  o.add("always_specular", &p.always_specular);
  o.add("skip_zero_weights", &p.skip_zero_weights);
  o.add("nearest_mip", &p.nearest_mip);
  o.add("skybox", &p.skybox);
  o.add("skybox_sun", &p.skybox_sun);
  o.add("atmosphere", &p.atmosphere);
  o.add("atmosphere_density", &p.atmosphere_density);
  o.add("atmosphere_log2_density", &p.atmosphere_log2_density);
  o.add("atmosphere_scale_height", &p.atmosphere_scale_height);
  o.add("atmosphere_inv_scale_height", &p.atmosphere_inv_scale_height);
  o.add("atmosphere_sun_slope_length", &p.atmosphere_sun_slope_length);
  o.add("atmosphere_grazing_term", &p.atmosphere_grazing_term);
  o.add("atmosphere_mie_a", &p.atmosphere_mie_a);
  o.add("atmosphere_mie_b", &p.atmosphere_mie_b);
  o.add3("atmosphere_extinction_log2", p.atmosphere_extinction_log2);
  o.add3("atmosphere_camera_sun_depth_log2", p.atmosphere_camera_sun_depth_log2);
  o.add3("atmosphere_rayleigh_sun", p.atmosphere_rayleigh_sun);
  o.add3("atmosphere_mie_sun", p.atmosphere_mie_sun);
  o.add("gradient_enabled", &p.gradient_enabled);
  o.add("gradient_count", &p.gradient_count);
  o.add("gradient_height[0]", &p.gradient_height[0], sizeof(float));
  o.add("gradient_inv_span[0]", &p.gradient_inv_span[0], sizeof(float));
  o.add3("gradient_color[0]", p.gradient_color[0]);
  o.add("clouds", &p.clouds);
  o.add("cloud_octaves", &p.cloud_octaves);
  o.add("cloud_warped", &p.cloud_warped);
  o.add("cloud_steps", &p.cloud_steps);
  o.add("cloud_bottom", &p.cloud_bottom);
  o.add("cloud_top", &p.cloud_top);
  o.add("cloud_ground", &p.cloud_ground);
  o.add("cloud_extinction_log2", &p.cloud_extinction_log2);
  o.add("cloud_sun_depth_log2", &p.cloud_sun_depth_log2);
  o.add("cloud_threshold", &p.cloud_threshold);
  o.add("cloud_sharpness", &p.cloud_sharpness);
  o.add("cloud_mean_density", &p.cloud_mean_density);
  o.add("cloud_inv_scale[0]", &p.cloud_inv_scale[0], sizeof(float));
  o.add("cloud_offset_x[0]", &p.cloud_offset_x[0], sizeof(float));
  o.add("cloud_offset_z[0]", &p.cloud_offset_z[0], sizeof(float));
  o.add("cloud_amplitude[0]", &p.cloud_amplitude[0], sizeof(float));
  o.add("cloud_warp_gain[0]", &p.cloud_warp_gain[0], sizeof(float));
  o.add("cloud_warp_offset[0]", &p.cloud_warp_offset[0], sizeof(float));
  o.add3("cloud_sun_light", p.cloud_sun_light);
  o.add3("cloud_sky_light", p.cloud_sky_light);
  o.add("terrain_reflections", &p.terrain_reflections);
  o.add("reserved[0]", &p.reserved[0], sizeof(std::int32_t));
  o.add3("camera_forward", p.camera_forward);
  o.add("forward[0]", &p.forward[0], sizeof(double));
  o.add("right[0]", &p.right[0], sizeof(double));
  o.add("up[0]", &p.up[0], sizeof(double));
  o.add("tan_half_fov_x", &p.tan_half_fov_x);
  o.add("tan_half_fov_y", &p.tan_half_fov_y);
  o.add("planet_center_distance", &p.planet_center_distance);
  o.add("planet_limb_angle", &p.planet_limb_angle);
  o.add("planet_water_c", &p.planet_water_c);
  o.add("planet_datum_c", &p.planet_datum_c);
  return o;
}

// TransformParams<float>'s arrays are mirrored by scalars (std140 would stride a float[3] by
// 16): row_x[c] is "row_x" followed by c.
Offsets<TransformParams<float>> transform_offsets() {
  Offsets<TransformParams<float>> o("TransformBlock.");
  const TransformParams<float>& t = o.object();
  for (int c = 0; c < 3; ++c) {
    o.add("row_x" + std::to_string(c), &t.row_x[c]);
    o.add("row_y" + std::to_string(c), &t.row_y[c]);
    o.add("row_w" + std::to_string(c), &t.row_w[c]);
  }
  o.add("z_clip", &t.z_clip);
  o.add("gouraud", &t.gouraud);
  o.add("sun_x", &t.sun_x);
  o.add("sun_y", &t.sun_y);
  o.add("sun_z", &t.sun_z);
  return o;
}

// GL's members and C++'s must be the same set, at the same offsets with the same strides.
void check_mirror(const std::vector<gpu::GlBlockMember>& members,
                  const std::map<std::string, Expected>& expected) {
  std::map<std::string, gpu::GlBlockMember> by_name;
  for (const gpu::GlBlockMember& m : members) {
    INFO("GL lists " << m.name << " at " << m.offset << " (array stride " << m.array_stride << ")");
    CHECK(expected.count(m.name) == 1);
    by_name[m.name] = m;
  }
  for (const auto& [name, e] : expected) {
    INFO(name << ": C++ offset " << e.offset << ", array stride " << e.array_stride);
    REQUIRE(by_name.count(name) == 1);
    CHECK(by_name[name].offset == e.offset);
    CHECK(by_name[name].array_stride == e.array_stride);
  }
}

TEST_CASE("glShadeParamsBlockLaysEveryMemberOutAtItsCppOffset", "[gl]") {
  test::gl_context();
  gpu::GlTerrainDraw draw;
  const std::vector<gpu::GlBlockMember> members = draw.shade_params_layout();
  check_mirror(members, shade_offsets().table());
  // The layers: element k of the array is sizeof(LayerParams) after element k - 1.
  for (const gpu::GlBlockMember& m : members) {
    if (m.name.rfind("ShadeParamsBlock.layers[0].", 0) == 0) {
      INFO(m.name);
      CHECK(m.top_level_stride == int(sizeof(LayerParams<float>)));
    }
  }
  // Nothing after the last member: the block holds the struct's bytes and no more (C++ pads
  // the struct to its 8-byte alignment; std430 the block to its largest alignment, 8).
  CHECK(draw.shade_params_size() == int(sizeof(ShadeParams<float>)));
}

TEST_CASE("glTransformBlockLaysEveryMemberOutAtItsCppOffset", "[gl]") {
  test::gl_context();
  gpu::GlTerrainDraw draw;
  check_mirror(draw.transform_params_layout(), transform_offsets().table());
  // std140 rounds a uniform block up to 16 bytes; the struct's 40 bytes are its start.
  CHECK(draw.transform_params_size() >= int(sizeof(TransformParams<float>)));
}

}  // namespace
}  // namespace relief
