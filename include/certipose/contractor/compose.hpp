// certipose/contractor/compose.hpp — composing contractors at compile time: sequence
// (`compose(a, b)`, `a & b`) and union (`union_of(a, b)`, `a | b`).
//
// IBEX composes `Ctc&` references through virtual calls; here the parts are held by value in
// a tuple and called directly, so a composition is as cheap as writing the calls by hand.
// Sequence: contract with each part in turn (stopping once the box is empty) — the result
// contains every point all parts keep. Union: contract a copy with each part and keep the hull
// of the results — the result contains every point some part keeps (IBEX's CtcUnion), which is
// how a disjunction of constraints is contracted.
//
// Any type modelling `Contractor` for the box works as a part, user-written ones included.
// `&` and `|` are found by ADL when one operand is a certipose contractor (a class with the
// member `using certipose_contractor = void;`, which user contractors may declare too, or
// `using certipose::operator&;`); `compose(...)` and `union_of(...)` always work.
#pragma once

#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/detail/forward_param.hpp"
#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose {

/// True for classes declaring `using certipose_contractor = void;` (every certipose contractor).
template <class T>
concept tagged_contractor = requires { typename std::remove_cvref_t<T>::certipose_contractor; };

template <class... Cs>
class compose {
    static_assert(sizeof...(Cs) >= 1, "certipose::compose needs at least one contractor");

public:
    using certipose_contractor = void;

    explicit compose(Cs... cs) : cs_(std::move(cs)...) {}

    template <Interval I, std::size_t N>
    void contract(interval_box<I, N>& box) {
        static_assert((Contractor<Cs, interval_box<I, N>> && ...),
                      "certipose::compose: every part must model Contractor for this box");
        const expr::detail::upward_scope<I> rounding;
        std::apply(
            [&](auto&... c) {
                (void)((is_empty(box) ? true : (c.contract(box), false)) || ...);
            },
            cs_);
    }

    std::tuple<Cs...>& parts() noexcept { return cs_; }
    const std::tuple<Cs...>& parts() const noexcept { return cs_; }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id, contractor_detail::param_targets::those_having_one>(cs_, lo, hi);
    }

private:
    std::tuple<Cs...> cs_;
};

template <class... Cs>
compose(Cs...) -> compose<Cs...>;

template <class... Cs>
class union_of {
    static_assert(sizeof...(Cs) >= 1, "certipose::union_of needs at least one contractor");

public:
    using certipose_contractor = void;

    explicit union_of(Cs... cs) : cs_(std::move(cs)...) {}

    template <Interval I, std::size_t N>
    void contract(interval_box<I, N>& box) {
        static_assert((Contractor<Cs, interval_box<I, N>> && ...),
                      "certipose::union_of: every part must model Contractor for this box");
        const expr::detail::upward_scope<I> rounding;
        if (is_empty(box)) return;
        auto result = interval_box<I, N>::empty();
        std::apply(
            [&](auto&... c) {
                (
                    [&] {
                        auto b = box;
                        c.contract(b);
                        result = hull(result, b);
                    }(),
                    ...);
            },
            cs_);
        box = result;
    }

    std::tuple<Cs...>& parts() noexcept { return cs_; }
    const std::tuple<Cs...>& parts() const noexcept { return cs_; }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id, contractor_detail::param_targets::those_having_one>(cs_, lo, hi);
    }

private:
    std::tuple<Cs...> cs_;
};

template <class... Cs>
union_of(Cs...) -> union_of<Cs...>;

namespace detail {
template <class A, class B>
concept contractor_operands = std::is_class_v<std::remove_cvref_t<A>> && std::is_class_v<std::remove_cvref_t<B>> &&
                              (tagged_contractor<A> || tagged_contractor<B>);
template <class T>
struct compose_parts {
    using type = std::tuple<T>;
    static auto get(T t) { return std::tuple<T>(std::move(t)); }
};
template <class... Cs>
struct compose_parts<compose<Cs...>> {
    using type = std::tuple<Cs...>;
    static auto get(compose<Cs...> c) { return std::move(c.parts()); }
};
}  // namespace detail

/// a then b. Sequences flatten: `a & b & c` is compose<A, B, C>.
template <class A, class B>
    requires detail::contractor_operands<A, B>
auto operator&(A a, B b) {
    return std::apply(
        [](auto&&... p) { return compose<std::remove_cvref_t<decltype(p)>...>(std::move(p)...); },
        std::tuple_cat(detail::compose_parts<A>::get(std::move(a)), detail::compose_parts<B>::get(std::move(b))));
}

/// Hull of a's and b's results.
template <class A, class B>
    requires detail::contractor_operands<A, B>
auto operator|(A a, B b) {
    return union_of<A, B>(std::move(a), std::move(b));
}

}  // namespace certipose
