// terrain.basis (§3 Eq. 2's basis images, core/basis_images.h): the field's strict reading.
// Whether the images can be read, and their sizes, are checked when they are loaded
// (pipeline/basis_resources.cc).
#include <bit>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "core/limits.h"
#include "core/scene/scene_json.h"
#include "core/scene/scene_sections.h"

namespace relief {

namespace {

BasisImageSettings read_basis_image(const LayerReader& in, const json& value,
                                    const std::string& path,
                                    const std::filesystem::path& base_dir) {
  if (!value.is_object() || !value.contains("image")) {
    in.fail(path, path + " = " + brief(value) + " must be an object with at least an \"image\"");
  }
  BasisImageSettings image;
  const Range sigma{0.0, limits::kMaxBasisSigma};
  in.object(
      value, path,
      Handlers{
          {"image",
           [&](const json& v, const std::string& p) {
             image.image = resolve_scene_path(in.string(v, p), base_dir);
           }},
          {"weight",
           [&](const json& v, const std::string& p) {
             if (v.is_string()) {
               image.weight_image = resolve_scene_path(in.string(v, p), base_dir);
             } else {
               // One rule, one message, whichever side is crossed (README's scene table).
               const std::string allowed =
                   "allowed 0, or " + format_number(limits::kMinBasisWeight) + " <= " + p +
                   " <= " + format_number(limits::kMaxBasisWeight) + ", or a grey PNG's path";
               if (!v.is_number() || !std::isfinite(v.get<double>())) {
                 in.fail(p, p + " = " + brief(v) + " is not a finite number; " + allowed);
               }
               image.weight = v.get<double>();
               if (image.weight != 0.0 && !(image.weight >= limits::kMinBasisWeight &&
                                            image.weight <= limits::kMaxBasisWeight)) {
                 in.fail(p,
                         p + " = " + format_number(image.weight) + " is out of range; " + allowed);
               }
               image.weight_image.clear();
             }
           }},
          {"low_pass",
           [&](const json& v, const std::string& p) { image.low_pass = in.number(v, p, sigma); }},
          {"high_pass",
           [&](const json& v, const std::string& p) { image.high_pass = in.number(v, p, sigma); }},
          {"normalize",
           [&](const json& v, const std::string& p) { image.normalize = in.boolean(v, p); }},
      });
  return image;
}

}  // namespace

// terrain.basis: null removes it; an object patches it (a new one must list its images;
// "images" replaces the whole list).
void apply_basis(const LayerReader& in, const json& value, const std::string& path,
                 std::optional<BasisSettings>& basis, const std::filesystem::path& base_dir) {
  if (value.is_null()) {
    basis.reset();
    return;
  }
  if (!basis && value.is_object() && !value.contains("images")) {
    in.fail(path, path + " must be null or an object with at least \"images\"");
  }
  BasisSettings b = basis.value_or(BasisSettings{});
  in.object(
      value, path,
      Handlers{
          {"tile_size",
           [&](const json& v, const std::string& p) {
             b.tile_size =
                 in.number(v, p, Range{limits::kMinBasisTileSize, limits::kMaxBasisTileSize});
           }},
          {"wrap",
           [&](const json& v, const std::string& p) {
             b.wrap = in.choice<BasisWrap>(
                 v, p, {{"repeat", BasisWrap::kRepeat}, {"mirror", BasisWrap::kMirror}});
           }},
          {"upsample",
           [&](const json& v, const std::string& p) {
             const long long factor = in.integer(v, p, 1, limits::kMaxBasisUpsample);
             if (!std::has_single_bit(static_cast<unsigned long long>(factor))) {
               in.fail(p, p + " = " + brief(v) + " is not a power of two; allowed 1, 2, 4 or " +
                              std::to_string(limits::kMaxBasisUpsample));
             }
             b.upsample = static_cast<int>(factor);
           }},
          {"images",
           [&](const json& v, const std::string& p) {
             if (!v.is_array() || v.empty() || v.size() > std::size_t(limits::kMaxBasisImages)) {
               in.fail(p, p + " = " + brief(v) + " must be an array of 1 to " +
                              std::to_string(limits::kMaxBasisImages) + " images");
             }
             b.images.clear();
             for (std::size_t k = 0; k < v.size(); ++k) {
               b.images.push_back(
                   read_basis_image(in, v[k], p + "[" + std::to_string(k) + "]", base_dir));
             }
           }},
      });
  basis = b;
}

void validate_basis(const BasisSettings& basis, double coarsest_reach) {
  bool any_weight = false;
  for (const BasisImageSettings& image : basis.images) {
    any_weight = any_weight || !image.weight_image.empty() || image.weight > 0.0;
  }
  if (!any_weight) {
    throw SceneError("terrain.basis.images",
                     "scene: every terrain.basis.images[k].weight is 0, so the weights sum to 0 "
                     "everywhere; allowed: each weight 0, or " +
                         format_number(limits::kMinBasisWeight) + " to " +
                         format_number(limits::kMaxBasisWeight) +
                         ", or a grey PNG's path, with at least one not 0");
  }
  // The stage-3 period P is not known before the images are read: the bound holds for every
  // P up to kMaxLatticeSize (a smaller P gives a larger cell and a smaller period).
  const double largest_p = limits::kMaxLatticeSize;
  const double min_tile_size =
      largest_p * coarsest_reach / (limits::kMaxLatticeCoordinate - largest_p);
  if (basis.tile_size < min_tile_size) {
    throw SceneError("terrain.basis.tile_size",
                     "scene: terrain.basis.tile_size = " + format_number(basis.tile_size) +
                         " puts the farthest footprint beyond lattice coordinate 2^24 of the "
                         "coarsest octave for a " +
                         std::to_string(limits::kMaxLatticeSize) +
                         "-texel image, where float no longer holds every cell; allowed "
                         "terrain.basis.tile_size >= " +
                         format_number(min_tile_size) +
                         " for this camera.far, camera.fov_y_deg, viewport aspect, "
                         "terrain.first_octave and terrain.r (or a smaller camera.far)");
  }
}

json basis_to_json(const BasisSettings& basis) {
  json images = json::array();
  for (const BasisImageSettings& image : basis.images) {
    images.push_back(
        {{"image", image.image},
         {"weight", image.weight_image.empty() ? json(image.weight) : json(image.weight_image)},
         {"low_pass", image.low_pass},
         {"high_pass", image.high_pass},
         {"normalize", image.normalize}});
  }
  return {{"tile_size", basis.tile_size},
          {"wrap", basis.wrap == BasisWrap::kRepeat ? "repeat" : "mirror"},
          {"upsample", basis.upsample},
          {"images", images}};
}

}  // namespace relief
