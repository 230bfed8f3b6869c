// Each scene section's field list (scene_schema.h), and the rules across fields that
// validate_scene runs. One function per section; the lists live beside their rules:
// view_sections.cc (camera, viewport, grid), terrain_sections.cc (terrain, lod, warp),
// sketch_section.cc (sketch, heightfield), basis_section.cc, planet_section.cc, shading_section.cc
// and gradient_section.cc, light_sections.cc (lighting, water, sky, output), scene_schema.cc
// (the whole scene).
#pragma once

#include "core/scene/scene.h"
#include "core/scene/scene_schema.h"

namespace relief {

const Schema<Scene>& scene_schema();

const Schema<CameraSettings>& camera_schema();
const Schema<ViewportSettings>& viewport_schema();
const Schema<GridSettings>& grid_schema();
const Schema<TerrainSettings>& terrain_schema();
const Schema<SketchSettings>& sketch_schema();
const Schema<HeightFieldSettings>& heightfield_schema();
const Schema<BasisSettings>& basis_schema();
const Schema<PlanetSettings>& planet_schema();
const Schema<ShadingSettings>& shading_schema();
const Schema<GradientSettings>& gradient_schema();
const Schema<LightingSettings>& lighting_schema();
const Schema<WaterSettings>& water_schema();
const Schema<SkySettings>& sky_schema();
const Schema<OutputSettings>& output_schema();

// terrain.basis's rules across fields (validate_scene): some weight non-zero, and the octave-0
// cell tile_size / P for the largest P keeps `coarsest_reach` (the coarsest octave's frequency
// times the farthest footprint, world units) below kMaxLatticeCoordinate. Throws SceneError.
void validate_basis(const BasisSettings& basis, double coarsest_reach);
// The planet's rules across fields, run by validate_scene (throws SceneError).
void validate_planet(const Scene& scene);
// terrain.heightfield.geomipmap against the rest of the scene: refused with the fractal or its
// levels of detail (the mesh's vertices are the field's samples, its levels GeoMipMapping's),
// on a planet, and with lighting.shadows (whose horizon cache follows the projected grid).
void validate_geomipmap(const Scene& scene);

}  // namespace relief
