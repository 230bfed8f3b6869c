// terrain.basis (§3 Eq. 2's basis images, core/basis_images.h): its fields and its rules across
// fields. Whether the images can be read, and their sizes, are checked when they are loaded
// (pipeline/basis_resources.cc).
#include <cmath>
#include <optional>
#include <string>

#include "core/limits.h"
#include "core/scene/scene_json.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

// A constant weight (0, or kMinBasisWeight to kMaxBasisWeight) or a grey PNG of weights.
Field<BasisImageSettings> weight_field() {
  return {{"weight",
           "0, or [" + format_number(limits::kMinBasisWeight) + ", " +
               format_number(limits::kMaxBasisWeight) + "], or a grey PNG path of the image's size",
           {"", "w_k, renormalised per texel",
            "the sum > 0 everywhere (a non-zero weight below 1e-6 would bring Eq. 2's products "
            "near double's subnormals)"}},
          [](const LayerContext& cx, const json& v, const std::string& p, BasisImageSettings& s) {
            if (v.is_string()) {
              s.weight_image = resolve_scene_path(cx.in.string(v, p), cx.base_dir);
              return;
            }
            // One rule, one message, whichever side is crossed (docs/scene-reference.md's table).
            const std::string allowed =
                "allowed 0, or " + format_number(limits::kMinBasisWeight) + " <= " + p +
                " <= " + format_number(limits::kMaxBasisWeight) + ", or a grey PNG's path";
            if (!v.is_number() || !std::isfinite(v.get<double>())) {
              cx.in.fail(p, p + " = " + brief(v) + " is not a finite number; " + allowed);
            }
            s.weight = v.get<double>();
            if (s.weight != 0.0 &&
                !(s.weight >= limits::kMinBasisWeight && s.weight <= limits::kMaxBasisWeight)) {
              cx.in.fail(p, p + " = " + format_number(s.weight) + " is out of range; " + allowed);
            }
            s.weight_image.clear();
          },
          [](const BasisImageSettings& s) -> std::optional<json> {
            return s.weight_image.empty() ? json(s.weight) : json(s.weight_image);
          }};
}

const Schema<BasisImageSettings>& basis_image_schema() {
  using S = BasisImageSettings;
  const Range sigma{0.0, limits::kMaxBasisSigma};
  const std::string_view sigma_rule =
      "≤ half the image's side (of the mirrored image under `mirror`; before `upsample`)";
  static const Schema<S> schema({
      input_file_field("image", &S::image,
                       {"", "I_k",
                        "NAME `basis/craters`, `basis/dunes`, `basis/ridges`; the PNG: grey, 8 "
                        "or 16 bits, square, a power of two 4…4096 (…2048 mirrored), all images "
                        "of one size"}),
      weight_field(),
      number_field("low_pass", &S::low_pass, sigma,
                   {"texels", "periodic Gaussian blur's sigma (0: off)", sigma_rule}),
      number_field("high_pass", &S::high_pass, sigma,
                   {"texels", "the image minus its blur of this sigma (0: off)", sigma_rule}),
      boolean_field("normalize", &S::normalize, {"", "to mean 0, variance 1"}),
  });
  return schema;
}

// terrain.basis.images: replaced whole, 1 to kMaxBasisImages images, each naming its image.
Field<BasisSettings> images_field() {
  return {{"images",
           "array of 1 to " + std::to_string(limits::kMaxBasisImages) +
               " objects, each with an `image`",
           {"", "the basis images, replaced whole"},
           {},
           &basis_image_schema(),
           true},
          [](const LayerContext& cx, const json& v, const std::string& p, BasisSettings& s) {
            if (!v.is_array() || v.empty() || v.size() > std::size_t(limits::kMaxBasisImages)) {
              cx.in.fail(p, p + " = " + brief(v) + " must be an array of 1 to " +
                                std::to_string(limits::kMaxBasisImages) + " images");
            }
            s.images.clear();
            for (std::size_t k = 0; k < v.size(); ++k) {
              const std::string q = p + "[" + std::to_string(k) + "]";
              if (!v[k].is_object() || !v[k].contains("image")) {
                cx.in.fail(
                    q, q + " = " + brief(v[k]) + " must be an object with at least an \"image\"");
              }
              BasisImageSettings image;
              basis_image_schema().apply(cx, v[k], q, image);
              s.images.push_back(std::move(image));
            }
          },
          [](const BasisSettings& s) -> std::optional<json> {
            json images = json::array();
            for (const BasisImageSettings& image : s.images) {
              images.push_back(basis_image_schema().write(image));
            }
            return images;
          }};
}

}  // namespace

const Schema<BasisSettings>& basis_schema() {
  using S = BasisSettings;
  static const Schema<S> schema({
      number_field("tile_size", &S::tile_size,
                   Range{limits::kMinBasisTileSize, limits::kMaxBasisTileSize},
                   {"world units", "one image tile's span at octave 0 (cell: tile_size / P)",
                    "≥ 4096·r^first_octave·F/(2²⁴ − 4096)"}),
      choice_field("wrap", &S::wrap,
                   {{"repeat", BasisWrap::kRepeat}, {"mirror", BasisWrap::kMirror}},
                   {"", "`mirror`: the image mirrored into 2W × 2W, so that any image tiles"}),
      power_of_two_field("upsample", &S::upsample, 1, limits::kMaxBasisUpsample,
                         {"",
                          "the composed grid refined by the cubic B-spline; with the "
                          "linear interpolant, no terraces on smooth images"}),
      images_field(),
  });
  return schema;
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

}  // namespace relief
