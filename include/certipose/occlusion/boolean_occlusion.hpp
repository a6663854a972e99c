// certipose/occlusion/boolean_occlusion.hpp — `boolean_occlusion`, the paper's occlusion test
// (§6.3, Algorithm 2): its declaration, which needs no CGAL.
//
// What it decides and how is in certipose/occlusion/cgal_boolean_occlusion.hpp, which holds the
// definitions (CGAL's exact kernel and corefinement) and is what header-only users include.
// `boolean_occlusion` is `basic_boolean_occlusion<>`, a class template only so that its CGAL code
// (corefinement: about a minute to compile) is compiled where the policy is used, not in every
// translation unit that includes <certipose/cgal.hpp>; certipose::precompiled compiles it once.
#pragma once

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/detail/box_bounds.hpp"
#include "certipose/pose/pose_box.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <memory>
#include <span>

namespace certipose {

namespace detail::occ {
struct boolean_scene;  // exact copies of the solids (cgal_boolean_occlusion.hpp)
}  // namespace detail::occ

/// The paper's Algorithm 2 with exact booleans (see certipose/occlusion/cgal_boolean_occlusion.hpp).
/// Copies are cheap and share the scene; every member is const and thread-safe. `Lazy` is not
/// used (see the header comment).
template <class Lazy = void>
class basic_boolean_occlusion {
public:
    /// Validates `part` as a closed solid and keeps an exact copy; throws mesh_error.
    explicit basic_boolean_occlusion(const triangle_mesh& part);

    /// Part plus external occluders (closed solids; they may touch the part but must not
    /// enclose the facet). Facet indices refer to `part`.
    basic_boolean_occlusion(const triangle_mesh& part, std::span<const triangle_mesh> occluders);

    /// Classifies every camera position of `box` against facet `facet` of the part. Throws
    /// out_of_range("facet"), invalid_argument("box"), and geometry_error if CGAL fails in a
    /// way that is not a reportable non-manifold result.
    template <Interval I>
    visibility classify(const position_box<I>& box, std::size_t facet) const {
        return classify(detail::occ::box_bounds(box, "boolean_occlusion"), facet);
    }

    /// The same on a box given by double bounds.
    visibility classify(const Eigen::AlignedBox3d& box, std::size_t facet) const;

private:
    using scene = detail::occ::boolean_scene;
    std::shared_ptr<const scene> scene_;
};

/// The paper's occlusion test (Algorithm 2).
using boolean_occlusion = basic_boolean_occlusion<>;

}  // namespace certipose
