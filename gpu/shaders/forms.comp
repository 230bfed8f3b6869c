// Between stages 2 and 3: choose_coordinate_forms of core/octave_coordinates.cc, one
// invocation. The reach per octave is the running maximum of the finest-octave extents from
// the fine octaves down (a vertex summing octave n sums every coarser one); octave n takes the
// exact form where g_n * reach_n > P. The CPU decides in double from the plan's g_n; here g_n
// is the sum of its three float pieces, which is g_n exactly (stage_params.h: three floats
// hold a double, and the partial sums are doubles), and the product and comparison are double
// too. The decision is written into FbmParams::exact_coordinates of the parameter block that
// stage 3 reads, as the CPU frame writes it into its FbmParams.
layout(local_size_x = 1) in;

layout(std430, binding = RELIEF_BINDING_PARAMS) buffer FbmParamsBlock {
  FbmParams fbm;
};
layout(std430, binding = RELIEF_BINDING_REACH) readonly buffer ReachBlock {
  uint by_finest[RELIEF_MAX_OCTAVES];
};

void main() {
  precise double farthest = 0.0LF;
  precise double reach[RELIEF_MAX_OCTAVES];
  for (int n = RELIEF_MAX_OCTAVES - 1; n >= 0; --n) {
    const double extent = double(uintBitsToFloat(by_finest[n]));
    farthest = farthest < extent ? extent : farthest;
    reach[n] = farthest;
  }
  const double period = double(fbm.period);
  for (int n = 0; n < fbm.count; ++n) {
    precise double g = double(fbm.scale_piece[0][n]) + double(fbm.scale_piece[1][n]) +
                       double(fbm.scale_piece[2][n]);
    precise double product = g * reach[n];
    fbm.exact_coordinates[n] = product > period ? 1 : 0;
  }
}
