// certipose/contractor/hc4.hpp — HC4: propagation of HC4Revise over a set of constraints
// (paper §5.2.1; IBEX's CtcHC4 = CtcPropag over CtcFwdBwd).
//
// API summary (namespace certipose; the interval type and dimension come from the box given to
// contract(), so one contractor object serves `interval_box<I, N>` for every backend I):
//
//   #include <certipose/contractors.hpp>          // umbrella: expressions, contractors, tests
//   using namespace certipose;
//   constexpr var<0> x; constexpr var<1> y; constexpr var<2> z;
//   auto shell = in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25);
//   hc4 c(shell /*, more constraints */);     // CTAD: hc4<Constraints...>
//   c.set_ratio(0.01);                        // relative-narrowing ratio (IBEX default 0.01)
//   c.contract(box);                          // narrows box in place; is_empty(box) if infeasible
//   eval_test t(shell);   t.test(box);        // satisfied / violated / undecided (evaluation)
//   not_in_test u(shell); u.test(box);        // + inner proof by contracting the negation
//   acid a(hc4(shell));                       // 3BCID shaving, number of shaved vars learned
//   c & a, compose(c, a), c | d, fixpoint(c, 1e-3), identity{}
//   not_in n(shell); n.contract(box);         // keeps the hull of the VIOLATING points: what it
//                                             // removes is certified inside (IBEX inner contractor)
//   set_param<0>(c, lo, hi);                  // update every param<0> in c's constraints
//
// Algorithm (AC3-like, as IBEX's CtcPropag): every constraint is queued; popping one runs
// HC4Revise on it; each of its variables narrowed by a relative amount ≥ ratio requeues the
// constraints that use that variable. A constraint is requeued after its own revision only
// when a variable occurs in it more than once: with single occurrences HC4Revise already
// reaches hull consistency (Benhamou et al. 1999; up to rounding, and up to the sin/cos
// projection, which leaves domains wider than 8 periods alone), so revisiting it gains
// nothing that matters. Skipping it is never a soundness question, only of tightness.
// The queue, the incidence masks and the node values are fixed-size arrays: no allocation.
// contract() is const and keeps no state, so one object may be shared by threads.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>

#include "certipose/detail/format.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/detail/forward_param.hpp"
#include "certipose/contractor/detail/narrowing.hpp"
#include "certipose/error.hpp"
#include "certipose/expr/constraint.hpp"
#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose {

template <Constraint... Cs>
class hc4 {
    static_assert(sizeof...(Cs) >= 1, "certipose::hc4 needs at least one constraint");
    static_assert(sizeof...(Cs) <= 255, "certipose::hc4 handles at most 255 constraints");

public:
    using certipose_contractor = void;
    static constexpr std::size_t constraint_count = sizeof...(Cs);
    static constexpr std::size_t var_bound = std::max({std::size_t{0}, Cs::var_bound...});
    /// IBEX's default propagation ratio.
    static constexpr double default_ratio = 0.01;

    explicit hc4(Cs... cs) : cs_(std::move(cs)...) {}

    /// Requeue a constraint only when a variable narrowed by at least this fraction of its
    /// width. 0 propagates every change (bounded by `max_revisions()`); must be in [0, 1).
    void set_ratio(double r) {
        if (!(r >= 0.0 && r < 1.0))
            throw invalid_argument("ratio", "hc4 ratio must be in [0, 1), got " + detail::format_double(r));
        ratio_ = r;
    }
    double ratio() const noexcept { return ratio_; }
    /// Safety bound on HC4Revise calls per contract() (a tiny ratio must not loop for long).
    static constexpr std::size_t max_revisions() noexcept { return 1000 * constraint_count; }

    template <Interval I, std::size_t N>
    void contract(interval_box<I, N>& box) const {
        static_assert(var_bound <= N, "certipose::hc4: a constraint uses a variable beyond the box");
        if constexpr (constraint_count == 1 && !(Cs::repeated && ...)) {
            revise<0>(box);  // one pass reaches hull consistency (see above); holds the rounding
        } else {
            const expr::detail::upward_scope<I> rounding;
            if (is_empty(box)) return;
            propagate(box);
        }
    }

    /// HC4Revise of the k-th constraint alone (one forward–backward pass); false and an empty
    /// box when it proves infeasibility.
    template <std::size_t K, Interval I, std::size_t N>
    bool revise(interval_box<I, N>& box) const {
        const expr::detail::upward_scope<I> rounding;
        if (is_empty(box)) return false;
        if (!std::get<K>(cs_).revise(box)) {
            set_empty(box);
            return false;
        }
        return true;
    }

    const std::tuple<Cs...>& constraints() const noexcept { return cs_; }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id>(cs_, lo, hi);
    }

    /// ACID's variable ordering heuristic (smearsumrel, Araya et al.): for each variable, the
    /// sum over constraints of |∂f/∂x_k|·w(x_k) normalised by the constraint's total. Larger
    /// means shaving that variable is more likely to pay.
    template <Interval I, std::size_t N>
    std::array<double, N> smear(const interval_box<I, N>& box) const {
        const expr::detail::upward_scope<I> rounding;
        std::array<double, N> sum{};
        std::apply(
            [&](const auto&... c) {
                (
                    [&] {
                        const auto g = c.gradient(box);
                        std::array<double, N> term{};
                        double total = 0.0;
                        for (std::size_t k = 0; k < N; ++k) {
                            if (!((c.var_mask >> k) & 1u) || is_empty(g[k])) continue;
                            double m = std::max(std::abs(lower(g[k])), std::abs(upper(g[k]))) * width(box[k]);
                            if (!(m == m)) m = 0.0;                                 // NaN (0·∞)
                            if (m > 1e300) m = 1e300;                               // keep sums finite
                            term[k] = m;
                            total += m;
                        }
                        if (total > 1e-5)
                            for (std::size_t k = 0; k < N; ++k) sum[k] += term[k] / total;
                    }(),
                    ...);
            },
            cs_);
        return sum;
    }

private:
    static constexpr std::array<std::uint64_t, constraint_count> masks{Cs::var_mask...};
    static constexpr std::array<bool, constraint_count> revisit_self{Cs::repeated...};

    template <class Box>
    bool revise_at(std::size_t c, Box& box) const {
        return [&]<std::size_t... Is>(std::index_sequence<Is...>) {
            bool ok = true;
            (void)((c == Is ? (ok = std::get<Is>(cs_).revise(box), true) : false) || ...);
            return ok;
        }(std::index_sequence_for<Cs...>{});
    }

    template <Interval I, std::size_t N>
    void propagate(interval_box<I, N>& box) const {
        constexpr std::size_t M = constraint_count;
        std::array<std::uint8_t, M> queue{};
        std::array<bool, M> queued{};
        std::size_t head = 0, count = 0;
        const auto push = [&](std::size_t c) {
            if (queued[c]) return;
            queued[c] = true;
            queue[(head + count) % M] = static_cast<std::uint8_t>(c);
            ++count;
        };
        for (std::size_t c = 0; c < M; ++c) push(c);
        std::size_t revisions = 0;
        while (count > 0 && revisions < max_revisions()) {
            const std::size_t c = queue[head];
            head = (head + 1) % M;
            --count;
            queued[c] = false;
            const auto before = box;
            ++revisions;
            if (!revise_at(c, box)) {
                set_empty(box);
                return;
            }
            for (std::size_t k = 0; k < N; ++k) {
                if (!((masks[c] >> k) & 1u)) continue;
                const double r = contractor_detail::narrowing(before[k], box[k]);
                if (r <= 0.0 || r < ratio_) continue;
                for (std::size_t j = 0; j < M; ++j)
                    if (((masks[j] >> k) & 1u) && (j != c || revisit_self[c])) push(j);
            }
        }
    }

    std::tuple<Cs...> cs_;
    double ratio_ = default_ratio;
};

template <Constraint... Cs>
hc4(Cs...) -> hc4<Cs...>;

}  // namespace certipose
