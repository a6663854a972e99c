// certipose/coverage/deployment.hpp — choosing camera boxes that certify the part: the fewest
// boxes for a target share of the coverable area, or the k boxes that certify the most area
// (maximum coverage, weighted by facet area).
//
// The input is a list of candidate 6D boxes, each with its certified facet set C(B)
// (coverage/inspection.hpp); a facet counts as covered when some chosen box certifies it, so
// every claim of a plan is a certificate. The choice is greedy — the box adding the most
// uncovered area next (lazily re-evaluated, which is exact for this submodular objective), with
// the (1 − 1/e) guarantee of maximum coverage — and comes with a lower bound on the number of
// boxes any plan needs: here the area bound ⌈target / largest box area⌉ and the greedy bound
// (the guarantee read backwards), and the LP relaxation of the covering problem in
// coverage/glpk_deployment.hpp (GLPK), which also solves small instances exactly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"

namespace certipose {

/// One candidate camera box: its certified facets C(B) (indices into the facet areas).
struct deployment_candidate {
    std::vector<std::size_t> facets;
};

/// What to plan for: `cameras` boxes at most, and/or enough to certify `coverage` (a fraction
/// of the coverable area, the area of the facets some candidate certifies). Unset both: 95 %.
struct deployment_options {
    std::optional<std::size_t> cameras{};
    std::optional<double> coverage{};

    void validate() const {
        if (cameras && *cameras == 0) throw invalid_argument("cameras", "deployment: cameras must be at least 1");
        if (coverage && !(*coverage > 0.0 && *coverage <= 1.0))
            throw invalid_argument("coverage", "deployment: coverage must be in (0, 1], got " +
                                                   detail::format_double(*coverage));
    }
};

/// A plan: the chosen candidates in the order greedy took them, with the area certified after
/// each (`curve[k]`: after k + 1 boxes), the areas, and a lower bound on the boxes any plan needs
/// to certify `certified_area`.
struct deployment_plan {
    std::vector<std::size_t> chosen;
    std::vector<double> curve;
    double certified_area = 0, coverable_area = 0, total_area = 0;
    std::size_t lower_bound = 0;          ///< boxes any plan needs for `certified_area`
    std::vector<std::size_t> covered_by;  ///< per facet: index into `chosen`, or npos
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);
};

namespace detail {

/// Every candidate's facets must be increasing (each counted once) and index `areas`.
inline void check_candidates(const std::vector<deployment_candidate>& candidates, std::size_t facets) {
    for (std::size_t j = 0; j < candidates.size(); ++j) {
        const auto& fs = candidates[j].facets;
        for (std::size_t k = 0; k < fs.size(); ++k) {
            if (fs[k] >= facets) throw out_of_range("facet", fs[k], facets);
            if (k > 0 && fs[k] <= fs[k - 1])
                throw invalid_argument("candidates", "deployment: candidate " + std::to_string(j) + " lists facet " +
                                                         std::to_string(fs[k]) +
                                                         " twice or out of order (facet lists must be increasing)");
        }
    }
}

}  // namespace detail

/// The area of the facets some candidate lists, each counted once. Throws as plan_greedy does
/// for a malformed candidate.
inline double union_area(const std::vector<deployment_candidate>& candidates, const std::vector<double>& areas) {
    detail::check_candidates(candidates, areas.size());
    std::vector<char> in(areas.size(), 0);
    double a = 0;
    for (const auto& c : candidates)
        for (std::size_t f : c.facets)
            if (!in[f]) in[f] = 1, a += areas[f];
    return a;
}

/// The area bound: a plan certifying `target` needs at least ⌈target / (largest candidate area)⌉ boxes.
inline std::size_t area_lower_bound(const std::vector<deployment_candidate>& candidates, const std::vector<double>& areas,
                                    double target) {
    detail::check_candidates(candidates, areas.size());
    double largest = 0;
    for (const auto& c : candidates) {
        double a = 0;
        for (std::size_t f : c.facets) a += areas[f];
        largest = std::max(largest, a);
    }
    if (!(target > 0) || !(largest > 0)) return 0;
    return static_cast<std::size_t>(std::ceil(target / largest * (1 - 1e-12)));
}

/// The greedy bound. Greedy's first k boxes certify at least 1 − (1 − 1/k)^k of what the best k
/// boxes can (Nemhauser, Wolsey and Fisher, for this monotone submodular objective), so no k
/// boxes certify more than curve[k−1] / (1 − (1 − 1/k)^k): the fewest k for which that reaches
/// `target` is a lower bound on every plan. `curve` must be a greedy plan's (plan_greedy's
/// `curve`, the area after each box); it needs no solver, where the LP bound may be out of
/// reach for a large part. 0 for no target; curve.size() at most.
inline std::size_t greedy_lower_bound(const std::vector<double>& curve, double target) {
    if (!(target > 0)) return 0;
    for (std::size_t k = 1; k <= curve.size(); ++k) {
        const double kd = static_cast<double>(k);
        const double guarantee = 1 - std::pow(1 - 1 / kd, kd);
        // Rounding may only lower the bound: the target is shaved, the reach taken generously.
        if (curve[k - 1] / guarantee * (1 + 1e-9) >= target * (1 - 1e-9)) return k;
    }
    return curve.size();
}

/// Greedy maximum coverage (see the header comment). Throws invalid_argument for bad options or
/// a candidate whose facets are not increasing, out_of_range for a facet index beyond `areas`.
inline deployment_plan plan_greedy(const std::vector<deployment_candidate>& candidates, const std::vector<double>& areas,
                                   const deployment_options& options = {}) {
    options.validate();
    detail::check_candidates(candidates, areas.size());
    deployment_plan plan;
    for (double a : areas) plan.total_area += a;
    plan.coverable_area = union_area(candidates, areas);
    const double fraction = options.coverage ? *options.coverage : (options.cameras ? 1.0 : 0.95);
    const double target = fraction * plan.coverable_area * (1 - 1e-12);
    const std::size_t max_cameras = options.cameras ? *options.cameras : candidates.size();
    plan.covered_by.assign(areas.size(), deployment_plan::npos);
    // Lazy greedy: a candidate's gain only shrinks as others are chosen (submodularity), so a
    // stale gain is an upper bound; re-evaluate the top until it is current.
    std::priority_queue<std::pair<double, std::size_t>> heap;
    for (std::size_t j = 0; j < candidates.size(); ++j) {
        double a = 0;
        for (std::size_t f : candidates[j].facets) a += areas[f];
        if (a > 0) heap.push({a, j});
    }
    const auto gain = [&](std::size_t j) {
        double a = 0;
        for (std::size_t f : candidates[j].facets)
            if (plan.covered_by[f] == deployment_plan::npos) a += areas[f];
        return a;
    };
    while (!heap.empty() && plan.chosen.size() < max_cameras && plan.certified_area < target) {
        auto [stale, j] = heap.top();
        heap.pop();
        const double now = gain(j);
        if (now <= 0) continue;
        if (!heap.empty() && now < heap.top().first) {
            heap.push({now, j});
            continue;
        }
        for (std::size_t f : candidates[j].facets)
            if (plan.covered_by[f] == deployment_plan::npos) plan.covered_by[f] = plan.chosen.size();
        plan.chosen.push_back(j);
        plan.certified_area += now;
        plan.curve.push_back(plan.certified_area);
    }
    plan.lower_bound = std::max(area_lower_bound(candidates, areas, plan.certified_area),
                                greedy_lower_bound(plan.curve, plan.certified_area));
    return plan;
}

/// The plan made of exactly `chosen` (e.g. an exact solver's answer): the same fields as
/// plan_greedy's, with the chosen boxes in the order greedy would take them among themselves,
/// but the area bound alone as `lower_bound` (a greedy curve over a subset bounds nothing for
/// the whole candidate set).
/// Throws out_of_range for an index beyond `candidates`.
inline deployment_plan plan_of(const std::vector<deployment_candidate>& candidates, const std::vector<double>& areas,
                               const std::vector<std::size_t>& chosen) {
    detail::check_candidates(candidates, areas.size());
    std::vector<deployment_candidate> subset;
    for (std::size_t j : chosen) {
        if (j >= candidates.size()) throw out_of_range("candidate", j, candidates.size());
        subset.push_back(candidates[j]);
    }
    deployment_options all;
    all.cameras = std::max<std::size_t>(1, chosen.size());
    deployment_plan p = plan_greedy(subset, areas, all);
    for (std::size_t& j : p.chosen) j = chosen[j];
    p.coverable_area = union_area(candidates, areas);
    p.lower_bound = area_lower_bound(candidates, areas, p.certified_area);
    return p;
}

}  // namespace certipose
