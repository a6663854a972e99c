// robot_reach — run-time parameters for a constraint set: a camera on a robot arm must stay
// within the arm's reach, a ball read from JSON ({"base": [x, y, z], "reach": r}, metres).
//
//   robot_reach [REACH.json]        (default: examples/data/robot_reach.json)
//
// The paper's position constraints and `keep_in_sphere` are combined with all_of; the sphere's
// centre and radius are values given to the solver (`setup::constraints`), not compile-time
// constants, so one compiled pipeline serves every robot cell. Solves the case-study facet of
// the sample part with and without the reach limit and prints both counts.
#include <certipose/cgal.hpp>
#include <certipose/io/json.hpp>

#include <cstdio>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>

namespace {

template <class I>
using reachable = certipose::all_of<certipose::paper_position_constraints<I>, certipose::keep_in_sphere<I>>;

/// The reach file: {"base": [x, y, z], "reach": r}.
certipose::keep_in_sphere<certipose::boost_interval>::parameters read_reach(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path);
    const nlohmann::json j = nlohmann::json::parse(in);
    const auto base = j.at("base").get<std::array<double, 3>>();
    return {.centre = Eigen::Vector3d(base[0], base[1], base[2]), .radius = j.at("reach").get<double>()};
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const std::string path = argc > 1 ? argv[1] : CERTIPOSE_EXAMPLE_DATA "/robot_reach.json";
        const auto reach = read_reach(path);
        const auto part = certipose::make_sample_part();
        const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
            .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
            .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
        const certipose::inspection_task task{.min_view_angle = 0.35};
        const certipose::solve_options options{.position_eps = 0.1, .orientation_eps = 0.38};

        const certipose::pose_solver<> anywhere(part.mesh, camera, task);
        const certipose::pose_solver<certipose::with_constraints<reachable>> within(
            part.mesh, camera, task, {.constraints = {{}, reach}});
        const auto all = anywhere.solve(part.facet_of_interest, options);
        const auto reachable_boxes = within.solve(part.facet_of_interest, options);
        std::printf("facet %zu: %zu VALID boxes anywhere, %zu within %.3g m of (%.3g, %.3g, %.3g)\n",
                    part.facet_of_interest, all.stats.valid, reachable_boxes.stats.valid, reach.radius,
                    reach.centre.x(), reach.centre.y(), reach.centre.z());
        return reachable_boxes.stats.valid > 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "robot_reach: %s\n", e.what());
        return 1;
    }
}
