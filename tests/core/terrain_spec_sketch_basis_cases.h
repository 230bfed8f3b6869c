// The worked numbers of docs/terrain-spec.md's cases F (section 11, the sketch) and G (section
// 12, basis images), printed by their generator, tests/oracles/sketch_basis_spec.py (written
// from the page alone): `python3 tests/oracles/sketch_basis_spec.py` prints the lines below.
// tests/core/terrain_spec_test.cc checks them against the code; ctest
// golden_numbers_have_an_independent_source re-derives each one.
#pragma once

namespace relief::spec_numbers {

// clang-format off
inline constexpr double kSketchPlan_offset_x = 1.7405;
inline constexpr double kSketchPlan_offset_z = 0.8516000000000001;
inline constexpr double kSketchPlan_inv_cell_x = 0.002;
inline constexpr double kSketchPlan_inv_cell_z = 0.0008;
inline constexpr double kSketchDouble_s_x = 0.27349999999999985;
inline constexpr double kSketchDouble_s_z = 2.3810000000000002;
inline constexpr double kSketchDouble_t_x = 0.27349999999999985;
inline constexpr double kSketchDouble_t_z = 0.3810000000000002;
inline constexpr double kSketchDouble_b = 542.8450961257531;
inline constexpr int kSketchDouble_i = 0;
inline constexpr int kSketchDouble_j = 2;
inline constexpr float kSketchFloat_s_x = 0.27349985f;
inline constexpr float kSketchFloat_s_z = 2.381f;
inline constexpr float kSketchFloat_t_x = 0.27349985f;
inline constexpr float kSketchFloat_t_z = 0.38100004f;
inline constexpr float kSketchFloat_b = 542.8451f;
inline constexpr int kSketchFloat_i = 0;
inline constexpr int kSketchFloat_j = 2;
inline constexpr double kBasisMean = 0.46584267948424507;
inline constexpr double kBasisDeviation = 0.2747988316467004;
inline constexpr double kBasisComposed[16] = {-1.0794007422879501, -0.8873825719992036, -0.3918855240662569, 0.40709040151089, -0.5175638345812678, -0.32554566429252146, 0.16995138364042528, 0.9689273092175723, 0.04427307312541434, 0.23629124341416077, 0.7317882913471075, 1.5307642169242548, 0.6061099808320964, 0.798128151120843, 0.9602867793798241, -0.666791421084784};
inline constexpr float kBasisRefined[64] = {-0.50174105f, -0.5782809f, -0.4715042f, -0.28863317f, -0.080435164f, 0.09388003f, 0.084878586f, -0.19576776f, -0.48149222f, -0.61570436f, -0.510222f, -0.30377614f, -0.02777844f, 0.2631756f, 0.3144351f, -0.048752625f, -0.23781228f, -0.38026333f, -0.27496585f, -0.06515219f, 0.2205312f, 0.52814794f, 0.58801615f, 0.21303679f, 0.03352495f, -0.100687206f, 0.0047951774f, 0.21124102f, 0.48723873f, 0.77819276f, 0.8294523f, 0.46626455f, 0.24737483f, 0.17083493f, 0.27761164f, 0.46048272f, 0.6686807f, 0.8429959f, 0.83399445f, 0.5533481f, 0.33775517f, 0.38479868f, 0.494349f, 0.62670267f, 0.68961555f, 0.61399037f, 0.47585836f, 0.37208638f, 0.20470442f, 0.32589796f, 0.43711242f, 0.53915566f, 0.51489747f, 0.28930807f, 0.073697716f, 0.07605034f, -0.17726198f, -0.13021849f, -0.020668173f, 0.111685514f, 0.1745984f, 0.0989732f, -0.03915881f, -0.1429308f};
inline constexpr double kBasisDouble_height = -412.7807156351406;
inline constexpr double kBasisDouble_s0 = 0.23580204882192643;
inline constexpr float kBasisFloat_height = -412.7807f;
inline constexpr float kBasisFloat_s0 = 0.23580196f;
// clang-format on

}  // namespace relief::spec_numbers
