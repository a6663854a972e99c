// docs/orientation.md — certified aims for one position box: certify_fov on a hand-made box,
// the default policy (paper §6.4 + certification) and the paving policy, then a user-side
// check of a few sampled poses.
#include <certipose/certipose.hpp>

#include <cstdio>

int main() {
    using I = certipose::boost_interval;
    const certipose::thin_lens_camera camera({.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6,
                                              .max_blur_circle = 6.9e-6, .pixel_pitch = 3.45e-6,
                                              .width_px = 2448, .height_px = 2048});
    // A 3 cm facet at the origin and a 5 cm position box about 0.55 m away.
    certipose::facet f;
    f.v = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.03, 0, 0), Eigen::Vector3d(0, 0.03, 0)};
    f.centroid = (f.v[0] + f.v[1] + f.v[2]) / 3.0;
    f.normal = Eigen::Vector3d::UnitZ();
    const auto position = certipose::position_box<I>::from_bounds({{{0.20, 0.25}, {0.10, 0.15}, {0.50, 0.55}}});

    // 1. The nominal aim (box centre → centroid) and a certification over a whole 6D box.
    const auto aim = certipose::nominal_aim(position, f);  // φ, γ (β = 0)
    std::printf("nominal aim: phi %.4f, gamma %.4f rad\n", aim->phi, aim->gamma);
    const certipose::fov_frustum<I> frustum(camera);  // precomputed once per camera
    const auto e = certipose::orientation_box<I>::from_bounds(
        {{{aim->phi - 0.05, aim->phi + 0.05}, {aim->gamma - 0.05, aim->gamma + 0.05}, {-3.2, 3.2}}});
    const char* names[] = {"satisfied", "violated", "undecided"};
    std::printf("certify_fov(aim +/- 0.05, any roll): %s\n",
                names[static_cast<int>(certipose::certify_fov(position, e, f, frustum))]);

    // 2. The default policy: one certified box around the nominal aim, as wide as it can prove.
    const certipose::paper_orientation paper;
    const auto r = paper.orient(position, f, camera, /*orientation_eps=*/0.38);
    for (const auto& b : r.boxes)
        std::printf("paper_orientation: phi [%.4f, %.4f] gamma [%.4f, %.4f] beta [%.4f, %.4f] (%zu certifications)\n",
                    certipose::lower(b[0]), certipose::upper(b[0]), certipose::lower(b[1]), certipose::upper(b[1]),
                    certipose::lower(b[2]), certipose::upper(b[2]), r.certifications);

    // 3. The paving policy: every certified box of the orientation space at resolution ε_o.
    const auto all = certipose::paving_orientation{}.orient(position, f, camera, 0.38);
    std::printf("paving_orientation: %zu certified boxes (%zu certifications)\n", all.boxes.size(), all.certifications);

    // 4. Any pose of position × box sees the whole facet: check one corner pose in plain double.
    const auto& b = r.boxes.at(0);
    const Eigen::Matrix3d R = certipose::zxz_rotation(certipose::upper(b[0]), certipose::lower(b[1]), certipose::upper(b[2]));
    const Eigen::Vector3d p(0.25, 0.10, 0.55);
    for (const auto& v : f.v) {
        const Eigen::Vector3d q = camera.intrinsics() * (R.transpose() * (v - p));
        std::printf("  vertex at pixel (%.1f, %.1f)\n", q.x() / q.z(), q.y() / q.z());
    }
}
