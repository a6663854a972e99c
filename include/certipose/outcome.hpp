// certipose/outcome.hpp — the words every layer reports outcomes with: a box test's `verdict`,
// the paver's `box_class` and `termination`, and the `boundary_reason` a BOUNDARY box was left
// undecided for, with their names (`to_string`).
//
// Below the contractors, the paver and the constraint sets: every layer reports with these words
// (expressions, contractors, pavers, constraint sets, the solver, the whole-part run, the
// writers), so naming one never pulls in the layer that first produced it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace certipose {

/// Three-valued answer of a box test over *every* point of the box.
enum class verdict {
    satisfied,  ///< every point of the box satisfies the constraints (certified)
    violated,   ///< no point of the box satisfies them (certified)
    undecided   ///< neither could be proven
};

/// What the paver made of a box (the classes of Algorithm 1, plus the two states of a tree
/// node that is not a leaf of the final paving).
enum class box_class : std::uint8_t {
    valid,      ///< every point satisfies the constraints (certified by the inner test)
    boundary,   ///< undecided and narrower than the bisector's precision
    discarded,  ///< certified to hold no solution (contracted to empty, or the test violated)
    bisected,   ///< split into two children (tree nodes only)
    pending     ///< not classified because the run stopped early
};

/// Why a run ended.
enum class termination : std::uint8_t {
    completed,   ///< the list of unclassified boxes ran empty
    box_budget,  ///< `max_boxes` boxes were processed
    deadline,    ///< the time limit or deadline passed
    cancelled    ///< the stop token was triggered or the progress callback returned false
};

inline const char* to_string(box_class c) noexcept {
    switch (c) {
        case box_class::valid: return "valid";
        case box_class::boundary: return "boundary";
        case box_class::discarded: return "discarded";
        case box_class::bisected: return "bisected";
        case box_class::pending: return "pending";
    }
    return "?";
}

inline const char* to_string(termination t) noexcept {
    switch (t) {
        case termination::completed: return "completed";
        case termination::box_budget: return "box_budget";
        case termination::deadline: return "deadline";
        case termination::cancelled: return "cancelled";
    }
    return "?";
}

/// Why a BOUNDARY box was left undecided: a constraint (docs/conventions.md) that could be proven
/// neither true nor false over the whole box — the first one the set checks that way (the
/// paper's set: backface, viewing angle, d_max, facet contact, d_min) — or the budget that ended
/// the run first, or (after the solve) the surface of a camera region or the part's placement
/// tolerance.
enum class boundary_reason : std::uint8_t {
    facet_contact,  ///< constraint 1: the box may touch the facet
    distance,       ///< constraint 2: d_min ≤ ‖p − q‖ ≤ d_max undecided (focus, resolution)
    backface,       ///< constraint 3: the box may reach the facet's plane
    view_angle,     ///< constraint 4: the viewing angle to the normal is undecided
    constraint,     ///< a user constraint set (one that does not say which of its constraints)
    occlusion,      ///< constraint 6: some sight lines blocked, some free (occlusion PARTIAL)
    field_of_view,  ///< constraint 5: no orientation box certified, even at ε_p
    budget,         ///< not decided: a box budget, deadline or cancellation ended the run
    /// a piece of a VALID box straddling a keep-in or keep-out region's surface at the regions'
    /// minimum width (solver/camera_regions.hpp): certified, but not every position is allowed
    camera_region,
    /// a piece of a VALID box not proven for every placement of the part its placement
    /// tolerance admits, at the placement stage's minimum width (solver/placement_stage.hpp):
    /// certified for the nominal placement only
    placement
};
inline constexpr std::size_t boundary_reason_count = 10;

/// "facet_contact", "distance", ... (JSON, messages).
constexpr std::string_view to_string(boundary_reason r) noexcept {
    switch (r) {
        case boundary_reason::facet_contact: return "facet_contact";
        case boundary_reason::distance: return "distance";
        case boundary_reason::backface: return "backface";
        case boundary_reason::view_angle: return "view_angle";
        case boundary_reason::constraint: return "constraint";
        case boundary_reason::occlusion: return "occlusion";
        case boundary_reason::field_of_view: return "field_of_view";
        case boundary_reason::budget: return "budget";
        case boundary_reason::camera_region: return "camera_region";
        case boundary_reason::placement: return "placement";
    }
    return "?";
}

}  // namespace certipose
