// certipose/coverage/glpk_deployment.hpp — the covering problem of coverage/deployment.hpp as an
// integer program, solved with GLPK (Debian libglpk-dev; link -lglpk): the LP relaxation's
// optimum, rounded up, is a lower bound on the number of camera boxes any plan needs for a
// target area, and for small instances the program itself is solved exactly.
//
//   minimise Σ_j x_j   over candidates j (x_j ∈ {0, 1}; in [0, 1] for the relaxation)
//   s.t.     Σ_i a_i y_i ≥ target           (y_i ∈ [0, 1]: facet i counts as certified)
//            y_i ≤ Σ_{j : i ∈ C(B_j)} x_j    (only if a chosen box certifies it)
// where facets certified by the same candidates share one y (weighted by their summed area).
//
// On a large part the classes number tens of thousands and the simplex runs for minutes. The
// bound then solves a relaxation (lp_relaxation): the smallest classes are left out and the
// target is lowered by their area. Every plan's (x, y) restricted to the classes kept is
// feasible for it (Σ_kept a y ≥ target − Σ_left-out a y ≥ target − left-out area), so its
// optimum is still a lower bound, and leaving out a sliver of the area removes most rows.
#pragma once

#include <glpk.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <memory>
#include <optional>
#include <vector>

#include "certipose/coverage/deployment.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"

namespace certipose {

/// Which facet classes the LP bound may leave out (see the header comment): the smallest, while
/// more than `max_classes` remain, and never more than `max_left_out` of the target area in all.
/// {max_left_out = 0}: the whole program (classes of zero area aside, which change nothing).
struct lp_relaxation {
    std::size_t max_classes = 4096;
    double max_left_out = 0.01;  ///< share of the target, in [0, 1)

    /// Throws invalid_argument naming the field for an impossible value.
    void validate() const {
        if (max_classes < 1) throw invalid_argument("max_classes", "lp_relaxation: max_classes must be at least 1");
        if (!(max_left_out >= 0.0 && max_left_out < 1.0))
            throw invalid_argument("max_left_out", "lp_relaxation: max_left_out must be a share in [0, 1), got " +
                                                       detail::format_double(max_left_out));
    }
};

/// The options of lp_lower_bound.
struct lp_bound_options {
    /// GLPK's simplex stops here, and then nothing is claimed; none: no limit.
    std::optional<std::chrono::milliseconds> time_limit{};
    lp_relaxation relaxation{};
};

namespace detail {

struct glp_deleter {
    void operator()(glp_prob* p) const noexcept { glp_delete_prob(p); }
};

/// The covering program for `target` (see the header comment); columns 1..n are the candidates.
/// With `relaxation`, its smallest classes are left out and the target lowered by their area.
/// Throws for malformed candidates (GLPK would abort() on a repeated facet). Needs a candidate.
inline std::unique_ptr<glp_prob, glp_deleter> covering_program(const std::vector<deployment_candidate>& candidates,
                                                               const std::vector<double>& areas, double target,
                                                               const std::optional<lp_relaxation>& relaxation = {}) {
    check_candidates(candidates, areas.size());
    // A negative area would raise the relaxed target (and NaN breaks the ordering below).
    for (std::size_t f = 0; f < areas.size(); ++f)
        if (!(areas[f] >= 0.0) || !std::isfinite(areas[f]))
            throw invalid_argument("areas", "deployment: facet " + std::to_string(f) + " has area " +
                                                detail::format_double(areas[f]) + "; areas must be finite and >= 0");
    glp_term_out(GLP_OFF);
    std::unique_ptr<glp_prob, glp_deleter> lp(glp_create_prob());
    glp_set_obj_dir(lp.get(), GLP_MIN);
    // Facets certified by the same candidates are interchangeable here: one y column and row per
    // such class, weighted by the class's area, has the same optimum (the area-weighted mean of
    // a solution's y over a class is feasible for the class's y, and back) with far fewer rows,
    // as the neighbouring facets of a finely tessellated surface are mostly certified by the
    // same boxes.
    std::vector<std::vector<int>> by_facet(areas.size());  // the columns certifying each facet
    for (std::size_t j = 0; j < candidates.size(); ++j)
        for (std::size_t f : candidates[j].facets) by_facet[f].push_back(static_cast<int>(j) + 1);
    std::vector<std::size_t> order;
    for (std::size_t f = 0; f < areas.size(); ++f)
        if (!by_facet[f].empty()) order.push_back(f);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return by_facet[a] < by_facet[b]; });
    std::vector<const std::vector<int>*> class_columns;
    std::vector<double> class_area;
    for (std::size_t k = 0; k < order.size(); ++k) {
        if (k == 0 || by_facet[order[k]] != by_facet[order[k - 1]]) {
            class_columns.push_back(&by_facet[order[k]]);
            class_area.push_back(0.0);
        }
        class_area.back() += areas[order[k]];
    }
    if (relaxation && class_columns.size() > relaxation->max_classes) {
        // Leave out the smallest classes (ties: the later in the order above, so the same
        // instance always gives the same program) while the budget allows.
        std::vector<std::size_t> by_area(class_columns.size());
        for (std::size_t c = 0; c < by_area.size(); ++c) by_area[c] = c;
        std::stable_sort(by_area.begin(), by_area.end(), [&](std::size_t a, std::size_t b) { return class_area[a] > class_area[b]; });
        const double budget = relaxation->max_left_out * target;
        double left_out = 0;
        std::size_t keep = by_area.size();
        while (keep > relaxation->max_classes && left_out + class_area[by_area[keep - 1]] <= budget)
            left_out += class_area[by_area[--keep]];
        std::vector<char> kept(class_columns.size(), 0);
        for (std::size_t k = 0; k < keep; ++k) kept[by_area[k]] = 1;
        std::vector<const std::vector<int>*> columns;
        std::vector<double> area;
        for (std::size_t c = 0; c < kept.size(); ++c)
            if (kept[c]) columns.push_back(class_columns[c]), area.push_back(class_area[c]);
        class_columns = std::move(columns), class_area = std::move(area);
        // Lowered a little more than the sum, and the difference rounded down: rounding must not
        // make the bound claim more.
        target = std::nextafter(target - left_out * (1 + 1e-9), -std::numeric_limits<double>::infinity());
    }
    const int n = static_cast<int>(candidates.size()), classes = static_cast<int>(class_columns.size());
    const int rows = 1 + classes;
    glp_add_rows(lp.get(), rows);
    glp_add_cols(lp.get(), n + classes);
    glp_set_row_bnds(lp.get(), 1, GLP_LO, target, 0.0);
    for (int r = 2; r <= rows; ++r) glp_set_row_bnds(lp.get(), r, GLP_UP, 0.0, 0.0);
    for (int j = 1; j <= n + classes; ++j) {
        glp_set_col_bnds(lp.get(), j, GLP_DB, 0.0, 1.0);
        glp_set_obj_coef(lp.get(), j, j <= n ? 1.0 : 0.0);
    }
    std::vector<int> ia{0}, ja{0};
    std::vector<double> ar{0.0};
    for (int c = 0; c < classes; ++c) {
        const int y = n + c + 1, row = c + 2;
        ia.push_back(1), ja.push_back(y), ar.push_back(class_area[static_cast<std::size_t>(c)]);  // Σ a y ≥ target
        ia.push_back(row), ja.push_back(y), ar.push_back(1.0);                                     // y − Σ x_j ≤ 0
        for (int j : *class_columns[static_cast<std::size_t>(c)]) ia.push_back(row), ja.push_back(j), ar.push_back(-1.0);
    }
    glp_load_matrix(lp.get(), static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());
    return lp;
}

}  // namespace detail

/// ⌈optimum of the LP relaxation⌉ (of the program `options.relaxation` leaves, see the header
/// comment): no plan certifies `target` m² with fewer boxes. 0 when the LP could not be solved,
/// or not within `options.time_limit` (then nothing is claimed): the simplex grows with the
/// candidates and the facet classes, and a large part has many of both. Throws
/// invalid_argument for bad options.
inline std::size_t lp_lower_bound(const std::vector<deployment_candidate>& candidates, const std::vector<double>& areas,
                                  double target, const lp_bound_options& options = {}) {
    options.relaxation.validate();
    if (!(target > 0) || candidates.empty()) {
        detail::check_candidates(candidates, areas.size());
        return 0;
    }
    auto lp = detail::covering_program(candidates, areas, target, options.relaxation);
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    parm.presolve = GLP_ON;
    if (options.time_limit) parm.tm_lim = static_cast<int>(std::clamp<long long>(options.time_limit->count(), 1, 1 << 30));
    if (glp_simplex(lp.get(), &parm) != 0 || glp_get_status(lp.get()) != GLP_OPT) return 0;
    // A little below the optimum before rounding up: the simplex's own tolerance must not add a box.
    return static_cast<std::size_t>(std::ceil(glp_get_obj_val(lp.get()) - 1e-6));
}

/// The fewest candidates certifying `target` m², if GLPK proves it within `time_limit`
/// (branch and bound); nothing otherwise.
inline std::optional<std::vector<std::size_t>> plan_exact(const std::vector<deployment_candidate>& candidates,
                                                          const std::vector<double>& areas, double target,
                                                          std::chrono::milliseconds time_limit) {
    if (candidates.empty()) {
        detail::check_candidates(candidates, areas.size());
        if (target > 0) return std::nullopt;
        return std::vector<std::size_t>{};
    }
    auto lp = detail::covering_program(candidates, areas, target);
    for (int j = 1; j <= static_cast<int>(candidates.size()); ++j) glp_set_col_kind(lp.get(), j, GLP_BV);
    glp_iocp parm;
    glp_init_iocp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    parm.presolve = GLP_ON;
    parm.tm_lim = static_cast<int>(std::min<long long>(time_limit.count(), 1 << 30));
    if (glp_intopt(lp.get(), &parm) != 0 || glp_mip_status(lp.get()) != GLP_OPT) return std::nullopt;
    std::vector<std::size_t> chosen;
    for (int j = 1; j <= static_cast<int>(candidates.size()); ++j)
        if (glp_mip_col_val(lp.get(), j) > 0.5) chosen.push_back(static_cast<std::size_t>(j - 1));
    return chosen;
}

}  // namespace certipose
