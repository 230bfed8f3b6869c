// The worked-numbers oracle's one printing convention (tests/oracles/worked/worked_numbers.cc):
// a named value as it is quoted in docs/architecture.md, docs/terrain-spec.md and
// docs/planet.md, in shortest round-trip decimal and in hexadecimal.
#pragma once

#include <cstdio>

namespace relief::test::worked {

inline void print_double(const char* name, double v) {
  std::printf("  %-28s %.17g  %a\n", name, v, v);
}
inline void print_float(const char* name, float v) {
  std::printf("  %-28s %.9g  %a\n", name, double(v), double(v));
}
template <class Real>
void print_real(const char* name, Real v) {
  if constexpr (sizeof(Real) == 4) {
    print_float(name, v);
  } else {
    print_double(name, v);
  }
}

}  // namespace relief::test::worked
