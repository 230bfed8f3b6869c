// The linear bound's share for the cloud layer over terrain (docs/gl-shading.md, "Clouds over
// terrain"). The layer's density reads the lattice at coordinates u = (offset + x / cell) +
// warp x gain, whose float rounding is up to an ulp of |u| (1.5e-5 cells below 256): the
// density is a staircase at that scale, and two evaluations whose positions differ by a few
// ulps (GL's interpolants against the CPU's) may land on different steps. Through the
// layer's optical depth (and the warp's gain of up to 2^i cells per cell of warp) a step
// reaches 1e-5 of the radiance, at pixels where the image changes by under 1e-3 between
// neighbours: beyond the shifted-sample bound, which assumes a radiance smooth at the
// pixel scale.
//
// So where the scene has clouds, each covered pixel's radiance is also allowed the spread of
// the CPU's own shading (core/shade.h, terrain_radiance) over the box of positions the GL's
// interpolation arithmetic may give: the arithmetic part of the interpolants' bound
// (attribute_rounding, tests/oracles/gl_interpolation_bound.h: the planes' roundings and the
// final ones) on the camera-relative x, z and height, at the box's extremes and middle on
// each axis, 27 positions, every other attribute the CPU's. The sample's shift (up to 1/256
// px) moves every attribute together along the surface and is the shifted-sample term's
// already. The box is a few ulps wide on each axis and the staircase a few levels at a pixel,
// so 27 positions meet them: an estimate of the spread, as the level-switch envelope is, not a
// proof. A sample that is not finite (which the CPU's shading never gives) leaves the pixel
// no envelope.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/shade.h"
#include "core/stage_params.h"
#include "pipeline/scene_resources.h"
#include "raster/resolve.h"
#include "tests/oracles/whole_frame.h"

namespace relief::test {

// Per channel of each pixel (3 per pixel, as FrameImage::linear): the spread of the CPU's
// linear radiance (times the exposure) over the box [a - rounding, a + rounding] of the
// pixel's dx, dz and height; 0 where no terrain covers the pixel, a rounding is not finite or
// a sample is not finite.
inline std::vector<double> cloud_position_envelope(const TerrainFrame& frame,
                                                   const ShadeParams<float>& params,
                                                   const SceneResources& resources,
                                                   const std::vector<double>& dx_rounding,
                                                   const std::vector<double>& dz_rounding,
                                                   const std::vector<double>& height_rounding) {
  const raster::ResolvedFrame resolved = resolve_for_shading(frame);
  const ShadingInputs inputs = shading_inputs(frame, resolved);
  const ShadeResources shade{&resources.lattice, resources.textures};
  const std::size_t pixels = inputs.primitive.size();
  std::vector<double> envelope(3 * pixels, 0.0);
  ShadeWork work;
  for (std::size_t k = 0; k < pixels; ++k) {
    const double tolerance[3] = {dx_rounding[k], dz_rounding[k], height_rounding[k]};
    if (inputs.primitive[k] == 0xffffffffu || !std::isfinite(tolerance[0]) ||
        !std::isfinite(tolerance[1]) || !std::isfinite(tolerance[2])) {
      continue;
    }
    const PixelAttributes<float> a = inputs.at<float>(k);
    double low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
    bool finite = true;
    for (int sx = -1; sx <= 1; ++sx) {
      for (int sz = -1; sz <= 1; ++sz) {
        for (int sh = -1; sh <= 1; ++sh) {
          PixelAttributes<float> b = a;
          b.dx = float(double(a.dx) + sx * tolerance[0]);
          b.dz = float(double(a.dz) + sz * tolerance[1]);
          b.height = float(double(a.height) + sh * tolerance[2]);
          const Vec3<float> radiance = terrain_radiance(params, shade, b, work);
          // shade_pixels' product, rounded in float as the frame's linear output is.
          const float linear[3] = {radiance.x * params.exposure, radiance.y * params.exposure,
                                   radiance.z * params.exposure};
          for (int c = 0; c < 3; ++c) {
            finite = finite && std::isfinite(linear[c]);
            low[c] = std::min(low[c], double(linear[c]));
            high[c] = std::max(high[c], double(linear[c]));
          }
        }
      }
    }
    for (int c = 0; c < 3 && finite; ++c) {
      envelope[3 * k + c] = high[c] - low[c];
    }
  }
  return envelope;
}

}  // namespace relief::test
