#include "core/projected_domain.h"

#include <algorithm>
#include <cmath>

#include "core/det_math.h"
#include "core/limits.h"
#include "core/projected_domain_rows.h"

namespace relief {

template <class Real>
void project_domain(const DomainParams<Real>& p, const DomainRows<Real>& table, RowRange rows,
                    DomainSpans<Real> out) {
  project_domain_rows(p, table, rows, out, p.terrain_visible != 0,
                      [&](Real x, Real y, Real descent, Real& dx, Real& dz) {
                        return p.rays.footprint(x, y, descent, dx, dz);
                      });
}

template void project_domain<float>(const DomainParams<float>&, const DomainRows<float>&, RowRange,
                                    DomainSpans<float>);
template void project_domain<double>(const DomainParams<double>&, const DomainRows<double>&,
                                     RowRange, DomainSpans<double>);

}  // namespace relief
