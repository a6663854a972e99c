// Lens distortion through the whole pipeline (issue 35): the case-study facet and the
// plate_holes reference case solved with a distorted camera (pincushion k1 = +0.3, k2 = 0.1 and
// barrel k1 = −0.3), every VALID box sampled (random poses and its 64 corners) by the independent
// check, which projects through the distortion (verify/point_check.hpp). And the reason for it
// all: the boxes of the same camera solved as a pinhole are NOT sound once the lens distorts.
#include "solver_support.hpp"

#include <certipose/io/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

using namespace solver_test;

namespace {

using I = boost_interval;
using case_solver = pose_solver<with_camera<calibrated_camera>>;

struct distortion_case {
    std::string label;
    triangle_mesh mesh;
    thin_lens_camera camera;
    inspection_task task;
    std::size_t facet;
};

std::vector<distortion_case> cases() {
    std::vector<distortion_case> out;
    out.push_back({"case study", part().mesh, thin_lens_camera(design_camera_parameters()),
                   inspection_task{.min_view_angle = 0.35}, part().facet_of_interest});
    const std::string dir = std::string(CERTIPOSE_SHARED_MESHES);
    const camera_task in = read_camera_task(std::filesystem::path(dir) / "../cases/camera.json");
    out.push_back({"plate_holes facet 7", read_mesh(dir + "/plate_holes.off", {.scale = 0.00109127}),
                   std::get<thin_lens_camera>(in.camera), in.task, 7});
    return out;
}

}  // namespace

TEST_CASE("distortion: VALID boxes of distorted cameras are sound, a pinhole's are not under pincushion") {
    const solve_options options{.position_eps = 0.1, .orientation_eps = 0.38};
    const brown_conrady pincushion{.k1 = 0.3, .k2 = 0.1}, barrel{.k1 = -0.3};
    std::size_t pinhole_violations = 0;
    std::uint32_t seed = 3501;
    for (const distortion_case& c : cases()) {
        CAPTURE(c.label);
        const calibrated_camera pinhole(c.camera, "thin_lens");
        const case_solver pinhole_solver(c.mesh, pinhole, c.task);
        const auto plain = pinhole_solver.solve(c.facet, options);
        for (const brown_conrady& d : {pincushion, barrel}) {
            CAPTURE(d.k1);
            const calibrated_camera camera(distorted_camera(c.camera, d), "thin_lens");
            const case_solver solver(c.mesh, camera, c.task);
            const auto r = solver.solve(c.facet, options);
            const sampling_report rep =
                check_valid_boxes(r, c.mesh, camera, solver.range(), c.task.min_view_angle, 4, seed++, true);
            MESSAGE(c.label << ", k1 = " << d.k1 << ": " << rep.valid_boxes << " VALID boxes (pinhole: "
                            << plain.stats.valid << "), " << rep.samples << " poses sampled, " << rep.violations
                            << " violations");
            CHECK(rep.valid_boxes > 0);
            CHECK(rep.violations == 0);
            if (d.k1 > 0) {
                // The pinhole's VALID boxes judged through the pincushion lens.
                const sampling_report wrong =
                    check_valid_boxes(plain, c.mesh, camera, pinhole_solver.range(), c.task.min_view_angle, 16, seed++, true);
                MESSAGE(c.label << ": the pinhole's " << wrong.valid_boxes << " VALID boxes under k1 = 0.3, k2 = 0.1: "
                                << wrong.violations << " violations in " << wrong.samples << " poses");
                pinhole_violations += wrong.violations;
            }
        }
    }
    CHECK(pinhole_violations > 0);
}
