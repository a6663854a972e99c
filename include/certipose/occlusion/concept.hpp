// certipose/occlusion/concept.hpp — the OcclusionPolicy concept: classify a camera position box
// against one facet of the part (paper §6.3; constraint 6 of docs/conventions.md). No CGAL here: the
// solver includes this header and must compile with `no_occlusion` and without CGAL.
//
// A policy is built once per scene — the part mesh plus optional external occluder meshes —
// and caches whatever depends on the scene only (AABB tree, exact copies). `classify(box, f)`
// then answers for every camera position p in the box and every point q of facet f:
//   VISIBLE  — every sight line from p to q is free (certified);
//   OCCLUDED — no sight line from the box reaches a point of f's relative interior (certified);
//   PARTIAL  — anything else, or not decided: the paver bisects.
// A sight line is blocked when its open segment (p, q) meets a scene triangle other than f, or
// runs through the inside of a scene solid (the scene is a set of closed solids; the camera
// cannot sit inside the part). See docs/occlusion.md for the exact rules of each policy.
#pragma once

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/pose_box.hpp"

#include <Eigen/Core>

#include <array>
#include <concepts>
#include <cstddef>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

namespace certipose {

/// What a position box sees of a facet (paper Algorithm 2's three outcomes).
enum class visibility {
    visible,   ///< every sight line from every box point to every facet point is free
    partial,   ///< some free and some blocked, or undecided: bisect
    occluded   ///< no free sight line from the box to the facet's relative interior
};

/// "visible", "partial" or "occluded" (tables, JSON, test messages).
constexpr std::string_view to_string(visibility v) noexcept {
    switch (v) {
        case visibility::visible: return "visible";
        case visibility::partial: return "partial";
        case visibility::occluded: return "occluded";
    }
    return "?";
}

/// How hard `classify` works on a box that is not VISIBLE. `full` looks for a certificate of
/// OCCLUDED (it prunes the paving: an occluded box is not bisected further); `visible_only` may
/// answer PARTIAL without looking, for boxes the paver will not bisect anyway — there OCCLUDED
/// and PARTIAL both keep the box out of the VALID set, and the search is most of the cost of a
/// blocked box (docs/occlusion.md). VISIBLE is decided the same way either way.
enum class occlusion_effort { full, visible_only };

/// A policy built from the scene (`P(part)` or `P(part, occluders)`) whose const `classify`
/// takes a position box over interval type `I` and a facet index of the part. Models say in
/// their documentation whether one object may be shared by several threads (all of
/// certipose's are).
template <class P, class I>
concept OcclusionPolicy =
    Interval<I> && std::constructible_from<P, const triangle_mesh&> &&
    std::constructible_from<P, const triangle_mesh&, std::span<const triangle_mesh>> &&
    requires(const P& policy, const position_box<I>& box, std::size_t facet) {
        { policy.classify(box, facet) } -> std::same_as<visibility>;
    };

/// Whether a policy takes an `occlusion_effort` (optional: the solver passes `visible_only` for
/// boxes it will not bisect when the policy does, and calls plain `classify` otherwise).
template <class P, class I>
concept EffortAwareOcclusionPolicy =
    OcclusionPolicy<P, I> && requires(const P& policy, const position_box<I>& box, std::size_t facet) {
        { policy.classify(box, facet, occlusion_effort::full) } -> std::same_as<visibility>;
    };

/// A closed half-space of camera positions given exactly: the p with
/// sign · ((b − a) × (c − a)) · (p − a) ≤ 0, for double points a, b, c (`points`) and sign ±1.
struct occlusion_half_space {
    std::array<Eigen::Vector3d, 3> points;
    int sign = 1;
};

/// Where one scene triangle T may block a sight line to the facet: the intersection of
/// `count` closed half-spaces. Each is the closed side, away from the facet, of a plane with
/// the facet's vertices on one closed side and T's on the other; from a position strictly on
/// the facet's side every open sight segment to the facet stays strictly on that side, so T
/// blocks none of them. Outside the shadow of every triangle that might block, the facet is
/// VISIBLE. `count == 0` means T has no such plane here: its shadow is everything.
struct occlusion_shadow {
    static constexpr std::size_t max_planes = 19;  // T's plane, 9 edge–vertex planes each way
    std::array<occlusion_half_space, max_planes> planes{};
    std::size_t count = 0;
    std::size_t triangle = 0;  ///< T's index in the scene (part faces first)
};

/// Receives the scene triangles of `ShadowingOcclusionPolicy::blockers` one at a time (their
/// indices); returning false stops the walk.
class blocker_visitor {
public:
    template <class F>
        requires std::is_invocable_r_v<bool, F&, std::size_t>
    blocker_visitor(F& f) noexcept  // NOLINT(implicit): built from a lambda at the call
        : ctx_(&f), fn_([](void* c, std::size_t t) { return static_cast<bool>((*static_cast<F*>(c))(t)); }) {}
    bool operator()(std::size_t triangle) const { return fn_(ctx_, triangle); }

private:
    void* ctx_;
    bool (*fn_)(void*, std::size_t);
};

/// An occlusion policy that can also say *where* a box loses sight of the facet (optional; the
/// position stage uses it to carve the certainly visible part off an occlusion-PARTIAL box,
/// solve_options::occlusion_cuts):
///  * `blockers(box, facet, visit)` calls `visit` with every scene triangle that may block a
///    sight line from the box, and returns true when it has shown them all; false — nothing
///    certified — when `visit` stopped it or it cannot say (a box not strictly in front of the
///    facet, too many candidates);
///  * `shadow(facet, triangle)` is that triangle's shadow, which depends on the two triangles
///    alone (so callers may keep it for every box).
/// Positions of the box outside the shadows of all its blockers see the facet: every other
/// constraint-6 condition the policy's VISIBLE needs holds on the whole box.
template <class P, class I>
concept ShadowingOcclusionPolicy =
    OcclusionPolicy<P, I> && requires(const P& policy, const position_box<I>& box, std::size_t facet, blocker_visitor visit) {
        { policy.blockers(box, facet, visit) } -> std::same_as<bool>;
        { policy.shadow(facet, facet) } -> std::same_as<occlusion_shadow>;
    };

/// An occlusion policy that can refute VISIBLE cheaply (optional): `sight_line_blocked(p, facet)`
/// true says the sight line from the point p to the facet's centroid meets another scene
/// triangle (or that no camera sees the facet at all), so no box holding p is VISIBLE or clear
/// of its blockers' shadows; false says nothing. One segment query is cheaper than the
/// sight-hull walk, and most facets a box fails to see are blocked at its centre too, so a
/// caller proving many facets visible from one box (the coverage inspector) asks this first. A
/// wrong `true` would only lose a certificate, never add one.
template <class P>
concept RefutingOcclusionPolicy = requires(const P& policy, const Eigen::Vector3d& p, std::size_t facet) {
    { policy.sight_line_blocked(p, facet) } -> std::same_as<bool>;
};

/// Whether a policy decides constraint 6 at all: true unless it declares
/// `static constexpr bool checks_occlusion = false` (as `no_occlusion` does), in which case
/// VALID boxes are certified for every constraint but occlusion, and results say so.
template <class P>
inline constexpr bool checks_occlusion = [] {
    if constexpr (requires { P::checks_occlusion; })
        return static_cast<bool>(P::checks_occlusion);
    else
        return true;
}();

}  // namespace certipose
