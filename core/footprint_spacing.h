// Stage 2's local grid spacing sigma (§4.1's LOD), shared by the plane (projected_domain.cc)
// and the sphere (planet_domain.cc): the half distance between a vertex's two neighbours'
// footprints along one grid axis, one-sided where a neighbour is invalid.
#pragma once

namespace relief {

template <class Real>
struct Footprint {
  Real x = 0;
  Real z = 0;
  bool valid = false;
};

template <class Real>
Real footprint_distance_sq(const Footprint<Real>& a, const Footprint<Real>& b) {
  const Real ex = a.x - b.x;
  const Real ez = a.z - b.z;
  return ex * ex + ez * ez;
}

// Squared spacing along one grid axis from the centre and its two neighbours.
template <class Real>
Real axis_spacing_sq(const Footprint<Real>& minus, const Footprint<Real>& centre,
                     const Footprint<Real>& plus) {
  if (minus.valid && plus.valid) {
    return footprint_distance_sq(minus, plus) * Real(0.25);
  }
  if (plus.valid) {
    return footprint_distance_sq(centre, plus);
  }
  if (minus.valid) {
    return footprint_distance_sq(minus, centre);
  }
  return Real(0);
}

}  // namespace relief
