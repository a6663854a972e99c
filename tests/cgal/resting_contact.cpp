// occlusion/resting_contact.hpp: a facet lies face to face on an occluder exactly when its corners
// are on a coplanar occluder triangle facing the other way; a facet a hair above, facing the same
// way, or reaching past the occluder's edge does not rest on it.
#include <certipose/occlusion/resting_contact.hpp>

#include <doctest/doctest.h>

#include <vector>

using namespace certipose;
using V = Eigen::Vector3d;

namespace {
/// A plate whose top face is z = 0 from (-1, -1) to (1, 1), split along its diagonal, facing +z.
triangle_mesh plate_top() {
    return triangle_mesh({V(-1, -1, 0), V(1, -1, 0), V(1, 1, 0), V(-1, 1, 0)}, {face_indices{0, 1, 2}, face_indices{0, 2, 3}});
}
}  // namespace

TEST_CASE("resting contact: the underside of a part on a plate rests on it, nothing else does") {
    // Part facets, each a triangle of its own:
    //  0 facing down (-z) on z = 0, across the plate's diagonal: rests;
    //  1 facing up on z = 0: coplanar but facing the same way as the plate: does not rest;
    //  2 facing down at z = 1e-9: not coplanar: does not rest;
    //  3 facing down on z = 0 but reaching past x = 1: a corner off the plate: does not rest;
    //  4 facing down on z = 0 with a corner exactly on the plate's edge: rests (closed triangles).
    const double tiny = 1e-9;
    const triangle_mesh part({V(-0.5, -0.2, 0), V(0.3, 0.5, 0), V(0.4, -0.4, 0),     // 0: normal -z
                              V(-0.5, -0.2, 0), V(0.4, -0.4, 0), V(0.3, 0.5, 0),     // 1: normal +z
                              V(-0.5, -0.2, tiny), V(0.3, 0.5, tiny), V(0.4, -0.4, tiny),
                              V(0.5, 0, 0), V(0.9, 0.5, 0), V(1.5, 0, 0),
                              V(0.5, 0, 0), V(1.0, 0.5, 0), V(1.0, 0, 0)},
                             {face_indices{0, 1, 2}, face_indices{3, 4, 5}, face_indices{6, 7, 8}, face_indices{9, 10, 11},
                              face_indices{12, 13, 14}});
    REQUIRE(part.facet(0).normal.z() < 0);
    REQUIRE(part.facet(1).normal.z() > 0);
    REQUIRE(part.facet(3).normal.z() < 0);
    REQUIRE(part.facet(4).normal.z() < 0);
    const std::vector<triangle_mesh> occluders{plate_top()};
    const auto resting = resting_on_occluders(part, occluders);
    CHECK(resting == std::vector<char>{1, 0, 0, 0, 1});
    // Only the facets asked about are tested.
    CHECK(resting_on_occluders(part, occluders, {0, 0, 0, 0, 1}) == std::vector<char>{0, 0, 0, 0, 1});
    // No occluder, nothing rests.
    CHECK(resting_on_occluders(part, std::vector<triangle_mesh>{}) == std::vector<char>(5, 0));
}
