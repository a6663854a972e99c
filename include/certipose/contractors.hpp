// certipose/contractors.hpp — umbrella for expressions, constraints, contractors and box tests.
//
// Expressions over box variables (`var<0>`, sqr, sin, dot, ...), constraints (`in(e, a, b)`,
// `<=`, `>=`, `==`), the contractors `hc4`, `acid`, `not_in`, `identity`, their compositions
// (`compose` / `&`, `union_of` / `|`, `fixpoint`) and the box tests `eval_test` and
// `not_in_test` used by the paver. Interval backends are included separately
// (interval/boost_interval.hpp, interval/cgal_interval.hpp). See docs/contractors.md.
#pragma once

#include "certipose/contractor/acid.hpp"  // IWYU pragma: export
#include "certipose/contractor/compose.hpp"  // IWYU pragma: export
#include "certipose/contractor/concept.hpp"  // IWYU pragma: export
#include "certipose/contractor/eval_test.hpp"  // IWYU pragma: export
#include "certipose/contractor/fixpoint.hpp"  // IWYU pragma: export
#include "certipose/contractor/hc4.hpp"  // IWYU pragma: export
#include "certipose/contractor/identity.hpp"  // IWYU pragma: export
#include "certipose/contractor/not_in.hpp"  // IWYU pragma: export
#include "certipose/expr.hpp"  // IWYU pragma: export
