// docs/completeness.md: certifying more of the true inspection space — the paper's paving against
// the default (inner contraction, occlusion cuts, corner boxes), refinement for a time budget,
// grown boxes, and the installation tolerance of one pose. Links certipose::precompiled.
#include <certipose/cgal.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

int main() {
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::pose_solver<> solver(part.mesh, camera, {.min_view_angle = 0.35});
    const std::size_t facet = part.facet_of_interest;

    // The paper's paving: partly valid boxes are bisected down to ε_p, then given up.
    certipose::solve_options paper{.position_eps = 0.1, .orientation_eps = 0.38};
    paper.paving = certipose::paper_paving{};
    // The default: what certainly holds is carved off partly valid boxes instead.
    const certipose::solve_options carving{.position_eps = 0.1, .orientation_eps = 0.38};
    // As complete as 1 s allows: refine below ε_p, largest undecided box first.
    certipose::solve_options anytime{.position_eps = 0.1, .orientation_eps = 0.38};
    anytime.time_limit = std::chrono::seconds(1);
    anytime.refine = certipose::refinement{};
    // Fewer, larger boxes: merge neighbours, then move every face out while certified.
    certipose::solve_options wide{.position_eps = 0.1, .orientation_eps = 0.38};
    wide.grow = certipose::growth_options{};
    // The most complete answer in 1 s: refine, orient, then widen with what time is left.
    certipose::solve_options most = anytime;
    most.grow = certipose::growth_options{};

    for (const auto& [name, options] : {std::pair{"paper", paper}, std::pair{"carving", carving},
                                        std::pair{"anytime", anytime}, std::pair{"wide", wide}, std::pair{"most", most}}) {
        const auto r = solver.solve(facet, options);
        std::printf("%-8s %5zu VALID %6zu BOUNDARY  certified %.4f m^3 of positions in %.3f s\n", name, r.stats.valid,
                    r.stats.boundary, r.stats.valid_volume, r.stats.seconds);
    }

    // The installation tolerance of one pose: the largest certified 6D box around it.
    const certipose::facet& f = part.mesh.facet(facet);
    const Eigen::Vector3d p = f.centroid + 0.6 * f.normal;  // 0.6 m above the facet, looking at it
    const Eigen::Vector3d d = (f.centroid - p).normalized();
    const std::array<double, 6> pose{p.x(), p.y(), p.z(), std::atan2(d.x(), -d.y()), std::acos(d.z()), 0.0};
    if (const auto box = solver.largest_box_around(facet, pose)) {
        const auto half = [&](const certipose::boost_interval& x) { return (certipose::upper(x) - certipose::lower(x)) / 2; };
        std::printf("around the pose: x ±%.3f y ±%.3f z ±%.3f m, phi ±%.3f gamma ±%.3f beta ±%.3f rad\n",
                    half(box->position[0]), half(box->position[1]), half(box->position[2]), half(box->orientation[0]),
                    half(box->orientation[1]), half(box->orientation[2]));
        std::printf("certified: %s\n", solver.certify(facet, *box) ? "yes" : "no");
    }
}
