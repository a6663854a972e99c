// certipose/occlusion/aabb_occlusion.hpp — `aabb_occlusion`, the default occlusion policy:
// its declaration, which needs no CGAL.
//
// What it decides and how is in certipose/occlusion/cgal_aabb_occlusion.hpp, which holds the
// definitions (CGAL's AABB tree and exact predicates) and is what header-only users include.
// This header is what the solver and the precompiled build (certipose::precompiled) see: a user
// translation unit that only declares the policy does not parse CGAL.
#pragma once

#include "certipose/detail/config.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/detail/box_bounds.hpp"
#include "certipose/occlusion/mesh_survey.hpp"
#include "certipose/pose/pose_box.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace certipose {

namespace detail::occ {

struct aabb_scene;  // the triangles and the AABB tree (cgal_aabb_occlusion.hpp)

/// Counters of one classification (tests and benchmarks read them through `explain`).
struct aabb_trace {
    std::size_t triangles_tested = 0;
    std::size_t exact_clips = 0;
    std::size_t blocker = static_cast<std::size_t>(-1);  ///< a triangle that blocks, if any
};

}  // namespace detail::occ

/// Fast certified occlusion policy (see certipose/occlusion/cgal_aabb_occlusion.hpp). Copies
/// are cheap and share the scene; every member is const and thread-safe.
class aabb_occlusion {
public:
    /// What `explain` reports about one classification.
    using trace = detail::occ::aabb_trace;

    /// Validates `part` as a closed solid and builds the AABB tree; throws mesh_error.
    explicit aabb_occlusion(const triangle_mesh& part);

    /// Part plus external occluders (each a closed solid; they may touch the part but must not
    /// enclose the facet). Facet indices refer to `part`.
    aabb_occlusion(const triangle_mesh& part, std::span<const triangle_mesh> occluders);

    /// The same, reading the scene as `semantics` says (occlusion/mesh_survey.hpp). `solid`
    /// validates as above; `soup` accepts any triangles (overlapping bodies, duplicate faces,
    /// open seams) and surveys them; `automatic` is `solid` when the meshes pass its checks and
    /// `soup` otherwise (`why_not_solid` then says what failed).
    aabb_occlusion(const triangle_mesh& part, std::span<const triangle_mesh> occluders, mesh_semantics semantics);

    /// How the scene is read: `solid` or `soup` (`automatic` resolved).
    mesh_semantics semantics() const noexcept;
    /// The survey of the scene (part faces first, then each occluder's) when it is read as a
    /// triangle soup; null for solids.
    const mesh_survey* survey() const noexcept;
    /// Why the scene was not taken as solids (the mesh_error of the solid checks); empty for
    /// solids and for a soup asked for as such.
    const std::string& why_not_solid() const noexcept;
    /// Why no camera can inspect facet `facet` of the part (buried, covered, a duplicate), when
    /// the survey proved it; nothing otherwise (always nothing for solids). The part solver
    /// skips such facets with this reason.
    std::optional<std::string> hidden(std::size_t facet) const;

    /// Classifies every camera position of `box` against facet `facet` of the part. Throws
    /// out_of_range("facet") and invalid_argument("box") (empty or unbounded box). With
    /// `occlusion_effort::visible_only` a blocked box is PARTIAL, without the search for an
    /// OCCLUDED certificate (occlusion/concept.hpp).
    template <Interval I>
    visibility classify(const position_box<I>& box, std::size_t facet,
                        occlusion_effort effort = occlusion_effort::full) const {
        return classify(detail::occ::box_bounds(box, "aabb_occlusion"), facet, effort);
    }

    /// The same on a box given by double bounds.
    visibility classify(const Eigen::AlignedBox3d& box, std::size_t facet,
                        occlusion_effort effort = occlusion_effort::full) const;

    /// ShadowingOcclusionPolicy: visits the scene triangles that may block a sight line from
    /// `box` to facet `facet` (occlusion/concept.hpp), as the AABB tree walk finds them. True
    /// when it showed them all; false when `visit` stopped it, when some corner of the box is
    /// not strictly in front of the facet, or after `max_blockers` triangles. Throws as `classify`.
    template <Interval I>
    bool blockers(const position_box<I>& box, std::size_t facet, blocker_visitor visit) const {
        return blockers(detail::occ::box_bounds(box, "aabb_occlusion"), facet, visit);
    }
    bool blockers(const Eigen::AlignedBox3d& box, std::size_t facet, blocker_visitor visit) const;

    /// ShadowingOcclusionPolicy: the shadow of scene triangle `triangle` (part faces first,
    /// then each occluder's) for facet `facet`: the planes through three of their six vertices
    /// with the facet on one closed side and the triangle on the other (exact orientations).
    /// Throws out_of_range("facet") / out_of_range("triangle").
    occlusion_shadow shadow(std::size_t facet, std::size_t triangle) const;

    /// RefutingOcclusionPolicy: whether the segment from `from` to facet `facet`'s centroid
    /// (rounded to doubles), open at the centroid, may meet another scene triangle not wholly
    /// behind or in the facet's plane, or the survey proved the facet hidden. True refutes
    /// VISIBLE for every box holding `from`. Throws out_of_range("facet"), invalid_argument("point")
    /// for a non-finite point.
    bool sight_line_blocked(const Eigen::Vector3d& from, std::size_t facet) const;
    /// The same answer, trying triangle `hint` first and then setting it to the triangle that
    /// blocked: the facets a camera does not see, taken in order, are mostly hidden behind the
    /// same triangle, which then settles the line without a walk of the tree. Any value is a
    /// valid hint (one beyond the scene is ignored).
    bool sight_line_blocked(const Eigen::Vector3d& from, std::size_t facet, std::size_t& hint) const;

    /// Whether every sight line from a position of `box` strictly in front of facet `facet`'s
    /// plane to any point of the facet is free: no scene triangle but the facet has a point
    /// strictly in front of that plane within the bounding box of `box` and the facet (exact
    /// orientations). Such a line lies in that bounding box, and strictly in front of the plane
    /// but at its end, so no triangle wholly on or behind the plane can meet it. False for a
    /// facet the survey proved hidden. The caller proves its positions in front (the part
    /// solver's reuse stage, part/translates.hpp). Throws as `classify`.
    bool front_clear(const Eigen::AlignedBox3d& box, std::size_t facet) const;
    template <Interval I>
    bool front_clear(const position_box<I>& box, std::size_t facet) const {
        return front_clear(detail::occ::box_bounds(box, "aabb_occlusion"), facet);
    }

    /// `blockers` gives up after this many possibly blocking triangles (a box that many
    /// triangles may block is bisected instead).
    static constexpr std::size_t max_blockers = 64;

    /// `classify`, also reporting how the answer was reached (for tests and benchmarks).
    visibility explain(const Eigen::AlignedBox3d& box, std::size_t facet, trace& info,
                       occlusion_effort effort = occlusion_effort::full) const;

    /// At most this many distinct planes of blocking triangles are tried as walls.
    static constexpr std::size_t max_wall_planes = 8;

    /// Number of exact rational fallbacks taken so far by all copies (diagnostics).
    std::uint64_t exact_fallbacks() const noexcept;

private:
    std::shared_ptr<const detail::occ::aabb_scene> scene_;
};

}  // namespace certipose
