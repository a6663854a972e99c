// certipose/expr/detail/rounding_scope.hpp — holds the rounding mode for one entry point
// (contract(), test(), evaluate()) without paying for nested guards.
//
// Not for users. Constructing `rounding_guard<I>` saves and sets the FPU mode, ~20 ns on
// these machines (boost: 24 ns, CGAL: 17 ns, measured) — a quarter of HC4's budget. A
// composition calls its parts' contract(), each of which must hold the mode too; so a scope
// constructs the backend's guard only when the mode is not already upward (a cheap register
// read), i.e. only at the outermost entry point. When the mode is already upward somebody up
// the stack holds a guard, which restores the caller's mode when it ends.
#pragma once

#include <optional>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"

namespace certipose::expr::detail {

template <class I>
class upward_scope {
public:
    upward_scope() {
        if (!certipose::detail::rounding_is_upward()) guard_.emplace();
    }
    upward_scope(const upward_scope&) = delete;
    upward_scope& operator=(const upward_scope&) = delete;

private:
    std::optional<rounding_guard<I>> guard_;
};

}  // namespace certipose::expr::detail
