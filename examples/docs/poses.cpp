// docs/poses.md — the ZXZ rotation, the nominal aim at a facet and the projection of its
// vertices, for one pose and for a whole pose box.
#include <certipose/certipose.hpp>

#include <cstdio>

int main() {
    using I = certipose::boost_interval;
    using namespace certipose;

    Eigen::Matrix3d K;  // f_px = 0.012 / 3.45e-6, principal point at the centre of 2448 x 2048
    K << 3478.26, 0, 1224, 0, 3478.26, 1024, 0, 0, 1;
    const Eigen::Vector3d facet_centre(0.1, 0.05, 0.0), camera(0.1, -0.3, 0.45);
    const Eigen::Vector3d vertex(0.12, 0.06, 0.0);

    // Nominal aim (paper §6.4): the optical axis from the camera to the facet centre, β = 0.
    const zxz_angles aim = zxz_angles_from_axis(facet_centre - camera);
    const Eigen::Matrix3d R = zxz_rotation(aim.phi, aim.gamma, aim.beta);
    const Eigen::Vector3d qc = world_to_camera(R, camera, vertex);  // q_c = Rᵀ(q − p)
    const Eigen::Vector2d px = project(K, qc);
    std::printf("aim: phi = %.4f, gamma = %.4f rad; axis = (%.3f, %.3f, %.3f)\n", aim.phi, aim.gamma,
                optical_axis(aim.phi, aim.gamma).x(), optical_axis(aim.phi, aim.gamma).y(),
                optical_axis(aim.phi, aim.gamma).z());
    std::printf("vertex at depth %.4f m, pixel (%.1f, %.1f)\n", qc.z(), px.x(), px.y());

    // A pose box: 2 cm of position and ±0.05 rad of each angle around that pose. Every pose in it
    // sees the vertex inside the pixel box below (sound enclosure).
    pose_box<I> box;
    for (int i = 0; i < 3; ++i) box.position[i] = I(camera(i) - 0.01, camera(i) + 0.01);
    box.orientation = orientation_box<I>::from_bounds(
        {{{aim.phi - 0.05, aim.phi + 0.05}, {aim.gamma - 0.05, aim.gamma + 0.05}, {-0.05, 0.05}}});
    vector3<I> qc_box;
    vector2<I> px_box;
    bool front = false;
    {
        const rounding_guard<I> guard;
        const matrix3<I> R_box = zxz_rotation(box.orientation);
        const vector3<I> p(box.position[0], box.position[1], box.position[2]);
        qc_box = world_to_camera(R_box, p, vertex);
        front = in_front(qc_box);  // certainly in front, for every pose of the box
        if (front) px_box = project(K, qc_box);
    }
    std::printf("box: depth [%.4f, %.4f], in front: %d\n", lower(qc_box.z()), upper(qc_box.z()), front);
    if (front)
        std::printf("box: u in [%.1f, %.1f], v in [%.1f, %.1f] (image 2448 x 2048)\n", lower(px_box(0)),
                    upper(px_box(0)), lower(px_box(1)), upper(px_box(1)));
    return front && contains(px_box(0), px.x()) && contains(px_box(1), px.y()) ? 0 : 1;
}
