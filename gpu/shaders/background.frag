// Stages 8-9 where no terrain covers the pixel: sky, fog colour or open water (shade.cc,
// background_radiance). Drawn over every pixel first; the terrain pass then overwrites the
// pixels it covers, so the other outputs hold their uncovered values here.
layout(location = 0) out vec4 out_linear;
layout(location = 1) out uvec4 out_srgb;
layout(location = 2) out uint out_primitive;
layout(location = 3) out vec4 out_normal;
layout(location = 4) out vec2 out_height_octaves;

void main() {
  const vec3 radiance = background_radiance(int(gl_FragCoord.x), int(gl_FragCoord.y));
  precise vec3 rgb = radiance * P.exposure;
  out_linear = vec4(rgb, 1.0);
  out_srgb = uvec4(srgb_byte(rgb.r), srgb_byte(rgb.g), srgb_byte(rgb.b), 255u);
  out_primitive = 0xffffffffu;
  out_normal = vec4(0.0);
  out_height_octaves = vec2(0.0);
}
