// Stage 7's Highway kernels (simd/resolve.h) over awkward counts of triangle slots and
// rectangles of every awkward width (tests/simd/kernel_ranges.h) on every target this CPU runs:
// the planes are raster::PerspectivePlane's and the resolved attributes raster's quad weights
// applied as the scalar tile resolve applies them (pipeline/tile_pass.cc), bit for bit, and no
// element outside the range, the rectangle or its covered pixels is written.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "raster/resolve.h"
#include "simd/resolve.h"
#include "simd/targets.h"
#include "tests/simd/kernel_ranges.h"
#include "tests/support/simd_targets.h"
#include "tests/support/test_support.h"

namespace relief {
namespace {

constexpr int kVertices = 64;
// dx, dz, height, nx, ny, nz, slope, water_depth, nu, lambert, drop
constexpr int kStreams = 11;
constexpr std::size_t kMaxSlots = 5 + 53 + test::kGuardElements;

// Per-vertex clip positions in front of the camera, the streams the resolve interpolates, and
// each slot's three vertices.
struct TileTriangles {
  std::vector<float> clip_x, clip_y, clip_w;
  std::vector<float> stream[kStreams];
  std::vector<std::int32_t> vertex[3];
  simd::WindowTransform window{32.0, 32.0, 32.0, 32.0};  // a 64 x 64 viewport

  TileTriangles() {
    test::TestRandom random(67);
    for (int v = 0; v < kVertices; ++v) {
      const float w = float(random.uniform(0.5, 10));
      clip_w.push_back(w);
      clip_x.push_back(float(random.uniform(-1.2, 1.2)) * w);
      clip_y.push_back(float(random.uniform(-1.2, 1.2)) * w);
      for (std::vector<float>& s : stream) {
        s.push_back(float(random.uniform(-500, 500)));
      }
    }
    for (std::vector<std::int32_t>& c : vertex) {
      for (std::size_t s = 0; s < kMaxSlots; ++s) {
        c.push_back(std::int32_t(random.uniform(0, kVertices - 1)));
      }
    }
  }

  // raster::VertexPositions' homogeneous window position of vertex v, in double.
  void position(std::int32_t v, double& x, double& y, double& w) const {
    w = clip_w[std::size_t(v)];
    x = clip_x[std::size_t(v)] * window.scale_x + w * window.translate_x;
    y = clip_y[std::size_t(v)] * window.scale_y + w * window.translate_y;
  }

  raster::PerspectivePlane plane(std::size_t slot) const {
    double x[3], y[3], w[3];
    for (int c = 0; c < 3; ++c) {
      position(vertex[c][slot], x[c], y[c], w[c]);
    }
    return raster::PerspectivePlane(x, y, w);
  }
};

TEST_CASE("simdPlaneSetUpForAwkwardSlotCountsIsRastersPlaneAndWritesOnlyItsSlots", "[simd]") {
  const EachTarget targets;
  const TileTriangles t;
  for (const std::size_t start : test::kRangeStarts) {
    for (const std::size_t count : test::awkward_lengths()) {
      std::vector<double> expected[9];
      for (std::vector<double>& e : expected) {
        e = test::sentinel_buffer<double>(start, count);
      }
      for (std::size_t s = 0; s < count; ++s) {
        const raster::PerspectivePlane p = t.plane(start + s);
        for (int i = 0; i < 3; ++i) {
          expected[i][start + s] = p.k[i];
          expected[3 + i][start + s] = p.ku[i];
          expected[6 + i][start + s] = p.kv[i];
        }
      }
      const std::int32_t* const vertex[3] = {t.vertex[0].data() + start, t.vertex[1].data() + start,
                                             t.vertex[2].data() + start};
      for (const std::string& target : targets.runnable()) {
        simd::force_target(target);
        std::vector<double> got[9];
        for (std::vector<double>& g : got) {
          g = test::sentinel_buffer<double>(start, count);
        }
        double* const k[3] = {got[0].data() + start, got[1].data() + start, got[2].data() + start};
        double* const ku[3] = {got[3].data() + start, got[4].data() + start, got[5].data() + start};
        double* const kv[3] = {got[6].data() + start, got[7].data() + start, got[8].data() + start};
        simd::set_up_planes(t.clip_x.data(), t.clip_y.data(), t.clip_w.data(), t.window, vertex,
                            count, k, ku, kv);
        INFO(target << ", start " << start << ", slots " << count);
        for (int i = 0; i < 9; ++i) {
          CHECK(test::same_bits(got[i], expected[i]));
        }
      }
    }
  }
}

// Which of the optional streams (7-10) are given: none, all, lambert alone (gradient shading
// without the octave output: the fourth group of a record read for lambert alone), or a
// planet's drop alone (the fourth and fifth groups read for the drop alone).
enum class Optional { kNone, kAll, kLambert, kDrop };

bool present(Optional optional, int stream) {
  return stream < 7 || optional == Optional::kAll ||
         (optional == Optional::kLambert && stream == 9) ||
         (optional == Optional::kDrop && stream == 10);
}

simd::ResolveStreams streams_of(const TileTriangles& t, Optional optional) {
  const auto at = [&](int s) { return present(optional, s) ? t.stream[s].data() : nullptr; };
  return {at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7), at(8), at(9), at(10)};
}

TEST_CASE("slotRecordsForAwkwardSlotCountsHoldTheirVerticesValuesAndNothingBeyond", "[simd]") {
  // simd/resolve.h's layout: stream f at vertex c of slot s at s * 40 + 3 f + c, 0 for a null
  // stream. (Plain C++ shared by every target, tried with the other kernels of the family.)
  const TileTriangles t;
  for (const Optional optional :
       {Optional::kNone, Optional::kAll, Optional::kLambert, Optional::kDrop}) {
    const simd::ResolveStreams streams = streams_of(t, optional);
    for (const std::size_t start : test::kRangeStarts) {
      for (const std::size_t count : test::awkward_lengths()) {
        const std::int32_t* const vertex[3] = {
            t.vertex[0].data() + start, t.vertex[1].data() + start, t.vertex[2].data() + start};
        std::vector<float> records =
            test::sentinel_buffer<float>(start, count * simd::kSlotRecordFloats);
        simd::gather_slot_records(streams, vertex, count, records.data() + start);
        INFO("optional streams " << int(optional) << ", start " << start << ", slots " << count);
        CHECK(test::untouched_outside(records, start, start + count * simd::kSlotRecordFloats));
        for (std::size_t s = 0; s < count; ++s) {
          for (int f = 0; f < kStreams; ++f) {
            for (int c = 0; c < 3; ++c) {
              const float value =
                  present(optional, f) ? t.stream[f][std::size_t(vertex[c][s])] : 0.0f;
              REQUIRE(records[start + s * simd::kSlotRecordFloats + 3 * std::size_t(f) +
                              std::size_t(c)] == value);
            }
          }
        }
      }
    }
  }
}

// The seventeen resolved fields in ResolveTargets' order.
constexpr int kTargets = 17;

simd::ResolveTargets targets_of(std::vector<float> (&out)[kTargets], std::size_t start) {
  float* p[kTargets];
  for (int f = 0; f < kTargets; ++f) {
    p[f] = out[f].data() + start;
  }
  return {p[0], p[1],  p[2],  p[3],  p[4],  p[5],  p[6],  p[7], p[8],
          p[9], p[10], p[11], p[12], p[13], p[14], p[15], p[16]};
}

// The scalar tile resolve of pipeline/tile_pass.cc at one pixel: raster's quad weights of the
// slot's plane, each value interpolated in double and rounded once; derivatives (fields 3-8)
// from the quad partners where defined, else 0.
void resolve_pixel(const TileTriangles& t, const simd::ResolveStreams& streams, std::size_t slot,
                   int px, int py, std::vector<float> (&out)[kTargets], std::size_t k) {
  const raster::QuadWeights q = raster::quad_weights(t.plane(slot), px, py);
  const auto at = [&](const float* s, const double weights[3]) {
    return raster::QuadWeights::at(weights, s[t.vertex[0][slot]], s[t.vertex[1][slot]],
                                   s[t.vertex[2][slot]]);
  };
  const float* const with_derivatives[3] = {streams.dx, streams.dz, streams.height};
  for (int f = 0; f < 3; ++f) {
    const double centre = at(with_derivatives[f], q.b);
    out[f][k] = float(centre);
    out[3 + 2 * f][k] = q.has_x ? float(q.sign_x * (at(with_derivatives[f], q.bx) - centre)) : 0;
    out[4 + 2 * f][k] = q.has_y ? float(q.sign_y * (at(with_derivatives[f], q.by) - centre)) : 0;
  }
  out[9][k] = float(at(streams.nx, q.b));
  out[10][k] = float(at(streams.ny, q.b));
  out[11][k] = float(at(streams.nz, q.b));
  out[12][k] = float(at(streams.slope, q.b));
  out[13][k] = streams.water_depth != nullptr ? float(at(streams.water_depth, q.b)) : 0.0f;
  if (streams.nu != nullptr) {
    out[14][k] = float(at(streams.nu, q.b));
  }
  if (streams.lambert != nullptr) {
    out[15][k] = float(at(streams.lambert, q.b));
  }
  if (streams.drop != nullptr) {
    out[16][k] = float(at(streams.drop, q.b));
  }
}

TEST_CASE("simdResolveOfAwkwardRectanglesIsTheScalarResolveAndWritesOnlyCoveredPixels", "[simd]") {
  const EachTarget targets;
  const TileTriangles t;
  test::TestRandom random(71);
  for (const Optional optional :
       {Optional::kNone, Optional::kAll, Optional::kLambert, Optional::kDrop}) {
    const simd::ResolveStreams streams = streams_of(t, optional);
    for (const std::size_t width : test::awkward_lengths()) {
      // Rows of whole 16-pixel groups (the kernel reads whole vectors of a row); the
      // rectangle's origin at even and odd pixels, so its first pixel is either of a quad's.
      const int stride = int((width + 15) / 16 * 16) + 16;
      for (const std::size_t start : test::kRangeStarts) {
        const int x0 = int(start), y0 = int(start) + 2, height = 3;
        const std::size_t pixels = std::size_t(height) * std::size_t(stride);
        // Every pixel's slot: a quarter uncovered (-1), the others among kMaxSlots triangles.
        std::vector<std::int32_t> slot(start + pixels + test::kGuardElements, -1);
        for (std::size_t k = start; k < start + pixels; ++k) {
          slot[k] = random.uniform(0, 1) < 0.25 ? -1 : std::int32_t(random.uniform(0, 20));
        }
        std::vector<float> expected[kTargets];
        for (std::vector<float>& e : expected) {
          e = test::sentinel_buffer<float>(start, pixels);
        }
        for (int j = 0; j < height; ++j) {
          for (int i = 0; i < int(width); ++i) {
            const std::size_t k = start + std::size_t(j) * std::size_t(stride) + std::size_t(i);
            if (slot[k] >= 0) {
              resolve_pixel(t, streams, std::size_t(slot[k]), x0 + i, y0 + j, expected, k);
            }
          }
        }
        // The slots' planes and records as the tile pass sets them up (checked above).
        std::vector<double> planes[9];
        for (std::vector<double>& p : planes) {
          p.assign(kMaxSlots, 0.0);
        }
        const std::int32_t* const vertex[3] = {t.vertex[0].data(), t.vertex[1].data(),
                                               t.vertex[2].data()};
        double* const k[3] = {planes[0].data(), planes[1].data(), planes[2].data()};
        double* const ku[3] = {planes[3].data(), planes[4].data(), planes[5].data()};
        double* const kv[3] = {planes[6].data(), planes[7].data(), planes[8].data()};
        simd::set_up_planes(t.clip_x.data(), t.clip_y.data(), t.clip_w.data(), t.window, vertex,
                            kMaxSlots, k, ku, kv);
        std::vector<float> records(kMaxSlots * simd::kSlotRecordFloats);
        simd::gather_slot_records(streams, vertex, kMaxSlots, records.data());
        const simd::ResolveSlots slots{
            {k[0], k[1], k[2]}, {ku[0], ku[1], ku[2]}, {kv[0], kv[1], kv[2]}, records.data()};
        for (const std::string& target : targets.runnable()) {
          simd::force_target(target);
          std::vector<float> got[kTargets];
          for (std::vector<float>& g : got) {
            g = test::sentinel_buffer<float>(start, pixels);
          }
          simd::resolve_rect(slots, streams, slot.data() + start, x0, y0, int(width), height,
                             stride, targets_of(got, start));
          INFO(target << ", optional streams " << int(optional) << ", width " << width
                      << ", origin " << x0 << ", " << y0);
          for (int f = 0; f < kTargets; ++f) {
            INFO("field " << f);
            CHECK(test::same_bits(got[f], expected[f]));
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace relief
