// GlTerrain's planet passes (§4.1, docs/planet.md): the parameters of stage 2 on the sphere,
// the bend after stage 3 and the normals' rotation after stage 4 (bend.comp and
// bend_normals.comp, the GLSL twins of core/planet_bend.cc).
#include <string>

#include <epoxy/gl.h>

#include "gpu/gl_checks.h"
#include "gpu/gl_shader_prelude.h"
#include "gpu/gl_terrain.h"

namespace relief::gpu {

void GlTerrain::upload_planet(const PlanetParams<float>& planet) {
  glNamedBufferSubData(planet_params_.get(), 0, sizeof planet, &planet);
  checkpoint("uploading the planet's parameters");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingPlanet, planet_params_.get());
}

void GlTerrain::bend_vertices(const PlanetParams<float>& planet) {
  require_context("bend_vertices");
  if (planet.enabled == 0) {
    return;
  }
  for (const GlStream stream :
       {GlStream::kBentX, GlStream::kBentY, GlStream::kBentZ, GlStream::kBentDrop}) {
    GlName& name = streams_[static_cast<int>(stream)];
    if (name.get() == 0) {
      name = make_storage_buffer(layout_.size() * sizeof(float),
                                 "stream " + std::string(gl_stream_name(stream)));
    }
  }
  upload_planet(planet);
  const GLuint program = programs_->bend.get();
  glProgramUniform1i(program, glGetUniformLocation(program, "grid_pitch"), layout_.pitch);
  for (const GlStream s :
       {GlStream::kDx, GlStream::kDz, GlStream::kHeight, GlStream::kValid, GlStream::kBentX,
        GlStream::kBentY, GlStream::kBentZ, GlStream::kBentDrop}) {
    bind_stream(s);
  }
  dispatch(program, (layout_.pitch + kGroupSize - 1) / kGroupSize, layout_.height,
           "the planet's bend (bend.comp)");
}

void GlTerrain::bend_normals(const PlanetParams<float>& planet) {
  require_context("bend_normals");
  if (planet.enabled == 0) {
    return;
  }
  upload_planet(planet);
  const GLuint program = programs_->bend_normals.get();
  glProgramUniform1i(program, glGetUniformLocation(program, "grid_pitch"), layout_.pitch);
  for (const GlStream s : {GlStream::kDx, GlStream::kDz, GlStream::kValid, GlStream::kNx,
                           GlStream::kNy, GlStream::kNz}) {
    bind_stream(s);
  }
  dispatch(program, (layout_.pitch + kGroupSize - 1) / kGroupSize, layout_.height,
           "the planet's normals (bend_normals.comp)");
}

}  // namespace relief::gpu
