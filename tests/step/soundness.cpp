// The VALID boxes of a part read from STEP pass the sampling check: the real SolidWorks part of
// ../shared/cad, read in metres and tessellated at the default deflection, solved as the programs
// solve it (mesh semantics "auto": a tessellation that is not a clean closed solid is a triangle
// soup), one facet of each kind of surface, run to completion and stopped by a box budget; each
// checked box's random poses and 64 corners evaluated plainly and by sight lines cast against
// every triangle of the tessellation. What is certified is the tessellation (docs/step.md).
#include "solver_support.hpp"

#include <certipose/io/json.hpp>
#include <certipose/io/read_step.hpp>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

using namespace solver_test;

namespace {

/// The facets of face kind `surface`, those facing up most first (normal z, then index).
std::vector<std::size_t> upward_facets_of(const step_part& p, const std::string& surface) {
    std::vector<std::size_t> out;
    for (const auto& face : p.cad.faces.faces)
        if (face.surface == surface) out.insert(out.end(), face.facets.begin(), face.facets.end());
    std::sort(out.begin(), out.end(), [&](std::size_t a, std::size_t b) {
        const double za = p.mesh.facet(a).normal.z(), zb = p.mesh.facet(b).normal.z();
        return za != zb ? za > zb : a < b;
    });
    return out;
}

}  // namespace

TEST_CASE("soundness: VALID boxes of a STEP part's facets, completed and budget-stopped, pass the sampling check") {
    const step_part p = read_step(std::string(CERTIPOSE_SHARED_CAD) + "/featuretype.STEP");
    const auto camera = read_camera_task(std::string(CERTIPOSE_SOURCE_DIR) + "/examples/data/camera.json");
    const pose_solver<with_camera<calibrated_camera>> solver(p.mesh, camera.calibrated(), camera.task, {.semantics = mesh_semantics::automatic});
    std::uint32_t seed = 51;
    std::size_t checked = 0;
    for (const std::string surface : {"plane", "cylinder", "bspline"}) {
        CAPTURE(surface);
        // The first upward facet of this kind that the camera certifies at all (a facet at the
        // bottom of a bore may have no VALID box), run to completion, then stopped by a box
        // budget of half its boxes.
        const solve_options complete{.position_eps = 0.1, .orientation_eps = 0.38};
        std::size_t facet = p.mesh.num_faces();
        solve_result<boost_interval> full;
        for (const std::size_t f : upward_facets_of(p, surface)) {
            full = solver.solve(f, complete);
            if (full.stats.valid > 0) {
                facet = f;
                break;
            }
        }
        REQUIRE(facet < p.mesh.num_faces());
        CAPTURE(facet);
        solve_options stopped = complete;
        stopped.max_boxes = full.boxes.size() / 2;
        const auto cut = solver.solve(facet, stopped);
        CHECK(cut.stats.reason == termination::box_budget);
        const std::array<const solve_result<boost_interval>*, 2> runs{&full, &cut};
        for (const auto* r : runs) {
            const sampling_report rep = check_valid_boxes(*r, p.mesh, solver.camera(), solver.range(),
                                                          camera.task.min_view_angle, 2, seed++, true, 150);
            MESSAGE(surface << " facet " << facet << std::string(r == &cut ? " (box budget)" : "") << ": "
                            << r->stats.valid << " VALID, " << rep.valid_boxes << " checked, " << rep.samples
                            << " poses, " << rep.violations << " violations");
            CHECK(rep.violations == 0);
            checked += rep.valid_boxes;
        }
    }
    CHECK(checked > 0);  // the check checked something
}
