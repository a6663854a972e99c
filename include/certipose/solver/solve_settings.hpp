// certipose/solver/solve_settings.hpp — the facet solver's options as a person writes them: plain
// numbers and switches, turned into `solve_options` in one place.
//
// The programs' flags (--position-eps, --time-limit SECONDS, --paper-paving, --corner-depth, ...)
// and the Python module's keywords (position_eps=, time_limit=, paper_paving=, ...) say the same
// things in the same units: seconds as numbers, the paving as a switch with carving's two tuning
// numbers. `to_solve_options` is the one translation, so that a flag means the same on every
// front end, and each mistake is an invalid_argument naming the setting as written here
// ("time_limit", "corner_depth"): a front end turns that name into its own spelling.
#pragma once

#include <chrono>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/solver/paving.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

/// The facet solver's options in the units a person gives them (see the header comment).
struct solve_settings {
    double position_eps = 0.1;              ///< ε_p, metres
    double orientation_eps = 0.38;          ///< ε_o, radians
    std::optional<std::size_t> max_boxes;   ///< box budget (unset: solve_options' default)
    std::optional<double> time_limit;       ///< wall-time budget, seconds
    bool paper_paving = false;              ///< the paper's paving instead of carving
    std::optional<std::size_t> corner_depth;  ///< carving::corner_depth (default paving only)
    std::optional<double> corner_rest;        ///< carving::rest_min_pieces (default paving only)
    std::optional<double> refine;           ///< anytime refinement below ε_p, seconds
    bool grow = false;                      ///< widen the VALID boxes (growth_options{})
};

/// A setting of `s` seconds as a steady_clock duration (a budget, a time limit);
/// invalid_argument(field) unless it is positive and finite.
inline std::chrono::steady_clock::duration seconds_setting(double s, const char* field) {
    if (!(s > 0.0) || !std::isfinite(s))
        throw invalid_argument(field, std::string(field) + " must be a positive finite number of seconds, got " +
                                          detail::format_double(s));
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

/// The solve_options the settings say, validated (invalid_argument naming the setting). The
/// callbacks and the stop token are the caller's to set.
inline solve_options to_solve_options(const solve_settings& s) {
    solve_options o;
    o.position_eps = s.position_eps;
    o.orientation_eps = s.orientation_eps;
    if (s.max_boxes) o.max_boxes = *s.max_boxes;  // 0: solve_options::validate names it
    if (s.time_limit) o.time_limit = seconds_setting(*s.time_limit, "time_limit");
    if (s.paper_paving) {
        // A tuning of carving that would be ignored is a mistake worth naming.
        if (s.corner_depth || s.corner_rest)
            throw invalid_argument(s.corner_depth ? "corner_depth" : "corner_rest",
                                   std::string(s.corner_depth ? "corner_depth" : "corner_rest") +
                                       " tunes the default paving; paper_paving has no corner boxes");
        o.paving = paper_paving{};
    } else {
        carving c;
        if (s.corner_depth) c.corner_depth = *s.corner_depth;
        if (s.corner_rest) c.rest_min_pieces = *s.corner_rest;
        o.paving = c;
    }
    if (s.refine) o.refine = refinement{.time_limit = seconds_setting(*s.refine, "refine")};
    if (s.grow) o.grow = growth_options{};
    try {
        o.validate();
    } catch (const invalid_argument& e) {  // "paving.corner_depth": name the setting as written here
        const std::string field = e.field() == "paving.corner_depth"       ? "corner_depth"
                                  : e.field() == "paving.rest_min_pieces" ? "corner_rest"
                                                                           : e.field();
        throw invalid_argument(field, e.what());
    }
    return o;
}

}  // namespace certipose
