// certipose/orientation/concept.hpp — the OrientationPolicy concept: certified orientation boxes
// for one certified position box (docs/orientation.md, paper §6.4 and Algorithm 3 lines 28–36).
//
// The solver paves positions first; for every VALID position box [p] it asks the orientation
// policy `policy.orient(p, facet, camera, orientation_eps)` for orientation boxes [e] such that
// every pose of [p] × [e] satisfies the field-of-view constraint (constraint 5, docs/conventions.md).
// Every returned box must be certified (e.g. by `certify_fov`); an empty answer means "none
// could be certified at this position-box size": the solver then bisects [p], down to ε_p, and
// finally reports it BOUNDARY. The counters let the solver report how much certification work
// the orientation stage did. The default model is `paper_orientation` (paper §6.4 with
// interval certification); `paving_orientation` paves the whole orientation space instead.
// A policy must work with any `CameraModel`; the concept is checked for the solver's camera.
#pragma once

#include <concepts>
#include <cstddef>
#include <span>
#include <vector>

#include "certipose/camera/camera_model.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

/// What an orientation policy returns for one position box.
template <Interval I>
struct orientation_result {
    /// Certified boxes [φ]×[γ]×[β]: every pose of position × box satisfies constraint 5.
    /// Empty when none could be certified for this position box.
    std::vector<orientation_box<I>> boxes;
    /// 6D interval certifications (`certify_fov` evaluations) attempted.
    std::size_t certifications = 0;
};

/// `p.orient(position, facet, camera, orientation_eps)` → certified orientation boxes.
template <class P, class I, class Camera>
concept OrientationPolicy =
    Interval<I> && CameraModel<Camera> &&
    requires(const P& p, const position_box<I>& position, const facet& f, const Camera& camera, double eps) {
        { p.orient(position, f, camera, eps) } -> std::same_as<orientation_result<I>>;
    };

/// An orientation policy that can start from what its search found for a nearby position box:
/// `p.orient(position, facet, camera, orientation_eps, hint)` reads and updates `hint`. The
/// solver keeps one hint per cell of ε_p, made by `p.new_hint(position_eps)` (a new hint knows
/// the size of the cell it serves and nothing else), so the many small position boxes of a cell
/// (carved pieces, corner boxes, refined leaves) search where their neighbours found a box. A
/// hint may change how fast a box is found and which, never whether a returned box is certified.
template <class P, class I, class Camera>
concept HintedOrientationPolicy =
    OrientationPolicy<P, I, Camera> && std::copy_constructible<typename P::hint> &&
    requires(const P& p, const position_box<I>& position, const facet& f, const Camera& camera, double eps,
             typename P::hint& hint) {
        { p.new_hint(eps) } -> std::same_as<typename P::hint>;
        { p.orient(position, f, camera, eps, hint) } -> std::same_as<orientation_result<I>>;
    };

/// A hinted policy that can also try what the searches of neighbouring position boxes found
/// when its own search found nothing: `p.orient_borrowed(position, facet, camera,
/// orientation_eps, neighbours)` tries the box (some of) the hints name around this box's own
/// aim, and nothing else. The solver asks it for a box whose own search failed in a cell of ε_p
/// where nothing was oriented yet, with the hints of the neighbouring cells: a search stops
/// narrowing at ε_o, while a neighbour's scale may certify a narrower box that the search never
/// tries. The same rule as for hints: which box is found, never whether it is certified.
template <class P, class I, class Camera>
concept BorrowingOrientationPolicy =
    HintedOrientationPolicy<P, I, Camera> &&
    requires(const P& p, const position_box<I>& position, const facet& f, const Camera& camera, double eps,
             std::span<const typename P::hint* const> neighbours) {
        { p.orient_borrowed(position, f, camera, eps, neighbours) } -> std::same_as<orientation_result<I>>;
    };

}  // namespace certipose
