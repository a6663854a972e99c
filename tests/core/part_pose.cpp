// Tests of certipose/pose/part_pose.hpp: what --part-pose accepts, what it refuses (naming the
// field) and that the moved mesh is the mesh moved vertex by vertex.
#include <certipose/geometry/sample_part.hpp>
#include <certipose/pose/part_pose.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

using namespace certipose;

namespace {

/// The field and message of the invalid_argument `f` throws.
template <class F>
std::pair<std::string, std::string> refusal(F&& f) {
    try {
        f();
    } catch (const invalid_argument& e) {
        return {e.field(), e.what()};
    }
    return {"", "(nothing thrown)"};
}

}  // namespace

TEST_CASE("part_pose: a matrix that is not a rigid motion is refused, naming the field and why") {
    const auto reflection = refusal([] { part_pose_from_matrix({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0}, "--part-pose"); });
    CHECK(reflection.first == "--part-pose");
    CHECK(reflection.second.find("reflection") != std::string::npos);
    const auto sheared = refusal([] { part_pose_from_matrix({1, 0.001, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}); });
    CHECK(sheared.first == "part_pose");
    CHECK(sheared.second.find("not a rotation") != std::string::npos);
    CHECK(refusal([] { part_pose_from_matrix({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}); }).second.find("0 0 0 1") !=
          std::string::npos);
    CHECK(refusal([] { part_pose_from_matrix({1, 0, 0}); }).second.find("got 3") != std::string::npos);
    CHECK(refusal([] { part_pose_from_matrix({1, 0, 0, NAN, 0, 1, 0, 0, 0, 0, 1, 0}); }).second.find("finite") !=
          std::string::npos);
    CHECK(refusal([] { part_pose_from_xyz_rpy({0, 0, INFINITY}, {0, 0, 0}); }).second.find("finite") != std::string::npos);
    // Ten significant digits of a rotation pass; the matrix is kept as given.
    const double c = 0.7071067812;
    const part_pose p = part_pose_from_matrix({c, -c, 0, 1, c, c, 0, 2, 0, 0, 1, 3});
    CHECK(p.rotation(0, 0) == c);
    CHECK(p.translation == Eigen::Vector3d(1, 2, 3));
    CHECK(!p.is_identity());
    CHECK(part_pose{}.is_identity());
}

TEST_CASE("part_pose: roll, pitch and yaw are URDF's, and the 4x4 is row-major") {
    const double h = std::numbers::pi / 2;
    const part_pose yaw = part_pose_from_xyz_rpy({1, 2, 3}, {0, 0, h});  // x -> y
    CHECK((yaw.rotation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-15);
    const part_pose roll = part_pose_from_xyz_rpy({0, 0, 0}, {h, 0, 0});  // y -> z
    CHECK((roll.rotation * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm() < 1e-15);
    // Fixed axes: roll first, then pitch, then yaw.
    const part_pose all = part_pose_from_xyz_rpy({0, 0, 0}, {0.1, 0.2, 0.3});
    const Eigen::Matrix3d want = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
    CHECK((all.rotation - want).cwiseAbs().maxCoeff() < 1e-15);
    const auto m = yaw.matrix();
    CHECK(m[3] == 1);
    CHECK(m[7] == 2);
    CHECK(m[11] == 3);
    CHECK(m[15] == 1);
    CHECK(m[12] == 0);
    const part_pose back = part_pose_from_matrix(std::vector<double>(m.begin(), m.end()));
    CHECK(back.rotation == yaw.rotation);
    CHECK(back.translation == yaw.translation);
}

TEST_CASE("part_pose: the posed mesh has the same faces, each vertex moved, and its facets follow") {
    const auto part = make_sample_part();
    const part_pose p = part_pose_from_xyz_rpy({0.5, -0.25, 1}, {0.3, -1.1, 2.0});
    const triangle_mesh moved = posed(part.mesh, p);
    REQUIRE(moved.num_faces() == part.mesh.num_faces());
    CHECK(moved.faces() == part.mesh.faces());
    for (std::size_t i = 0; i < part.mesh.num_vertices(); ++i)
        CHECK(moved.vertices()[i] == p.rotation * part.mesh.vertices()[i] + p.translation);
    // A facet's normal turns with the part; its area does not change.
    for (std::size_t f = 0; f < part.mesh.num_faces(); f += 97) {
        const auto& a = part.mesh.facet(f);
        const auto& b = moved.facet(f);
        CHECK((b.normal - p.rotation * a.normal).norm() < 1e-12);
    }
    // The identity leaves every coordinate as it was.
    const triangle_mesh same = posed(part.mesh, part_pose{});
    CHECK(same.vertices() == part.mesh.vertices());
}
