// certipose/contractor/acid.hpp — ACID: adaptive constructive interval disjunction
// (Neveu, Trombettoni, Araya; IBEX's CtcAcid over Ctc3BCid).
//
// 3BCID on one variable x: cut x's domain into `s3b` slices; contract a copy of the box with
// each slice from the left until one is not refuted, then from the right; the middle part left
// over is contracted as `scid` slices (CID), and the box becomes the hull of everything that
// survived. This removes what a propagation like HC4 cannot see, especially where variables
// occur several times (the expanded shell). ACID decides how many variables to shave per call
// — in order of decreasing smear, a first-order estimate of their impact — by learning: every
// `tuning_period` calls it spends `tuning_length` calls shaving twice as many variables and
// records how many of them still narrowed the box by more than `ct_ratio`; the average becomes
// the count used until the next tuning.
//
// Unlike IBEX the learned state (call counter, learned count, running average) is a member,
// never a static: two acid objects on two threads share nothing. An acid object itself is not
// thread safe (contract() updates it); give each thread its own copy.
//
// ACID only shaves; compose it after a propagation: `hc4(cs...) & acid(hc4(cs...))`. The inner
// contractor is any `Contractor`; when it offers `smear(box)` (hc4 does) variables are ordered
// by it, else by decreasing width.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "certipose/detail/format.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/detail/forward_param.hpp"
#include "certipose/contractor/detail/narrowing.hpp"
#include "certipose/error.hpp"
#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose {

/// ACID parameters; the defaults are IBEX's.
struct acid_options {
    int s3b = 10;                  ///< slices tried from each end when shaving a variable
    int scid = 1;                  ///< slices of the middle part contracted for the CID hull (0: none)
    double var_min_width = 1e-11;  ///< no shaving of narrower domains, and no thinner slices
    double ct_ratio = 0.002;       ///< a shaved variable "paid" if it narrowed the box by more than this on average
    int tuning_period = 1000;      ///< calls between the starts of two tuning phases
    int tuning_length = 50;        ///< calls per tuning phase
};

template <class C>
class acid {
public:
    using certipose_contractor = void;

    explicit acid(C c, acid_options options = {}) : c_(std::move(c)), opt_(options) {
        if (opt_.s3b < 2) throw invalid_argument("s3b", "acid needs s3b >= 2, got " + std::to_string(opt_.s3b));
        if (opt_.scid < 0) throw invalid_argument("scid", "acid needs scid >= 0, got " + std::to_string(opt_.scid));
        if (!(opt_.var_min_width >= 0.0))
            throw invalid_argument("var_min_width", "acid needs var_min_width >= 0, got " + certipose::detail::format_double(opt_.var_min_width));
        if (!(opt_.ct_ratio >= 0.0 && opt_.ct_ratio <= 1.0))
            throw invalid_argument("ct_ratio", "acid needs ct_ratio in [0, 1], got " + certipose::detail::format_double(opt_.ct_ratio));
        if (opt_.tuning_length < 1)
            throw invalid_argument("tuning_length", "acid needs tuning_length >= 1, got " + std::to_string(opt_.tuning_length));
        if (opt_.tuning_period < opt_.tuning_length)
            throw invalid_argument("tuning_period", "acid needs tuning_period >= tuning_length, got " +
                                                         std::to_string(opt_.tuning_period));
    }

    template <Interval I, std::size_t N>
    void contract(interval_box<I, N>& box) {
        static_assert(Contractor<C, interval_box<I, N>>, "certipose::acid: the inner contractor must model Contractor");
        const expr::detail::upward_scope<I> rounding;
        if (is_empty(box)) return;
        constexpr int n_vars = static_cast<int>(N);
        if (learned_ < 0) learned_ = (n_vars + 1) / 2;
        const int phase = static_cast<int>(calls_ % static_cast<std::size_t>(opt_.tuning_period));
        const bool tuning = phase < opt_.tuning_length;
        int handled = tuning ? std::max(2, 2 * learned_) : learned_;
        handled = std::min(handled, 5 * n_vars);

        std::array<double, 5 * N> gain{};
        if (handled > 0) {
            const auto order = variable_order(box);
            for (int v = 0; v < handled; ++v) {
                const auto before = box;
                shave(box, order[static_cast<std::size_t>(v % n_vars)]);
                if (is_empty(box)) return;  // as IBEX: an emptied box teaches nothing
                if (tuning) {
                    double g = 0.0;
                    for (std::size_t i = 0; i < N; ++i) g += contractor_detail::narrowing(before[i], box[i]);
                    gain[static_cast<std::size_t>(v)] = g / n_vars;
                }
            }
        }
        ++calls_;
        if (tuning) {
            int paid = 0;
            for (int v = handled - 1; v >= 0; --v)
                if (gain[static_cast<std::size_t>(v)] > opt_.ct_ratio) {
                    paid = v + 1;
                    break;
                }
            average_ = (average_ * phase + paid) / (phase + 1);
            if (phase + 1 == opt_.tuning_length) learned_ = static_cast<int>(average_ + 0.5);
        }
    }

    /// Variables shaved per call outside tuning phases (−1 before the first call).
    int learned_var_count() const noexcept { return learned_; }
    std::size_t calls() const noexcept { return calls_; }
    const acid_options& options() const noexcept { return opt_; }
    C& inner() noexcept { return c_; }
    const C& inner() const noexcept { return c_; }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id, contractor_detail::param_targets::those_having_one>(c_, lo, hi);
    }

private:
    template <Interval I, std::size_t N>
    std::array<std::size_t, N> variable_order(const interval_box<I, N>& box) const {
        std::array<double, N> score{};
        if constexpr (requires { c_.smear(box); }) {
            score = c_.smear(box);
        } else {
            for (std::size_t i = 0; i < N; ++i) score[i] = width(box[i]);
        }
        std::array<std::size_t, N> order{};
        for (std::size_t i = 0; i < N; ++i) order[i] = i;
        // Insertion sort, stable and allocation-free (std::stable_sort takes a heap buffer).
        for (std::size_t i = 1; i < N; ++i)
            for (std::size_t j = i; j > 0 && score[order[j]] > score[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
        return order;
    }

    // Slice k of [l, u] cut in n: consecutive slices share a bound computed by the same
    // expression, so together they cover [l, u] whatever the rounding.
    static double cut(double l, double u, double w, int k, int n) {
        if (k <= 0) return l;
        if (k >= n) return u;
        return std::min(u, l + k * w);
    }

    // 3BCID on one variable (the slices variant of IBEX's var3BCID; with s3b ≤ 16, IBEX's
    // default, that is the variant IBEX runs too).
    template <Interval I, std::size_t N>
    void shave(interval_box<I, N>& box, std::size_t var) {
        const double l = lower(box[var]), u = upper(box[var]);
        const double w = u - l;
        if (!std::isfinite(w) || w < opt_.var_min_width || w <= 0.0) return;
        int n = opt_.s3b;
        double slice = w / n;
        if (slice < opt_.var_min_width) {
            n = std::max(2, static_cast<int>(w / opt_.var_min_width));
            slice = w / n;
        }
        const interval_box<I, N> saved = box;
        const auto try_slice = [&](double lo, double hi) {
            interval_box<I, N> b = saved;
            b[var] = I(lo, hi);
            c_.contract(b);
            return b;
        };

        interval_box<I, N> left;
        int k_left = 0;
        for (; k_left < n; ++k_left) {
            left = try_slice(cut(l, u, slice, k_left, n), cut(l, u, slice, k_left + 1, n));
            if (!is_empty(left)) break;
        }
        if (k_left == n) {
            set_empty(box);
            return;
        }
        if (k_left == n - 1) {
            box = left;
            return;
        }
        interval_box<I, N> right;
        int k_right = n - 1;
        for (; k_right > k_left; --k_right) {
            right = try_slice(cut(l, u, slice, k_right, n), cut(l, u, slice, k_right + 1, n));
            if (!is_empty(right)) break;
        }
        if (k_right == k_left) {
            box = left;
            return;
        }
        interval_box<I, N> result = hull(left, right);
        if (k_right > k_left + 1) {
            // The middle part [cl, cu], never refuted slice by slice: CID over scid slices, or
            // just kept whole (the 3B result) when scid is 0 or CID stops paying.
            const double cl = cut(l, u, slice, k_left + 1, n), cu = cut(l, u, slice, k_right, n);
            bool useful = opt_.scid > 0;
            const double cw = useful ? (cu - cl) / opt_.scid : 0.0;
            for (int j = 0; useful && j < opt_.scid; ++j) {
                result = hull(result, try_slice(cut(cl, cu, cw, j, opt_.scid), cut(cl, cu, cw, j + 1, opt_.scid)));
                useful = !same_except(var, result, saved);
            }
            if (!useful) {
                result = saved;
                result[var] = I(lower(left[var]), upper(right[var]));
            }
        }
        box = result;
    }

    template <Interval I, std::size_t N>
    static bool same_except(std::size_t var, const interval_box<I, N>& a, const interval_box<I, N>& b) {
        for (std::size_t i = 0; i < N; ++i)
            if (i != var && !(a[i] == b[i])) return false;
        return true;
    }

    C c_;
    acid_options opt_;
    std::size_t calls_ = 0;
    int learned_ = -1;
    double average_ = 0.0;
};

template <class C>
acid(C) -> acid<C>;
template <class C>
acid(C, acid_options) -> acid<C>;

}  // namespace certipose
