// certipose/constraints/paper_position_constraints.hpp — the paper's position constraints for
// one facet (§6.2; constraints 1–4 of docs/conventions.md), as a contractor and a box test.
//
// For every p in the box and every point q of the facet:
//   C_f       the box does not meet the facet,
//   focus     d_min ≤ ‖p − q‖ ≤ d_max      (max over q at a vertex; min = box–triangle distance),
//   backface  (p − v1)·n > 0,
//   view      (p − c)·n ≥ sin θ_v ‖p − c‖  (the angle to the normal is at most π/2 − θ_v).
// Soundness to the last rounding error: the facet's normal and centroid are not doubles, so
// they enter as interval parameters enclosing the exact N = (v2 − v1) × (v3 − v1) and
// c = (v1 + v2 + v3)/3 (the view constraint is scale-free in n, so the unnormalised N is used
// with sin θ_v·‖N‖). Squared distance bounds are rounded outward for the contractor (it must
// never drop a valid position) and inward for the test (it must never certify an invalid one).
// The minimum distance is not polynomial: the contractor uses its consequences
// ‖p − v_i‖, ‖p − c‖ ≥ d_min, the test a certified box–triangle distance bound.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>
#include <utility>

#include <Eigen/Dense>

#include "certipose/detail/format.hpp"
#include "certipose/constraints/box_triangle_distance.hpp"
#include "certipose/constraints/concept.hpp"
#include "certipose/contractor/hc4.hpp"
#include "certipose/contractor/not_in.hpp"
#include "certipose/expr/constraint.hpp"
#include "certipose/expr/vector.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

namespace detail {

/// Interval enclosures of the facet's exact normal direction, centroid, and the distance
/// bounds, computed once per facet.
template <Interval I>
struct facet_enclosures {
    std::array<I, 3> N;     ///< (v2 − v1) × (v3 − v1), not normalised
    std::array<I, 3> c;     ///< centroid
    I sin_view_norm;        ///< sin θ_v · ‖N‖
    double dmin2_lo, dmin2_hi, dmax2_lo, dmax2_hi;
    double near2_hi;        ///< (d_min + r_f)² rounded up, r_f ≥ the facet's radius about c

    facet_enclosures(const facet& f, distance_range r, double min_view_angle) {
        const rounding_guard<I> rounding;
        std::array<std::array<I, 3>, 3> v;
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) v[i][k] = I(f.v[i][k]);
        const std::array<I, 3> e1{v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
        const std::array<I, 3> e2{v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
        N = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; ++k) c[k] = (v[0][k] + v[1][k] + v[2][k]) / I(3.0);
        sin_view_norm = sin(I(min_view_angle)) * sqrt(sqr(N[0]) + sqr(N[1]) + sqr(N[2]));
        const I dmin2 = sqr(I(r.min)), dmax2 = sqr(I(r.max));
        dmin2_lo = lower(dmin2), dmin2_hi = upper(dmin2);
        dmax2_lo = lower(dmax2), dmax2_hi = upper(dmax2);
        double radius = 0.0;
        for (int i = 0; i < 3; ++i)
            radius = std::max(radius, upper(sqrt(sqr(v[i][0] - c[0]) + sqr(v[i][1] - c[1]) + sqr(v[i][2] - c[2]))));
        near2_hi = upper(sqr(I(r.min) + I(radius)));
    }
};

/// Calls `build(dist2, pc, backface, view)` with what both expressions below share: ‖p − v‖² of a
/// vertex v, p − c, and the closures of the backface and viewing-angle constraints (parameters
/// 0–5 hold N and c, 6 sin θ_v · ‖N‖).
template <Interval I, class Build>
auto with_position_terms(const facet& f, const facet_enclosures<I>& e, Build&& build) {
    constexpr var<0> x;
    constexpr var<1> y;
    constexpr var<2> z;
    const auto dist2 = [&](const Eigen::Vector3d& v) { return sqr(x - v.x()) + sqr(y - v.y()) + sqr(z - v.z()); };
    const auto N = vec(param<0>(e.N[0]), param<1>(e.N[1]), param<2>(e.N[2]));
    const auto C = vec(param<3>(e.c[0]), param<4>(e.c[1]), param<5>(e.c[2]));
    const auto P = vec(x, y, z);
    const auto V1 = vec(f.v[0].x(), f.v[0].y(), f.v[0].z());
    const auto PC = P - C;
    return build(dist2, PC, dot(P - V1, N) >= 0.0,                                   // backface (closure)
                 dot(PC, N) - param<6>(e.sin_view_norm) * sqrt(sqr_norm(PC)) >= 0.0);  // view angle
}

/// The contractor of the set: HC4 over the polynomial constraints (outer constants).
template <Interval I>
auto make_position_hc4(const facet& f, const facet_enclosures<I>& e) {
    return with_position_terms(f, e, [&](const auto& dist2, const auto& PC, const auto& backface, const auto& view) {
        return hc4(dist2(f.v[0]) <= e.dmax2_hi, dist2(f.v[1]) <= e.dmax2_hi, dist2(f.v[2]) <= e.dmax2_hi,
                   dist2(f.v[0]) >= e.dmin2_lo, dist2(f.v[1]) >= e.dmin2_lo, dist2(f.v[2]) >= e.dmin2_lo,
                   sqr_norm(PC) >= e.dmin2_lo,  // q = c
                   backface, view);
    });
}

/// Sufficient conditions of constraints 1–4, whose negation `contract_complement` contracts
/// (not_in keeps the hull of the points violating one of them):
///   ‖p − v_i‖² ≤ d_max² rounded down                                   ⇒ focus, far side
///   ‖p − c‖ ≥ d_min + r_f, r_f ≥ max_i ‖v_i − c‖ (squared, rounded up)
///       ⇒ ‖p − q‖ ≥ ‖p − c‖ − ‖q − c‖ ≥ d_min for every q of the facet (focus, near side; C_f
///         too when d_min > 0, and when d_min = 0 the points of the facet fail the backface
///         closure below)
///   (p − v1)·N ≥ 0 and the view cone, the closures of constraints 3 and 4.
/// The near side is the only approximation: it gives away a shell of width ≤ r_f, the facet's
/// radius, which is small beside d_min for the facets of a part.
template <Interval I>
auto make_position_complement(const facet& f, const facet_enclosures<I>& e) {
    return with_position_terms(f, e, [&](const auto& dist2, const auto& PC, const auto& backface, const auto& view) {
        return not_in(dist2(f.v[0]) <= e.dmax2_lo, dist2(f.v[1]) <= e.dmax2_lo, dist2(f.v[2]) <= e.dmax2_lo,
                      sqr_norm(PC) >= e.near2_hi,  // ‖p − c‖ ≥ d_min + r_f
                      backface, view);
    });
}

}  // namespace detail

/// The paper's position constraint set C_p for one facet (§6.2). Models PositionConstraintSet.
template <Interval I>
class paper_position_constraints {
public:
    explicit paper_position_constraints(const position_problem& problem)
        : f_(validated(problem).facet),
          range_(problem.range),
          enc_(problem.facet, problem.range, problem.task.min_view_angle),
          hc4_(detail::make_position_hc4<I>(problem.facet, enc_)),
          complement_(detail::make_position_complement<I>(problem.facet, enc_)) {}

    /// HC4 over the polynomial constraints; empties the box when no position can satisfy them.
    void contract(position_box<I>& box) { hc4_.contract(box); }

    /// Narrows `box` to the hull of its positions that may violate one of constraints 1–4
    /// (ComplementContractingSet): every position removed satisfies all four.
    void contract_complement(position_box<I>& box) const { complement_.contract(box); }

    /// satisfied: every position of the box meets constraints 1–4 for every point of the facet;
    /// violated: none does; otherwise undecided.
    verdict test(const position_box<I>& b) const { return assess(b).v; }

    /// The first constraint that cannot be certified on `b`; nothing when `test` is satisfied.
    /// (A box the test calls violated gives boundary_reason::constraint.)
    std::optional<boundary_reason> undecided(const position_box<I>& b) const {
        const outcome o = assess(b);
        if (o.v == verdict::satisfied) return std::nullopt;
        return o.why;
    }

    /// The paper's initial search space (Algorithm 3 line 4): the facet's bounding box grown by
    /// d_max in every direction, contracted by this set.
    position_box<I> initial_box() {
        position_box<I> b;
        {
            const rounding_guard<I> rounding;
            for (int k = 0; k < 3; ++k)
                b[k] = I(lower(I(f_.bbox.min()[k]) - I(range_.max)), upper(I(f_.bbox.max()[k]) + I(range_.max)));
        }
        contract(b);
        return b;
    }

    const facet& facet_of_interest() const noexcept { return f_; }
    distance_range range() const noexcept { return range_; }

private:
    struct outcome {
        verdict v;
        boundary_reason why;  // meaningful when v is undecided
    };

    outcome assess(const position_box<I>& b) const {
        constexpr auto undecided_by = [](boundary_reason r) { return outcome{verdict::undecided, r}; };
        if (is_empty(b)) return {verdict::violated, boundary_reason::constraint};
        const rounding_guard<I> rounding;
        const std::array<I, 3> pv1{b[0] - f_.v[0].x(), b[1] - f_.v[0].y(), b[2] - f_.v[0].z()};
        const I back = pv1[0] * enc_.N[0] + pv1[1] * enc_.N[1] + pv1[2] * enc_.N[2];
        const std::array<I, 3> pc{b[0] - enc_.c[0], b[1] - enc_.c[1], b[2] - enc_.c[2]};
        const I pc_dot_n = pc[0] * enc_.N[0] + pc[1] * enc_.N[1] + pc[2] * enc_.N[2];
        const I pc_norm2 = sqr(pc[0]) + sqr(pc[1]) + sqr(pc[2]);
        const I view = pc_dot_n - enc_.sin_view_norm * sqrt(pc_norm2);
        std::array<I, 3> d2;
        for (int i = 0; i < 3; ++i)
            d2[i] = sqr(b[0] - f_.v[i].x()) + sqr(b[1] - f_.v[i].y()) + sqr(b[2] - f_.v[i].z());

        // Violated everywhere: one constraint is certainly false on the whole box.
        constexpr outcome violated{verdict::violated, boundary_reason::constraint};
        if (!(upper(back) > 0.0) || upper(view) < 0.0) return violated;
        for (const I& d : d2)
            if (lower(d) > enc_.dmax2_hi || upper(d) < enc_.dmin2_lo) return violated;
        if (upper(pc_norm2) < enc_.dmin2_lo) return violated;

        // Satisfied everywhere: each constraint certainly true on the whole box.
        if (!(lower(back) > 0.0)) return undecided_by(boundary_reason::backface);
        if (!(lower(view) >= 0.0)) return undecided_by(boundary_reason::view_angle);
        for (const I& d : d2)
            if (!(upper(d) <= enc_.dmax2_lo)) return undecided_by(boundary_reason::distance);
        const double near = box_triangle_distance_lower(b, f_.v, f_.normal, range_.min);  // compared with d_min only
        if (!(near > 0.0)) return undecided_by(boundary_reason::facet_contact);  // C_f
        if (!(near >= range_.min)) return undecided_by(boundary_reason::distance);
        return {verdict::satisfied, boundary_reason::constraint};
    }

    // Runs before any member is built from the problem, so bad input fails with its own name.
    static const position_problem& validated(const position_problem& problem) {
        problem.task.validate();
        const distance_range r = problem.range;
        if (!(r.min >= 0.0) || !(r.max > r.min) || !std::isfinite(r.max))
            throw invalid_argument("distance_range", "paper_position_constraints: need 0 <= d_min < d_max < inf, got [" +
                                                         detail::format_double(r.min) + ", " + detail::format_double(r.max) + "]");
        return problem;
    }

    facet f_;
    distance_range range_;
    detail::facet_enclosures<I> enc_;
    decltype(detail::make_position_hc4<I>(std::declval<const facet&>(),
                                          std::declval<const detail::facet_enclosures<I>&>())) hc4_;
    decltype(detail::make_position_complement<I>(std::declval<const facet&>(),
                                                 std::declval<const detail::facet_enclosures<I>&>())) complement_;
};

/// Several constraint sets at once (all must hold): contracts with each in turn; satisfied when
/// all are, violated when one is. Each is built from the same position_problem and its own
/// parameters: `all_of<A, B>::parameters` holds A's and B's (`no_parameters` for a set that
/// declares none), in order, e.g. `{{}, keep_in_sphere<I>::parameters{.centre = c, .radius = r}}`.
template <ConstructibleConstraintSet... Sets>
class all_of {
public:
    /// The member sets' parameters, in order (a struct rather than a std::tuple: braced lists
    /// like `{{}, sphere}` convert to it without ambiguity).
    struct parameters {
        std::tuple<constraint_parameters_t<Sets>...> each{};

        parameters() = default;
        parameters(constraint_parameters_t<Sets>... p) : each(std::move(p)...) {}  // NOLINT(implicit)

        template <std::size_t K>
        const auto& get() const noexcept { return std::get<K>(each); }
        friend bool operator==(const parameters&, const parameters&) = default;
    };

    explicit all_of(const position_problem& problem, const parameters& p = {})
        : all_of(problem, p, std::index_sequence_for<Sets...>{}) {}

    template <class Box>
    void contract(Box& box) {
        std::apply([&](auto&... s) { ((is_empty(box) ? void() : s.contract(box)), ...); }, sets_);
    }
    /// The hull of the members' complement contractions (a position violating the conjunction
    /// violates some member); only when every member can contract its complement.
    template <class Box>
        requires(ComplementContractingSet<Sets, typename Box::interval_type> && ...)
    void contract_complement(Box& box) {
        if (is_empty(box)) return;
        Box result = Box::empty();
        std::apply([&](auto&... s) {
            ((void)[&] {
                Box b = box;
                s.contract_complement(b);
                result = hull(result, b);
            }(), ...);
        }, sets_);
        box = result;
    }

    template <class Box>
    verdict test(const Box& box) {
        verdict r = verdict::satisfied;
        std::apply(
            [&](auto&... s) {
                ((r == verdict::violated ? void() : [&] {
                     const verdict v = s.test(box);
                     if (v == verdict::violated) r = verdict::violated;
                     else if (v == verdict::undecided) r = verdict::undecided;
                 }()),
                 ...);
            },
            sets_);
        return r;
    }
    /// The reason of the first member set that does not certify `box`; nothing if all do.
    template <class Box>
    std::optional<boundary_reason> undecided(const Box& box) {
        using I = typename Box::interval_type;
        std::optional<boundary_reason> r;
        std::apply([&](auto&... s) { ((r ? void() : void(r = undecided_constraint<I>(s, box))), ...); }, sets_);
        return r;
    }
    /// The first set's initial box (the paper's set knows the facet), contracted by all sets.
    template <class Box = decltype(std::declval<std::tuple_element_t<0, std::tuple<Sets...>>&>().initial_box())>
    Box initial_box() {
        Box b = std::get<0>(sets_).initial_box();
        contract(b);
        return b;
    }
    template <std::size_t K>
    auto& get() noexcept { return std::get<K>(sets_); }

private:
    template <std::size_t... Is>
    all_of(const position_problem& problem, const parameters& p, std::index_sequence<Is...>)
        : sets_(make_constraint_set<Sets>(problem, std::get<Is>(p.each))...) {}

    std::tuple<Sets...> sets_;
};

}  // namespace certipose
