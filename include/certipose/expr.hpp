// certipose/expr.hpp — umbrella for compile-time expressions and constraints: box variables,
// constants, interval parameters, operators, 3-vectors, `in`/`<=`/`>=`/`==` constraints and
// forward evaluation (expr/).
#pragma once

#include "certipose/expr/constraint.hpp"  // IWYU pragma: export
#include "certipose/expr/evaluate.hpp"  // IWYU pragma: export
#include "certipose/expr/expression.hpp"  // IWYU pragma: export
#include "certipose/expr/vector.hpp"  // IWYU pragma: export
