// The scene file's "camera", "viewport" and "grid" sections (docs/scene-reference.md).
#include <cmath>
#include <string>

#include "core/limits.h"
#include "core/scene/scene_sections.h"
#include "core/scene/schema_fields.h"

namespace relief {

namespace {

constexpr Range kCoordinate{-limits::kMaxCameraCoordinate, limits::kMaxCameraCoordinate};

// camera.look_at: read for its errors here, turned into yaw and pitch by finish_camera once
// the object's position is known; never printed (the angles are).
Field<CameraSettings> look_at_field() {
  Field<CameraSettings> field = vector_field(
      "look_at", &CameraSettings::position, kCoordinate,
      {"world units", "a point to look at, instead of yaw_deg and pitch_deg",
       "≠ position; not with yaw_deg or pitch_deg in one source (a file, or all `--set` "
       "options)"});
  field.read = [](const LayerContext& cx, const json& v, const std::string& p, CameraSettings&) {
    cx.in.vector<3>(v, p, kCoordinate);
  };
  field.write = [](const CameraSettings&) -> std::optional<json> { return std::nullopt; };
  return field;
}

void finish_camera(const LayerContext& cx, const json& value, const std::string& path,
                   CameraSettings& camera) {
  if (!value.contains("look_at")) {
    return;
  }
  const std::string p = child_path(path, "look_at");
  if (value.contains("yaw_deg") || value.contains("pitch_deg")) {
    cx.in.fail(p, p + " and " + child_path(path, "yaw_deg") + "/" + child_path(path, "pitch_deg") +
                      " both set the view direction; give one or the other");
  }
  // Converted to yaw/pitch at load time so that later layers can still adjust the angles.
  const Vec3d look_at = cx.in.vector<3>(value["look_at"], p, kCoordinate);
  const double dx = look_at[0] - camera.position[0];
  const double dy = look_at[1] - camera.position[1];
  const double dz = look_at[2] - camera.position[2];
  const double horizontal = std::hypot(dx, dz);
  if (horizontal == 0.0 && dy == 0.0) {
    cx.in.fail(p, p + " = the camera position; the target must differ from camera.position");
  }
  camera.yaw_deg = horizontal > 0.0 ? std::atan2(dx, -dz) * (180.0 / M_PI) : camera.yaw_deg;
  camera.pitch_deg = std::atan2(dy, horizontal) * (180.0 / M_PI);
}

}  // namespace

const Schema<CameraSettings>& camera_schema() {
  using S = CameraSettings;
  static const Schema<S> schema(
      {
          vector_field("position", &S::position, kCoordinate,
                       {"world units", "world position (double), y up"}),
          number_field("yaw_deg", &S::yaw_deg, Range{-limits::kMaxTurnDeg, limits::kMaxTurnDeg},
                       {"degrees", "rotation about +y; 0 looks along −z, 90 along +x"}),
          number_field("pitch_deg", &S::pitch_deg,
                       Range{-limits::kMaxElevationDeg, limits::kMaxElevationDeg},
                       {"degrees", "positive looks up"}),
          look_at_field(),
          number_field("fov_y_deg", &S::fov_y_deg, Range{limits::kMinFovDeg, limits::kMaxFovDeg},
                       {"degrees", "vertical field of view",
                        "the horizontal one (from the viewport's aspect) within [1, 175]"}),
          number_field("near", &S::near, Range{limits::kMinNearDistance, limits::kMaxViewDistance},
                       {"world units", "near plane distance", "< far"}),
          number_field("far", &S::far,
                       Range{limits::kMinNearDistance, limits::kMaxViewDistance, true},
                       {"world units",
                        "terrain is generated up to this distance (depth itself uses an infinite "
                        "far plane); also bounds terrain.horizontal_scale",
                        "> near"}),
      },
      finish_camera);
  return schema;
}

const Schema<ViewportSettings>& viewport_schema() {
  using S = ViewportSettings;
  static const Schema<S> schema({
      integer_field("width", &S::width, 1, limits::kMaxViewportSide,
                    {"pixels", "image width (the paper's viewport: 1280 × 1024)"}),
      integer_field("height", &S::height, 1, limits::kMaxViewportSide, {"pixels", "image height"}),
  });
  return schema;
}

const Schema<GridSettings>& grid_schema() {
  using S = GridSettings;
  static const Schema<S> schema({
      integer_field(
          "width", &S::width, limits::kMinGridSide, limits::kMaxGridSide,
          {"vertices", "projected-grid columns (the paper's grid: 512 × 512)", "≥ 2·margin + 2"}),
      integer_field("height", &S::height, limits::kMinGridSide, limits::kMaxGridSide,
                    {"vertices", "projected-grid rows", "≥ 2·margin + 2"}),
      integer_field("margin", &S::margin, 0, limits::kMaxGridMargin,
                    {"cells", "cells projected past the visible region on every side (§4.1)"}),
  });
  return schema;
}

}  // namespace relief
