// The fields of each scene section and their rules (README.md, "Scene reference"). Each
// function applies one section of a layer onto the scene; scene_json.cc dispatches to them.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/json_fields.h"
#include "core/scene/scene.h"

namespace relief {

void apply_camera(const LayerReader& in, const json& value, const std::string& path,
                  CameraSettings& camera);
void apply_viewport(const LayerReader& in, const json& value, const std::string& path,
                    ViewportSettings& viewport);
void apply_grid(const LayerReader& in, const json& value, const std::string& path,
                GridSettings& grid);
void apply_terrain(const LayerReader& in, const json& value, const std::string& path,
                   TerrainSettings& terrain, const std::filesystem::path& base_dir);
// terrain.sketch (sketch_section.cc): null removes it, an object patches it.
void apply_sketch(const LayerReader& in, const json& value, const std::string& path,
                  std::optional<SketchSettings>& sketch, const std::filesystem::path& base_dir);
// terrain.basis (basis_section.cc): null removes it, an object patches it.
void apply_basis(const LayerReader& in, const json& value, const std::string& path,
                 std::optional<BasisSettings>& basis, const std::filesystem::path& base_dir);
// terrain.basis's rules across fields (validate_scene): some weight non-zero, and the octave-0
// cell tile_size / P for the largest P keeps `coarsest_reach` (the coarsest octave's frequency
// times the farthest footprint, world units) below kMaxLatticeCoordinate. Throws SceneError.
void validate_basis(const BasisSettings& basis, double coarsest_reach);
json basis_to_json(const BasisSettings& basis);
// A file name relative to `base_dir` (the scene file's directory, the current one for --set)
// made absolute, so that the printed scene loads back from anywhere; "builtin:..." and absolute
// names unchanged.
std::string resolve_scene_path(std::string name, const std::filesystem::path& base_dir);
// terrain.planet (planet_section.cc): null removes it, an object patches it.
void apply_planet(const LayerReader& in, const json& value, const std::string& path,
                  std::optional<PlanetSettings>& planet);
// The planet's rules across fields, run by validate_scene (throws SceneError).
void validate_planet(const Scene& scene);
json planet_to_json(const PlanetSettings& planet);
void apply_shading(const LayerReader& in, const json& value, const std::string& path,
                   ShadingSettings& shading, const std::filesystem::path& base_dir);
void apply_lighting(const LayerReader& in, const json& value, const std::string& path,
                    LightingSettings& lighting);
void apply_water(const LayerReader& in, const json& value, const std::string& path,
                 WaterSettings& water);
void apply_sky(const LayerReader& in, const json& value, const std::string& path, SkySettings& sky);
void apply_output(const LayerReader& in, const json& value, const std::string& path,
                  OutputSettings& output);

}  // namespace relief
