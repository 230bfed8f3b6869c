// The worked numbers of docs/terrain-spec.md, checked against the code. That page is what an
// outside GPU, SIMD or double implementation of the terrain is written from, so every number
// it prints must be the code's: float bit for bit (a float port that follows the page gets
// these bits), double bit for bit as well (the page's operation order is the code's, without
// FMA). A change here is a change of the specification: update the page with it.
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include "core/basis_images.h"
#include "core/counter_hash.h"
#include "core/fbm.h"
#include "core/frame_plan.h"
#include "core/height_bounds.h"
#include "core/height_sketch.h"
#include "core/interpolant.h"
#include "core/lattice.h"
#include "core/octave_coordinates.h"
#include "core/stage_params.h"
#include "tests/core/terrain_spec_cases.h"
#include "tests/core/terrain_spec_exact_case.h"
#include "tests/core/terrain_spec_sketch_basis_cases.h"

namespace relief {
namespace {

using namespace spec_numbers;

// G = g_n d in the form the frame chose for octave n (octave_coordinates.h), as fbm.cc forms
// it: the test checks the page's G column against the code's two forms, not against itself.
template <class Real>
Real coordinate_term(const FbmParams<Real>& p, int n, Real d) {
  if (!p.exact_coordinates[n]) {
    return p.frequency[n] * (d * p.inv_scale);
  }
  Real d_hi, d_lo;
  split_halves(d, d_hi, d_lo);
  Real piece[kScalePieces<Real>], hi[kScalePieces<Real>], lo[kScalePieces<Real>];
  for (int q = 0; q < kScalePieces<Real>; ++q) {
    piece[q] = p.scale_piece[q][n];
    hi[q] = p.scale_piece_hi[q][n];
    lo[q] = p.scale_piece_lo[q][n];
  }
  return exact_scaled_mod(piece, hi, lo, d, d_hi, d_lo, p.period, p.inv_period);
}

template <class Real>
void check_octaves(const TerrainPlan& plan, const NoiseLattice& lattice, const WorkedCase& c,
                   const CellRow<Real>& cell, const std::vector<OctaveRow<Real>>& rows,
                   Real height) {
  const Real dx = Real(c.dx), dz = Real(c.dz), nu = Real(c.nu);
  // The forms of a frame of this one vertex, as fbm_height chooses them.
  FbmParams<Real> params = make_fbm_params<Real>(plan);
  const std::uint8_t valid = 1;
  choose_coordinate_forms(
      plan,
      octave_reach<Real>(IndexRange{0, 1}, std::span<const Real>(&dx, 1),
                         std::span<const Real>(&dz, 1), std::span<const Real>(&nu, 1),
                         std::span<const std::uint8_t>(&valid, 1)),
      params);

  const LatticeCell<Real> located = locate_cell(lattice, rows[0].px, rows[0].pz);
  CHECK(located.i0 == cell.i0);
  CHECK(located.j0 == cell.j0);
  CHECK(located.i1 == cell.i1);
  CHECK(located.j1 == cell.j1);
  CHECK(located.fx == cell.fx);
  CHECK(located.fz == cell.fz);
  CHECK(fade<Interpolant::kQuintic>(located.fx) == cell.tx);
  CHECK(fade<Interpolant::kQuintic>(located.fz) == cell.tz);
  CHECK(lattice.at(cell.i0, cell.j0) == cell.v00);
  CHECK(lattice.at(cell.i1, cell.j0) == cell.v10);
  CHECK(lattice.at(cell.i0, cell.j1) == cell.v01);
  CHECK(lattice.at(cell.i1, cell.j1) == cell.v11);

  REQUIRE(rows.size() <= static_cast<std::size_t>(params.count));
  for (std::size_t n = 0; n < rows.size(); ++n) {
    const OctaveRow<Real>& row = rows[n];
    const int octave = static_cast<int>(n);
    INFO("octave n = " << n);
    CHECK(params.exact_coordinates[n] == row.exact);
    CHECK(params.offset_x[n] == row.offset_x);
    CHECK(params.offset_z[n] == row.offset_z);
    CHECK(coordinate_term(params, octave, dx) == row.gx);
    CHECK(coordinate_term(params, octave, dz) == row.gz);
    CHECK((params.offset_x[n] + row.gx) + row.wx == row.px);
    CHECK((params.offset_z[n] + row.gz) + row.wz == row.pz);
    CHECK(sample_lattice<Interpolant::kQuintic>(lattice, row.px, row.pz) == row.s);
    CHECK(params.relative_base_height + params.height_scale * row.h == row.height);
    // The height with this octave the last one summed: nu = n + 1 sums octaves 0..n whole
    // with the same warp (the update after the last whole octave is never read); the last
    // row is the fractional octave of nu itself.
    const Real last_nu = n + 1 < rows.size() ? Real(n + 1) : nu;
    CHECK(fbm_height<Real>(plan, dx, dz, last_nu) == row.height);
  }
  CHECK(fbm_height<Real>(plan, dx, dz, nu) == height);
}

void check_case(const TerrainSettings& terrain, const WorkedCase& c) {
  const NoiseLattice lattice = make_noise_lattice(terrain.seed, terrain.lattice_size);
  const TerrainPlan plan = make_terrain_plan(terrain, lattice, c.camera);
  const double period = terrain.lattice_size;
  for (std::size_t n = 0; n < c.plan.size(); ++n) {
    INFO("plan octave n = " << n);
    const auto k = static_cast<std::uint64_t>(terrain.first_octave) + n;
    CHECK(plan.octaves.frequency[n] == c.plan[n].frequency);
    CHECK(plan.octaves.amplitude[n] == c.plan[n].amplitude);
    CHECK(plan.octaves.scale[n] == c.plan[n].scale);
    // omega_k as docs/noise-lattice.md specifies it.
    CHECK(double(counter_hash(terrain.seed, HashStream::kOctaveOffset, k, 0) >> 40) *
              (period * 0x1p-24) ==
          c.plan[n].omega_x);
    CHECK(double(counter_hash(terrain.seed, HashStream::kOctaveOffset, k, 1) >> 40) *
              (period * 0x1p-24) ==
          c.plan[n].omega_z);
  }
  check_octaves<double>(plan, lattice, c, c.cell_double, c.octaves_double, c.height);
  check_octaves<float>(plan, lattice, c, c.cell_float, c.octaves_float, c.height_float);
}

TEST_CASE("specWorkedNumbersOfTheDefaultTerrainAreTheCodes", "[spec]") {
  check_case(TerrainSettings{}, kCaseA);
}

TEST_CASE("specWorkedNumbersOfANonIntegerLacunarityFarOutAreTheCodes", "[spec]") {
  TerrainSettings terrain;
  terrain.r = 2.17;
  const NoiseLattice lattice = make_noise_lattice(terrain.seed, terrain.lattice_size);
  // No r^k but r^0 is an integer: the camera is not reduced, and r^k is the repeated product,
  // not pow (2.17^3 = 10.218313 by products, 10.218312999999998 by pow).
  const TerrainPlan plan = make_terrain_plan(terrain, lattice, kCaseB.camera);
  CHECK_FALSE(plan.octaves.periodic);
  CHECK(plan.octaves.frequency[3] == 10.218313);
  check_case(terrain, kCaseB);
}

TEST_CASE("specWorkedNumbersOfACameraATrillionUnitsOutAreTheCodes", "[spec]") {
  const TerrainSettings terrain;
  const NoiseLattice lattice = make_noise_lattice(terrain.seed, terrain.lattice_size);
  const TerrainPlan plan = make_terrain_plan(terrain, lattice, kCaseC.camera);
  CHECK(plan.octaves.periodic);
  CHECK(plan.octaves.world_period == 768000.0);  // P * horizontal_scale
  check_case(terrain, kCaseC);
}

TEST_CASE("specWorkedNumbersOfTheWarpedTerrainAreTheCodes", "[spec]") {
  TerrainSettings terrain;  // lava's terrain: Figure 3's constants
  terrain.warp.enabled = true;
  terrain.warp.r0 = {3.0, 4.0};  // normalised to (0.6, 0.8) before use
  terrain.warp.t0 = {0.5, -0.25};
  const NoiseLattice lattice = make_noise_lattice(terrain.seed, terrain.lattice_size);
  const TerrainPlan plan = make_terrain_plan(terrain, lattice, kCaseD.camera);
  CHECK(plan.warp.r0x == 0.6);
  CHECK(plan.warp.r0z == 0.8);
  CHECK(make_fbm_params<float>(plan).r0x == 0.6f);
  CHECK(make_fbm_params<float>(plan).r0z == 0.8f);
  check_case(terrain, kCaseD);
}

TEST_CASE("specWorkedNumbersOfTheExactCoordinateFormAreTheCodes", "[spec]") {
  TerrainSettings terrain;
  terrain.H = 0.05;
  terrain.last_octave = 23;
  check_case(terrain, kCaseE);
  // The page's step-by-step table of octave 23: the three float pieces of g_23 and their
  // halves, and the halves of dx.
  const NoiseLattice lattice = make_noise_lattice(terrain.seed, terrain.lattice_size);
  const FbmParams<float> params =
      make_fbm_params<float>(make_terrain_plan(terrain, lattice, kCaseE.camera));
  const float piece[3] = {2796.2026f, 2.9947916e-05f, 4.5474735e-13f};
  const float hi[3] = {2796.0f, 2.9951334e-05f, 4.5474735e-13f};
  const float lo[3] = {0.20263672f, -3.417881e-09f, 0.0f};
  for (int q = 0; q < 3; ++q) {
    CHECK(params.scale_piece[q][23] == piece[q]);
    CHECK(params.scale_piece_hi[q][23] == hi[q]);
    CHECK(params.scale_piece_lo[q][23] == lo[q]);
  }
  float d_hi, d_lo;
  split_halves(float(kCaseE.dx), d_hi, d_lo);
  CHECK(d_hi == 45680.0f);
  CHECK(d_lo == -1.75f);
}

TEST_CASE("specHeightBoundsOfTheDefaultSceneAreTheCodes", "[spec]") {
  // sum_k r^(-kH) times the lattice's extremes, widened by kHeightBoundSlack of the larger
  // magnitude, then base + amplitude * (...): what stages.json reports as height_bounds.
  const TerrainSettings terrain;
  const HeightBounds bounds = derive_height_bounds(make_noise_lattice(1, 256), terrain);
  CHECK(bounds.world_min == -3171.249194021546);
  CHECK(bounds.world_max == 3469.8280586799074);
}

// Case F (section 11): the page's per-vertex arithmetic, done here in Real, against the
// page's numbers; then the code's sample_sketch and add_sketch against B.
template <class Real>
void check_sketch_point(const SketchPlan& plan, const HeightSketch& sketch, Real s_x, Real s_z,
                        Real t_x, Real t_z, int i, int j, Real b) {
  const SketchParams<Real> params = make_sketch_params<Real>(plan, &sketch);
  CHECK(params.offset_x == Real(kSketchPlan_offset_x));
  CHECK(params.inv_cell_z == Real(kSketchPlan_inv_cell_z));
  CHECK(params.max_x == Real(6));
  CHECK(params.max_z == Real(5));
  const Real dx = Real(-733.5), dz = Real(1911.75);
  const Real sx = params.offset_x + dx * params.inv_cell_x;
  const Real sz = params.offset_z + dz * params.inv_cell_z;
  CHECK(sx == s_x);  // inside [-2, max]: the clamps leave both
  CHECK(sz == s_z);
  CHECK(sx - std::floor(sx) == t_x);
  CHECK(sz - std::floor(sz) == t_z);
  CHECK(int(std::floor(sx)) == i);  // taps i - 1 = -1 and j + 2 = 4 lie past the edges
  CHECK(int(std::floor(sz)) == j);
  CHECK(sample_sketch<Real>(params, sketch.heights, sx, sz) == b);
  Real height = Real(0);
  const std::uint8_t mask = 1;
  add_sketch<Real>(params, sketch.heights, IndexRange{0, 1}, std::span<const Real>(&dx, 1),
                   std::span<const Real>(&dz, 1), {}, std::span<const std::uint8_t>(&mask, 1),
                   std::span<Real>(&height, 1));
  CHECK(height == b);
}

TEST_CASE("specWorkedSketchCaseIsTheCodes", "[spec]") {
  SketchSettings settings;
  settings.image = "case F";
  settings.extent = {-1000.0, -2000.0, 1500.0, 3000.0};
  settings.height = {-150.0, 850.0};
  std::vector<std::uint16_t> grey;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 5; ++i) {
      grey.push_back(static_cast<std::uint16_t>((i * 9973 + j * 21001 + 1234) % 65536));
    }
  }
  const HeightSketch sketch = make_height_sketch(settings, 5, 4, grey, 65535);
  const SketchPlan plan = make_sketch_plan(settings, sketch, 120.25, -310.5);
  CHECK(plan.offset_x == kSketchPlan_offset_x);
  CHECK(plan.offset_z == kSketchPlan_offset_z);
  CHECK(plan.inv_cell_x == kSketchPlan_inv_cell_x);
  CHECK(plan.inv_cell_z == kSketchPlan_inv_cell_z);
  check_sketch_point<double>(plan, sketch, kSketchDouble_s_x, kSketchDouble_s_z, kSketchDouble_t_x,
                             kSketchDouble_t_z, kSketchDouble_i, kSketchDouble_j, kSketchDouble_b);
  check_sketch_point<float>(plan, sketch, kSketchFloat_s_x, kSketchFloat_s_z, kSketchFloat_t_x,
                            kSketchFloat_t_z, kSketchFloat_i, kSketchFloat_j, kSketchFloat_b);
}

// Case G (section 12): two 4 x 4 images, the first normalised, the second at weight 0.5,
// composed, refined twice per side (P = 8) and sampled at case A's point.
GreyGrid case_g_image(int which) {
  GreyGrid grid{.side = 4, .values = {}};
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const int grey = which == 0 ? (x * x * 4099 + y * 13001 + 777) % 65536
                                  : ((x + 2 * y) * 7919 + 4321) % 65536;
      grid.values.push_back(grey / 65535.0);
    }
  }
  return grid;
}

TEST_CASE("specWorkedBasisCaseIsTheCodes", "[spec]") {
  GreyGrid first = case_g_image(0);
  const GreyGrid raw = first;
  BasisImageSettings normalized;
  normalized.normalize = true;
  filter_basis_image(first, normalized, "terrain.basis.images[0]");
  for (std::size_t t = 0; t < 16; ++t) {
    CHECK(first.values[t] == (raw.values[t] - kBasisMean) / kBasisDeviation);
  }
  const GreyGrid second = case_g_image(1);
  const BasisTerm terms[2] = {{.image = &first, .weight_image = nullptr, .weight = 1.0},
                              {.image = &second, .weight_image = nullptr, .weight = 0.5}};
  const NoiseLattice unrefined = compose_basis(terms, 4, 1);
  GreyGrid composed{.side = 4, .values = {}};
  for (std::size_t t = 0; t < 16; ++t) {
    CHECK(unrefined.values[t] == float(kBasisComposed[t]));
    composed.values.push_back(kBasisComposed[t]);
  }
  const NoiseLattice lattice = compose_basis(terms, 4, 2);
  const GreyGrid refined = bspline_refine(composed, 2);
  REQUIRE(lattice.values.size() == 64);
  for (std::size_t t = 0; t < 64; ++t) {
    CHECK(lattice.values[t] == kBasisRefined[t]);
    CHECK(float(refined.values[t]) == kBasisRefined[t]);
  }
  TerrainSettings terrain;
  terrain.interpolant = Interpolant::kLinear;
  BasisSettings basis;  // tile_size 24000: a cell of 24000 / 8 = 3000, case A's
  basis.upsample = 2;
  terrain.basis = basis;
  const TerrainSettings stage3 = stage3_terrain(terrain, 8);
  CHECK(stage3.lattice_size == 8);
  CHECK(stage3.horizontal_scale == 3000.0);
  const TerrainPlan plan = make_terrain_plan(stage3, lattice, kCaseA.camera);
  CHECK(fbm_height<double>(plan, kCaseA.dx, kCaseA.dz, kCaseA.nu) == kBasisDouble_height);
  CHECK(fbm_height<float>(plan, float(kCaseA.dx), float(kCaseA.dz), float(kCaseA.nu)) ==
        kBasisFloat_height);
  // Octave 0 alone (a_0 = 1): height = relative base + height scale * S(p_0).
  const FbmParams<double> pd = make_fbm_params<double>(plan);
  CHECK(fbm_height<double>(plan, kCaseA.dx, kCaseA.dz, 1.0) ==
        pd.relative_base_height + pd.height_scale * kBasisDouble_s0);
  const FbmParams<float> pf = make_fbm_params<float>(plan);
  CHECK(fbm_height<float>(plan, float(kCaseA.dx), float(kCaseA.dz), 1.0f) ==
        pf.relative_base_height + pf.height_scale * kBasisFloat_s0);
}

}  // namespace
}  // namespace relief
