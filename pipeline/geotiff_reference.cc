// A GeoTIFF's placement (pipeline/geotiff_reference.h).
#include "pipeline/geotiff_reference.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <vector>

#include "core/input_file.h"
#include "core/limits.h"
#include "core/scene/json_fields.h"
#include "core/scene/json_input.h"
#include "pipeline/heightfield_checks.h"

namespace relief {

namespace {

constexpr const char* kGeoPath = "terrain.heightfield.georeferenced";

[[noreturn]] void refuse_geo(const HeightFieldSettings& s, const std::string& why) {
  heightfield_checks::refuse(s,
                             why +
                                 "; terrain.heightfield.georeferenced needs a GeoTIFF "
                                 "placed in projected metres or feet (or give extent and "
                                 "set georeferenced to false)",
                             kGeoPath);
}

// The tags of a classic TIFF's first directory that georeference it, as numbers.
struct GeoTags {
  std::vector<double> pixel_scale, tie_points, transformation;
  std::vector<double> key_directory;  // SHORT values
};

class TiffReader {
 public:
  TiffReader(const HeightFieldSettings& s, std::uintmax_t size) : s_(s), size_(size) {
    in_.open(s.image, std::ios::binary);
    if (!in_) {
      refuse_geo(s, "cannot be opened");
    }
  }

  void bytes(std::uint64_t at, void* out, std::size_t n) {
    if (at > size_ || n > size_ - at) {
      refuse_geo(s_, "has a TIFF directory reaching past its end");
    }
    in_.seekg(std::streamoff(at));
    if (!in_.read(static_cast<char*>(out), std::streamsize(n))) {
      refuse_geo(s_, "could not be read");
    }
  }

  std::uint64_t unsigned_of(std::uint64_t at, int n) {
    unsigned char b[8] = {};
    bytes(at, b, std::size_t(n));
    std::uint64_t v = 0;
    for (int k = 0; k < n; ++k) {
      v |= std::uint64_t(b[little_ ? k : n - 1 - k]) << (8 * k);
    }
    return v;
  }

  GeoTags read() {
    char order[2];
    bytes(0, order, 2);
    if (std::memcmp(order, "II", 2) != 0 && std::memcmp(order, "MM", 2) != 0) {
      refuse_geo(s_, "is not a TIFF file");
    }
    little_ = order[0] == 'I';
    const std::uint64_t magic = unsigned_of(2, 2);
    if (magic == 43) {
      refuse_geo(s_, "is a BigTIFF, whose georeferencing is not read");
    }
    if (magic != 42) {
      refuse_geo(s_, "is not a TIFF file");
    }
    const std::uint64_t directory = unsigned_of(4, 4);
    const std::uint64_t entries = unsigned_of(directory, 2);
    GeoTags tags;
    const std::map<std::uint64_t, std::vector<double>*> wanted = {{33550, &tags.pixel_scale},
                                                                  {33922, &tags.tie_points},
                                                                  {34264, &tags.transformation},
                                                                  {34735, &tags.key_directory}};
    for (std::uint64_t e = 0; e < entries; ++e) {
      const std::uint64_t at = directory + 2 + 12 * e;
      const auto found = wanted.find(unsigned_of(at, 2));
      if (found == wanted.end()) {
        continue;
      }
      const std::uint64_t type = unsigned_of(at + 2, 2);
      const std::uint64_t count = unsigned_of(at + 4, 4);
      const int width = type == 12 ? 8 : type == 3 ? 2 : 0;  // DOUBLE or SHORT
      if (width == 0 || count > 4096) {
        refuse_geo(s_, "has GeoTIFF tag " + std::to_string(found->first) + " of TIFF type " +
                           std::to_string(type) + " and " + std::to_string(count) +
                           " values; allowed DOUBLE (12) or SHORT (3), at most 4096");
      }
      // Values that fit in 4 bytes are in the entry itself, others at the offset it holds.
      const std::uint64_t values =
          count * std::uint64_t(width) <= 4 ? at + 8 : unsigned_of(at + 8, 4);
      for (std::uint64_t k = 0; k < count; ++k) {
        const std::uint64_t raw = unsigned_of(values + k * std::uint64_t(width), width);
        double v = double(raw);
        if (width == 8) {
          std::memcpy(&v, &raw, 8);
        }
        found->second->push_back(v);
      }
    }
    return tags;
  }

 private:
  const HeightFieldSettings& s_;
  std::uintmax_t size_;
  std::ifstream in_;
  bool little_ = true;
};

// GeoKey `id`'s SHORT value from the GeoKeyDirectory (header: version, revision, minor,
// count; then id, location, count, value per key), or `absent`.
double geo_key(const std::vector<double>& directory, int id, double absent) {
  if (directory.size() < 4) {
    return absent;
  }
  const std::size_t keys = std::size_t(directory[3]);
  for (std::size_t k = 0; k < keys && 4 + 4 * k + 3 < directory.size(); ++k) {
    const double* key = &directory[4 + 4 * k];
    if (key[0] == id) {  // location 0: the value is in the key itself; elsewhere: NaN, refused
      return key[1] == 0 ? key[3] : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return absent;
}

}  // namespace

std::array<double, 4> georeferenced_extent(const HeightFieldSettings& s, int width, int height) {
  if (!has_extension(s.image, ".tif") && !has_extension(s.image, ".tiff")) {
    refuse_geo(s, "is not a .tif or .tiff file");
  }
  const std::uintmax_t size = heightfield_checks::file_size(s, limits::kMaxHeightFieldFileBytes);
  const GeoTags tags = TiffReader(s, size).read();
  if (!tags.transformation.empty()) {
    refuse_geo(s, "is placed by a ModelTransformation (rotation or shear)");
  }
  if (tags.pixel_scale.size() != 3 || tags.tie_points.size() != 6) {
    refuse_geo(s, tags.tie_points.size() > 6 ? "has several tie points (a warped placement)"
                                             : "has no ModelPixelScale with one ModelTiePoint");
  }
  const double model_type = geo_key(tags.key_directory, 1024, 1.0);
  if (model_type != 1.0) {
    refuse_geo(s, model_type == 2.0 ? "is placed in geographic degrees (a map projection first)"
                                    : "has GTModelTypeGeoKey " + format_number(model_type) +
                                          "; allowed 1 (projected)");
  }
  const double linear_units = geo_key(tags.key_directory, 3076, 9001.0);
  const double metres = linear_units == 9001.0   ? 1.0
                        : linear_units == 9002.0 ? 0.3048
                        : linear_units == 9003.0 ? 1200.0 / 3937.0
                                                 : 0.0;
  if (metres == 0.0) {
    refuse_geo(s, "has ProjLinearUnitsGeoKey " + format_number(linear_units) +
                      "; allowed 9001 (metre), 9002 (foot), 9003 (US survey foot)");
  }
  // Heights are read as the samples' own numbers, which `height` maps: only metres say so.
  const double vertical_units = geo_key(tags.key_directory, 4099, 9001.0);
  if (vertical_units != 9001.0) {
    refuse_geo(s, "has VerticalUnitsGeoKey " + format_number(vertical_units) +
                      "; allowed 9001 (metre) or none");
  }
  const double raster_type = geo_key(tags.key_directory, 1025, 1.0);
  if (raster_type != 1.0 && raster_type != 2.0) {
    refuse_geo(s, "has GTRasterTypeGeoKey " + format_number(raster_type) +
                      "; allowed 1 (PixelIsArea) or 2 (PixelIsPoint)");
  }
  const double sx = tags.pixel_scale[0], sy = tags.pixel_scale[1];
  if (!(std::isfinite(sx) && std::isfinite(sy) && sx > 0 && sy > 0)) {
    refuse_geo(s, "has ModelPixelScale " + format_number(sx) + ", " + format_number(sy) +
                      "; allowed positive and finite");
  }
  // Raster point (0, 0): the top-left pixel's corner (PixelIsArea) or centre (PixelIsPoint).
  const double shift = raster_type == 2.0 ? 0.5 : 0.0;
  const double I = tags.tie_points[0], J = tags.tie_points[1];
  const double X = tags.tie_points[3], Y = tags.tie_points[4];
  const double left = (X + (-shift - I) * sx) * metres;
  const double right = (X + (width - shift - I) * sx) * metres;
  const double top = (Y - (-shift - J) * sy) * metres;
  const double bottom = (Y - (height - shift - J) * sy) * metres;
  const std::array<double, 4> extent = {left, -top, right, -bottom};  // z = -Y: north up
  for (const double v : extent) {
    if (!(std::abs(v) <= limits::kMaxCameraCoordinate)) {
      refuse_geo(s, "is placed at " + format_number(v) + " m; allowed within +-1e12");
    }
  }
  if (!(extent[2] - extent[0] >= limits::kMinSketchSpan &&
        extent[3] - extent[1] >= limits::kMinSketchSpan)) {
    refuse_geo(s, "spans " + format_number(extent[2] - extent[0]) + " x " +
                      format_number(extent[3] - extent[1]) + " m; allowed at least 0.001 m a side");
  }
  return extent;
}

}  // namespace relief
