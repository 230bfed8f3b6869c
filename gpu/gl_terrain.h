// The terrain stages 1-2, 3 and 4 as OpenGL 4.5 compute shaders (GLSL 450, gpu/shaders/):
// the GLSL twin of core/projected_domain.cc, core/octave_coordinates.cc (the forms' choice),
// core/fbm.cc and core/surface.cc. Each stage reads the same parameter struct as the CPU stage
// (core/stage_params.h), uploaded byte for byte into a std430 storage block whose GLSL
// declaration is generated from the struct's field list (params.glsl, from
// gpu/shaders/params.glsl.in; the offsets are checked against offsetof when the programs are
// linked, gl_param_layout.h), and writes one storage buffer per stream
// in the CPU's layout (gl_streams.h). The buffers stay on the GPU: buffer(stream) names them
// for a later draw pass, which reads them in its vertex shader without a round trip; read()
// copies one back. How far the results are from the CPU's, and why: docs/gl-backend.md.
//
// Every call needs the EGL context the object was made in to be current on the calling thread
// (gpu::HeadlessGl, or the caller's own); without it, or on a GL error, a call throws GlError
// (gl_checks.h) naming what failed, and parameters that do not fit the grid or the lattice
// throw std::invalid_argument naming the field. Nothing aborts.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "core/grid_buffers.h"
#include "core/height_sketch.h"
#include "core/heightfield/field_mesh.h"
#include "core/lattice.h"
#include "core/stage_params.h"
#include "gpu/gl_objects.h"
#include "gpu/gl_pass_timer.h"
#include "gpu/gl_streams.h"
#include "gpu/gl_terrain_programs.h"

namespace relief::gpu {

// How stage 3 forms each octave's coordinate (core/octave_coordinates.h).
enum class OctaveForms {
  kFromReach,  // as the frame does: from the farthest valid vertex summing each octave
               // (octave_reach and choose_coordinate_forms, run on the GPU after stage 2)
  kAsGiven,    // FbmParams::exact_coordinates as passed
};

// Who reads glGetError after a GlTerrain call.
enum class GlErrorChecks {
  kEachCall,  // every call, before and after its GL work: an error names the call (the default)
  kByCaller,  // the caller, once per group of calls (check_gl): the GL backend's frames. An
              // error is recorded when the call is made; glGetError never waits for the GPU,
              // but under a threaded driver (NVIDIA's threaded optimisation, Mesa's glthread)
              // it waits for the driver's thread to catch up: once per stage, not per call.
};

class GlTerrain {
 public:
  // Compiles the programs, checks their parameter layouts, allocates the streams of `layout`
  // (pitch = width rounded up to limits::kRowAlignFloats, as make_grid_layout gives) and
  // uploads `lattice`. Throws GlError if no GL 4.5 context is current, a limit of this GL is
  // too small for the grid or the lattice, or a program fails to build or to match the C++
  // structs; std::invalid_argument if the layout is not a make_grid_layout one.
  // `sketch`: §3's low-frequency base of the scene (core/height_sketch.h), uploaded here; null:
  // none (add_sketch then accepts only disabled parameters).
  GlTerrain(GridLayout layout, const NoiseLattice& lattice, const HeightSketch* sketch = nullptr);
  // The same with programs built once (build_terrain_programs) and shared by every GlTerrain of
  // their context, so that a new grid or scene costs no compilation; null: built here. Throws
  // GlError if they were built in another context. The programs' uniforms are set by each call
  // before its dispatch, so sharing them carries nothing from one GlTerrain to another.
  GlTerrain(std::shared_ptr<const GlTerrainPrograms> programs, GridLayout layout,
            const NoiseLattice& lattice, const HeightSketch* sketch = nullptr);
  ~GlTerrain() = default;
  GlTerrain(const GlTerrain&) = delete;
  GlTerrain& operator=(const GlTerrain&) = delete;

  // Stages 2, 3 and 4 over the whole grid, as core/terrain_stages.h's run_terrain_stages does
  // on the CPU: every valid vertex, the octaves' forms chosen from the reach; the need flags
  // of set_need(), if any, limit stages 3 and 4 as the frame's culling does.
  void run(const TerrainParams<float>& params);

  // The stages one by one, in this order (each reads what the previous ones wrote). `planet`:
  // stage 2 on the sphere when enabled (core/planet_domain.h); the default, the plane.
  void project_domain(const DomainParams<float>& params, const DomainRows<float>& rows,
                      const PlanetParams<float>& planet = {});
  void evaluate_fbm(const FbmParams<float>& params, OctaveForms forms = OctaveForms::kFromReach);
  // Stage 3's second part: adds the sketch to the heights evaluate_fbm wrote (where stage 3
  // evaluated). Nothing when params.enabled is 0; throws std::invalid_argument when the
  // parameters do not match the sketch given to the constructor.
  void add_sketch(const SketchParams<float>& params);
  void surface_pass(const SurfaceParams<float>& params);
  // A planet frame's bend (core/planet_bend.h; gl_terrain_planet.cc): bend_vertices after
  // stage 3 into the bent streams (allocated by the first call), bend_normals after stage 4.
  // Nothing when planet.enabled is 0.
  void bend_vertices(const PlanetParams<float>& planet);
  void bend_normals(const PlanetParams<float>& planet);

  // GeoMipMapping's vertex stages (terrain.heightfield.geomipmap; gl_terrain_mesh.cc,
  // shaders/mesh.comp), the GLSL twins of mesh_domain, mesh_heights and mesh_surface of
  // core/heightfield/field_mesh.h, in this order, over a mesh whose vertices fill the streams
  // flat (k = row * pitch + column; those after them padding, valid 0). set_mesh_vertices
  // uploads the frame's vertices (the field lattice's column and row of each); the texels the
  // heights and normals read are the sketch's (the constructor's or set_sketch's), which must
  // be `field`'s. Throws std::invalid_argument where the vertices do not fit the streams (rows
  // of whole work groups), the two spans differ in length, a pass comes before the vertices or
  // (heights, normals) there is no sketch; GlError where they exceed a storage block.
  void set_mesh_vertices(std::span<const std::int32_t> column, std::span<const std::int32_t> row);
  void mesh_domain(const FieldMesh& field, double camera_x, double camera_z);
  void mesh_heights(double camera_above_base);
  void mesh_surface(const FieldMesh& field, const SurfaceParams<float>& params);

  // Replace stage 3's lattice or the sketch (null: none), with the constructor's checks, keeping
  // the streams: a later frame of another scene on the same grid. Each upload is checked for
  // GL errors whatever set_error_checks says (it happens once per scene, not per frame).
  void set_lattice(const NoiseLattice& lattice);
  void set_sketch(const HeightSketch* sketch);

  // Each dispatch from now on is a pass of `timer` (gl_pass_timer.h), named as GL errors name
  // it ("stage 3 (fbm.comp)"); null: none (the default). The timer must outlive the calls.
  void set_pass_timer(GlPassTimer* timer) { timer_ = timer; }
  void set_error_checks(GlErrorChecks checks) { checks_ = checks; }

  // The frame's need flags (core/vertex_culling.h: kEvaluate, kDraw), one byte per vertex:
  // stage 3 evaluates where they are non-zero, stage 4 where kDraw is set; empty: stage 3
  // evaluates every valid vertex and stage 4 computes every valid vertex (the default).
  void set_need(std::span<const std::uint8_t> need);

  // Replaces a stream's contents (layout().size() values; valid: bytes), e.g. stage 2's
  // outputs from the CPU, so that stage 3 can run on them alone.
  void upload(GlStream stream, std::span<const float> values);
  void upload_valid(std::span<const std::uint8_t> valid);

  // Copies a stream back (layout().size() values or bytes).
  void read(GlStream stream, std::span<float> out) const;
  void read_valid(std::span<std::uint8_t> out) const;
  // Every stream into the matching GridBuffers fields (same layout); the bent streams where
  // `out` has them allocated (GridBuffers::allocate_bent) and this GlTerrain has bent.
  void read_all(GridBuffers<float>& out) const;
  // Stage 3's parameters as the GPU holds them: the last evaluate_fbm's, with the octave
  // forms it chose.
  FbmParams<float> fbm_params() const;

  // For a draw pass: the GL buffer name of each stream (GL_SHADER_STORAGE_BUFFER or vertex
  // attribute source; layout in gl_streams.h) and the grid's dimensions and pitch. The
  // buffers are written by compute shaders: every stage call ends with
  // glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
  // GL_BUFFER_UPDATE_BARRIER_BIT), so a later draw or copy sees them.
  unsigned int buffer(GlStream stream) const;
  const GridLayout& layout() const { return layout_; }

 private:
  void require_context(const char* who) const;
  void checkpoint(const std::string& what) const;  // check_gl under GlErrorChecks::kEachCall
  void check_lattice(const char* who, const NoiseLattice& lattice) const;
  void check_sketch(const char* who, const HeightSketch* sketch) const;
  void check_stream_size(const char* who, GlStream stream, std::size_t count) const;
  void bind_stream(GlStream stream) const;
  void dispatch(unsigned int program, int groups_x, int groups_y, const std::string& what) const;
  void upload_planet(const PlanetParams<float>& planet);
  void bind_mesh(unsigned int program, bool texels) const;  // gl_terrain_mesh.cc
  void require_mesh(const char* who, bool texels) const;

  GridLayout layout_;
  void* context_ = nullptr;           // the EGL context the objects belong to
  std::int64_t max_block_bytes_ = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  int lattice_size_ = 0;
  std::size_t lattice_bytes_ = 0, sketch_bytes_ = 0;  // the buffers' sizes
  std::shared_ptr<const GlTerrainPrograms> programs_;
  GlPassTimer* timer_ = nullptr;
  GlErrorChecks checks_ = GlErrorChecks::kEachCall;
  GlName domain_params_, fbm_params_, sketch_params_, surface_params_;  // the structs' bytes
  GlName planet_params_;
  GlName sketch_;  // the sketch's texel heights, when there is one
  int sketch_width_ = 0, sketch_height_ = 0;
  GlName rows_;           // DomainRows: descent, x0, step_x
  GlName lattice_;        // GlLatticeHeader, then the values
  GlName reach_;          // octave_reach's extents per finest octave (float bits)
  GlName need_;           // the need flags, when set
  GlName mesh_vertices_;  // set_mesh_vertices': column, row per vertex
  std::size_t mesh_vertex_count_ = 0, mesh_vertex_bytes_ = 0;
  bool use_need_ = false;
  GlName streams_[kGlStreamCount];
};

}  // namespace relief::gpu
