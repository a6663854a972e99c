// sight_region_clear (occlusion/fixed_occluders.hpp): a fixed triangle separated from the hull of
// the camera box and the moved facet is proven clear; one that only touches it is clear exactly
// when the touch is on the targets' side with the camera box strictly beyond (constraint 6 is
// about the open segment), and not otherwise.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/occlusion/fixed_occluders.hpp>

#include <doctest/doctest.h>

#include <array>
#include <vector>

using namespace certipose;

namespace {

using I = boost_interval;

/// A plate's top: two triangles at z = 0 over [-1, 1]², normal +z.
fixed_occluders plate_top() {
    fixed_occluders o;
    const Eigen::Vector3d a(-1, -1, 0), b(1, -1, 0), c(1, 1, 0), d(-1, 1, 0);
    for (const auto& t : {std::array<Eigen::Vector3d, 3>{a, b, c}, std::array<Eigen::Vector3d, 3>{a, c, d}}) {
        Eigen::AlignedBox3d box(t[0]);
        box.extend(t[1]), box.extend(t[2]);
        o.triangles.push_back({t, Eigen::Vector3d::UnitZ(), box});
    }
    return o;
}

position_box<I> box(double x0, double x1, double y0, double y1, double z0, double z1) {
    return {I(x0, x1), I(y0, y1), I(z0, z1)};
}

}  // namespace

TEST_CASE("sight_region_clear: a facet resting on the plate is clear from above, not from a camera at the plate") {
    const fixed_occluders plate = plate_top();
    // A wall facet from z = 0 up, facing +x.
    const std::array<Eigen::Vector3d, 3> wall{Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d(0.1, 0.1, 0), Eigen::Vector3d(0.1, 0, 0.1)};
    const Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
    const std::array<double, 3> across{0.002, 0.002, 0.0}, tipping{0.002, 0.002, 1e-4};
    const auto above = box(0.5, 0.6, -0.1, 0.1, 0.3, 0.4);
    // Resting, not moved into the plate, camera strictly above: every open sight segment stays
    // above z = 0.
    CHECK(sight_region_clear(above, wall, normal, across, plate));
    // Moved into the plate by a hair: a sight line may end below its top, so not proven.
    CHECK(!sight_region_clear(above, wall, normal, tipping, plate));
    // A camera box reaching down to the plate's top: a segment may run along it.
    CHECK(!sight_region_clear(box(0.5, 0.6, -0.1, 0.1, 0.0, 0.4), wall, normal, across, plate));
    // A facet clear of the plate is clear however the camera box touches nothing.
    const std::array<Eigen::Vector3d, 3> high{Eigen::Vector3d(0.1, 0, 0.2), Eigen::Vector3d(0.1, 0.1, 0.2),
                                              Eigen::Vector3d(0.1, 0, 0.3)};
    CHECK(sight_region_clear(above, high, normal, tipping, plate));
    // A camera below the plate looking up at the wall: the plate is in the way.
    CHECK(!sight_region_clear(box(0.5, 0.6, -0.1, 0.1, -0.4, -0.3), wall, normal, across, plate));
}
