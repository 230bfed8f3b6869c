#include "tools/stage_outputs.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene/scene_json.h"
#include "image/image_io.h"
#include "image/image_metadata.h"
#include "tools/atomic_file.h"
#include "tools/colormap.h"

namespace relief {

namespace {

using nlohmann::json;

struct ValueRange {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  bool empty() const { return min > max; }
};

ValueRange valid_range(const GridBuffers<float>& b, const AlignedVector<float>& field) {
  ValueRange range;
  for (int j = 0; j < b.layout.height; ++j) {
    for (int i = 0; i < b.layout.width; ++i) {
      const std::size_t k = b.layout.index(i, j);
      if (b.valid[k]) {
        range.min = std::min(range.min, static_cast<double>(field[k]));
        range.max = std::max(range.max, static_cast<double>(field[k]));
      }
    }
  }
  return range;
}

double normalise(double v, const ValueRange& range) {
  const double extent = range.max - range.min;
  return extent > 0 ? (v - range.min) / extent : 0.5;
}

// Colours each valid vertex with `color(k)`; invalid vertices are dark red.
std::vector<std::uint8_t> picture(const GridBuffers<float>& b,
                                  const std::function<Rgb8(std::size_t)>& color) {
  const GridLayout& l = b.layout;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(l.width) * l.height * 3);
  for (int j = 0; j < l.height; ++j) {
    for (int i = 0; i < l.width; ++i) {
      const std::size_t k = l.index(i, j);
      const Rgb8 c = b.valid[k] ? color(k) : Rgb8{90, 0, 0};
      std::copy(c.begin(), c.end(), rgb.begin() + (static_cast<std::size_t>(j) * l.width + i) * 3);
    }
  }
  return rgb;
}

// One channel of a raw file: the value at buffer index k.
std::function<float(std::size_t)> channel(const AlignedVector<float>& field) {
  return [&field](std::size_t k) { return field[k]; };
}

class StageWriter {
 public:
  StageWriter(std::filesystem::path dir, const GridBuffers<float>& buffers, OutputSet& files,
              FloatFormat raw_format, std::vector<ImageText> metadata)
      : dir_(std::move(dir)),
        buffers_(buffers),
        files_out_(files),
        raw_format_(raw_format),
        metadata_(std::move(metadata)) {}

  // Writes NAME.png and NAME.pfm (or .exr) and records them in the manifest.
  void field(const std::string& name, const std::string& meaning, const std::string& units,
             const std::vector<std::function<float(std::size_t)>>& channels,
             const std::function<Rgb8(std::size_t)>& color, const ValueRange& range) {
    const GridLayout& l = buffers_.layout;
    const std::vector<std::uint8_t> rgb = picture(buffers_, color);
    files_out_.add(dir_ / (name + ".png"), encode_png_rgb(l.width, l.height, rgb, metadata_));
    const int count = static_cast<int>(channels.size());  // PFM: 1 or 3
    std::vector<float> raw(static_cast<std::size_t>(l.width) * l.height * count);
    for (int j = 0; j < l.height; ++j) {
      for (int i = 0; i < l.width; ++i) {
        for (int c = 0; c < count; ++c) {
          raw[(static_cast<std::size_t>(j) * l.width + i) * count + c] = channels[c](l.index(i, j));
        }
      }
    }
    const std::string raw_name = name + std::string(float_extension(raw_format_));
    files_out_.add(dir_ / raw_name,
                   encode_float_image(raw_format_, l.width, l.height, count, raw,
                                      static_cast<std::size_t>(l.width) * count, metadata_));
    json entry = {{"image", name + ".png"},
                  {"raw", raw_name},
                  {"channels", count},
                  {"meaning", meaning},
                  {"units", units}};
    if (!range.empty()) {
      entry["valid_min"] = range.min;
      entry["valid_max"] = range.max;
    }
    files_[name] = entry;
  }

  const json& files() const { return files_; }

 private:
  std::filesystem::path dir_;
  const GridBuffers<float>& buffers_;
  OutputSet& files_out_;
  FloatFormat raw_format_;
  std::vector<ImageText> metadata_;  // carried by every PNG and EXR
  json files_ = json::object();
};

}  // namespace

void write_stage_outputs(const std::filesystem::path& dir, const Scene& scene,
                         const FramePlan& plan, const GridBuffers<float>& b,
                         FloatFormat raw_format) {
  OutputDirectory directory(dir);
  OutputSet files;  // every field and stages.json appear together or not at all
  StageWriter out(dir, b, files, raw_format, scene_metadata(scene));
  const double octave_cell = 1.0 / plan.terrain.inv_horizontal_scale;  // basis mode's too
  const glm::dvec3 camera = plan.camera.position;
  // A planet frame (docs/planet.md): the unbent frame's buffers, the normals rotated into the
  // bent one, and the bend itself (bent positions and drop).
  const bool bent = !b.bent_x.empty();

  // Domain: absolute base-domain position as two nested checkers (octave-0 cells in hue,
  // eighths of them in brightness), so both the far field and the near field show their
  // perspective.
  out.field(
      "domain",
      bent ? "camera-relative arc offset of each grid vertex on the sphere, as stage 2 writes "
             "and stage 3 evaluates it (the unbent frame; bent.pfm holds the bent positions): "
             "channels dx, dz (world units along the sphere) and the validity flag (1 valid, 0 "
             "invalid)"
           : "camera-relative base-domain position of each grid vertex: channels dx, dz (world "
             "units) and the validity flag (1 valid, 0 invalid)",
      "world units",
      {channel(b.dx), channel(b.dz), [&b](std::size_t k) { return float(b.valid[k]); }},
      [&](std::size_t k) {
        const double x = (camera.x + b.dx[k]) / octave_cell;
        const double z = (camera.z + b.dz[k]) / octave_cell;
        const bool coarse =
            (static_cast<long long>(std::floor(x)) + static_cast<long long>(std::floor(z))) & 1;
        const bool fine = (static_cast<long long>(std::floor(8 * x)) +
                           static_cast<long long>(std::floor(8 * z))) &
                          1;
        const double v = fine ? 1.0 : 0.6;
        return coarse ? Rgb8{static_cast<std::uint8_t>(230 * v), static_cast<std::uint8_t>(200 * v),
                             static_cast<std::uint8_t>(120 * v)}
                      : Rgb8{static_cast<std::uint8_t>(90 * v), static_cast<std::uint8_t>(150 * v),
                             static_cast<std::uint8_t>(230 * v)};
      },
      ValueRange{});

  ValueRange sigma_range = valid_range(b, b.sigma);
  const ValueRange log_sigma{std::log10(std::max(sigma_range.min, 1e-30)),
                             std::log10(std::max(sigma_range.max, 1e-30))};
  out.field(
      "sigma", "local grid spacing (heat map of log10 sigma)", "world units", {channel(b.sigma)},
      [&](std::size_t k) {
        return heat_color(normalise(std::log10(std::max<double>(b.sigma[k], 1e-30)), log_sigma));
      },
      sigma_range);

  const double nu_max = plan.lod.nu_max;
  out.field(
      "nu", "octave count (heat map from 1 to N)", "octaves", {channel(b.nu)},
      [&](std::size_t k) {
        return heat_color(nu_max > 1 ? (b.nu[k] - 1.0) / (nu_max - 1.0) : 0.0);
      },
      valid_range(b, b.nu));

  const ValueRange height_range = valid_range(b, b.height);
  out.field(
      "height",
      "terrain height relative to the camera, h - camera_position[1], as stage 3 computes it in "
      "float (gray from the lowest to the highest valid vertex); add camera_position[1] for the "
      "world height",
      "world units", {channel(b.height)},
      [&](std::size_t k) { return gray_color(normalise(b.height[k], height_range)); },
      height_range);

  out.field(
      "normal",
      bent ? "unit normal rotated into the bent frame (camera-relative axes), (n + 1) / 2 as RGB"
           : "unit normal, (n + 1) / 2 as RGB",
      "unit vector", {channel(b.nx), channel(b.ny), channel(b.nz)},
      [&](std::size_t k) {
        auto byte = [](float n) {
          return static_cast<std::uint8_t>(
              std::lround((std::clamp(n, -1.0f, 1.0f) + 1.0f) * 127.5f));
        };
        return Rgb8{byte(b.nx[k]), byte(b.ny[k]), byte(b.nz[k])};
      },
      ValueRange{});

  out.field(
      "slope", "slope |grad h| (heat map of its angle, 0 to 90 degrees)", "rise over run",
      {channel(b.slope)},
      [&](std::size_t k) {
        return heat_color(std::atan(static_cast<double>(b.slope[k])) / (M_PI / 2));
      },
      valid_range(b, b.slope));

  const ValueRange depth_range = valid_range(b, b.water_depth);
  out.field(
      "water_depth", "water depth below the water level (heat map; black: dry land)", "world units",
      {channel(b.water_depth)},
      [&](std::size_t k) {
        if (!(b.water_depth[k] > 0.0f)) {
          return Rgb8{0, 0, 0};
        }
        return heat_color(depth_range.max > 0 ? b.water_depth[k] / depth_range.max : 0.0);
      },
      depth_range);

  if (bent) {
    const ValueRange drop_range = valid_range(b, b.bent_drop);
    out.field(
        "bent",
        "camera-relative position of each grid vertex on the sphere after the bend (planet_bend.h):"
        " channels x, y, z; the sphere's centre is at (0, -D, 0), D = R + camera altitude, and "
        "a vertex lies at distance D + height from it (gray: y from the lowest to the highest "
        "valid vertex)",
        "world units", {channel(b.bent_x), channel(b.bent_y), channel(b.bent_z)},
        [&, range = valid_range(b, b.bent_y)](std::size_t k) {
          return gray_color(normalise(b.bent_y[k], range));
        },
        ValueRange{});
    out.field(
        "drop",
        "how far the bend lowers each vertex below its unbent height (stage 8 subtracts it; "
        "heat map from 0 to the largest)",
        "world units", {channel(b.bent_drop)},
        [&](std::size_t k) {
          return heat_color(drop_range.max > 0 ? b.bent_drop[k] / drop_range.max : 0.0);
        },
        drop_range);
  }

  std::size_t valid_count = 0;
  for (int j = 0; j < b.layout.height; ++j) {
    for (int i = 0; i < b.layout.width; ++i) {
      valid_count += b.valid[b.layout.index(i, j)];
    }
  }
  const json manifest = {
      {"format",
       raw_format == FloatFormat::kExr
           ? "Each field: NAME.png (picture; invalid vertices dark red) and NAME.exr (OpenEXR, "
             "float32 channels R, G, B or Y, rows top-to-bottom as in the picture = grid row 0 "
             "last)"
           : "Each field: NAME.png (picture; invalid vertices dark red) and NAME.pfm (PFM, "
             "little-endian float32, rows bottom-to-top = grid row 0 first, channels "
             "interleaved)"},
      {"grid", {{"width", b.layout.width}, {"height", b.layout.height}}},
      {"valid_vertices", valid_count},
      {"camera_position", {camera.x, camera.y, camera.z}},
      {"height_bounds", {{"min", plan.bounds.world_min}, {"max", plan.bounds.world_max}}},
      {"octaves", plan.terrain.octaves.count},
      {"files", out.files()},
      {"scene", scene_to_json(scene)}};
  const std::string text = manifest.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
  files.add(dir / "stages.json",
            std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
  files.commit();
  directory.keep();
}

}  // namespace relief
