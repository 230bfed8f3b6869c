#include "gpu/gl_terrain_programs.h"

#include <string>

#include "gpu/gl_checks.h"
#include "gpu/gl_shader_prelude.h"
#include "gpu/gl_shader_sources.h"

namespace relief::gpu {

namespace {

// The prelude, params.glsl, then the named files of gpu/shaders/ in order.
GlName build(const std::string& prelude, const std::string& name,
             std::initializer_list<std::string_view> files) {
  std::vector<std::string_view> sources = {prelude, shader_file("params.glsl")};
  for (const std::string_view file : files) {
    sources.push_back(shader_file(file));
  }
  return link_compute_program(sources, name);
}

}  // namespace

std::vector<GlProgramBlocks> terrain_program_blocks() {
  return {
      {"domain", {domain_params_layout(), planet_params_layout()}},
      {"reach", {}},
      {"forms", {fbm_params_layout()}},
      {"fbm", {fbm_params_layout(), lattice_layout()}},
      {"sketch", {sketch_params_layout()}},
      {"surface", {surface_params_layout()}},
      {"bend", {planet_params_layout()}},
      {"bend_normals", {planet_params_layout()}},
      {"mesh_domain", {}},
      {"mesh_heights", {}},
      {"mesh_surface", {}},
  };
}

unsigned int program_named(const GlTerrainPrograms& programs, std::string_view name) {
  if (name == "domain") {
    return programs.domain.get();
  }
  if (name == "reach") {
    return programs.reach.get();
  }
  if (name == "forms") {
    return programs.forms.get();
  }
  if (name == "fbm") {
    return programs.fbm.get();
  }
  if (name == "sketch") {
    return programs.sketch.get();
  }
  if (name == "surface") {
    return programs.surface.get();
  }
  if (name == "bend") {
    return programs.bend.get();
  }
  if (name == "bend_normals") {
    return programs.bend_normals.get();
  }
  if (name == "mesh_domain") {
    return programs.mesh_domain.get();
  }
  if (name == "mesh_heights") {
    return programs.mesh_heights.get();
  }
  if (name == "mesh_surface") {
    return programs.mesh_surface.get();
  }
  throw GlError("no terrain program named " + std::string(name));
}

GlTerrainPrograms build_terrain_programs() {
  const std::string prelude = shader_prelude();
  GlTerrainPrograms p;
  p.context = current_egl_context();
  p.domain =
      build(prelude, "domain.comp (stage 2)", {"det_math.glsl", "log2_det.glsl", "domain.comp"});
  p.reach = build(prelude, "reach.comp (octave reach)", {"reach.comp"});
  p.forms = build(prelude, "forms.comp (coordinate forms)", {"forms.comp"});
  p.fbm = build(prelude, "fbm.comp (stage 3)",
                {"wrap_period.glsl", "lattice.glsl", "octave_coordinates.glsl", "fbm.comp"});
  p.sketch = build(prelude, "sketch.comp (stage 3, sketch)", {"sketch.comp"});
  p.surface = build(prelude, "surface.comp (stage 4)", {"surface.comp"});
  p.bend = build(prelude, "bend.comp (a planet's bend)", {"det_math.glsl", "bend.comp"});
  p.bend_normals = build(prelude, "bend_normals.comp (a planet's normals)",
                         {"det_math.glsl", "bend_normals.comp"});
  // mesh.comp's three stages, each its own program (the prelude names the stage).
  const auto mesh = [&](int stage, const std::string& what) {
    return build(prelude + "#define RELIEF_MESH_STAGE " + std::to_string(stage) + "\n", what,
                 {"mesh.comp"});
  };
  p.mesh_domain = mesh(2, "mesh.comp (stage 2, GeoMipMapping)");
  p.mesh_heights = mesh(3, "mesh.comp (stage 3, GeoMipMapping)");
  p.mesh_surface = mesh(4, "mesh.comp (stage 4, GeoMipMapping)");
  for (const GlProgramBlocks& entry : terrain_program_blocks()) {
    std::string problems;
    for (const GlBlockLayout& block : entry.blocks) {
      for (const std::string& problem : layout_mismatches(program_named(p, entry.program), block)) {
        problems += "\n  " + problem;
      }
    }
    if (!problems.empty()) {
      throw GlError("the GLSL parameter blocks of program " + std::string(entry.program) +
                    " do not match the C++ structs (gpu/shaders/params.glsl.in against "
                    "core/stage_params.h):" +
                    problems);
    }
  }
  check_gl("checking the terrain programs' parameter layouts");
  return p;
}

}  // namespace relief::gpu
