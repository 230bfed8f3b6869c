// Highway's per-target compilation of simd/projected_domain-inl.h and its dynamic dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/projected_domain.cc"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "simd/projected_domain-inl.h"

#if HWY_ONCE
#include "simd/projected_domain.h"

namespace relief::simd {

HWY_EXPORT(ProjectDomainRows);
HWY_EXPORT(ProjectPlanetDomainRows);

void project_domain(const DomainParams<float>& params, const DomainRows<float>& table,
                    RowRange rows, DomainSpans<float> out) {
  HWY_DYNAMIC_DISPATCH(ProjectDomainRows)(params, table, rows, out);
}

void project_planet_domain(const DomainParams<float>& params, const PlanetParams<float>& planet,
                           const DomainRows<float>& table, RowRange rows, DomainSpans<float> out) {
  HWY_DYNAMIC_DISPATCH(ProjectPlanetDomainRows)(params, planet, table, rows, out);
}

}  // namespace relief::simd
#endif  // HWY_ONCE
