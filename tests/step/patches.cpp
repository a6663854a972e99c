// Patches of a STEP part's CAD faces (part/patches.hpp): a patch never spans two faces, and the
// boxes every member receives pass the sampling check against that member — the programs'
// pipeline on the real SolidWorks part of ../shared/cad, completed and budget-stopped. In the
// debug preset this runs under ASan + UBSan.
#include "solver_support.hpp"

#include <certipose/io/json.hpp>
#include <certipose/io/read_step.hpp>
#include <certipose/part/part_solver.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace solver_test;

TEST_CASE("patches: a STEP part's CAD faces as patches, every member's boxes pass the sampling check") {
    const step_part p = read_step(std::string(CERTIPOSE_SHARED_CAD) + "/featuretype.STEP");
    const auto camera = read_camera_task(std::string(CERTIPOSE_SOURCE_DIR) + "/examples/data/camera.json");
    const part_solver<with_camera<calibrated_camera>> whole(p.mesh, camera.calibrated(), camera.task,
                                                            {.semantics = mesh_semantics::automatic});
    part_options o;
    o.facet = {.position_eps = 0.1, .orientation_eps = 0.38};
    o.threads = 2;
    o.patches.enabled = true;
    o.patches.faces = p.cad.faces.face_of;
    const auto regions = whole.patches(o);
    REQUIRE(regions);
    // No region spans two CAD faces.
    std::map<std::uint32_t, std::uint32_t> face_of_region;
    for (std::size_t f = 0; f < p.mesh.num_faces(); ++f) {
        const auto [it, added] = face_of_region.try_emplace(regions->region_of[f], p.cad.faces.face_of[f]);
        CHECK(it->second == p.cad.faces.face_of[f]);
    }
    // The facets of the first faces of each kind with at least 4 upward facets (normal z > 0.3).
    for (const std::string surface : {"plane", "cylinder", "bspline"}) {
        for (const auto& face : p.cad.faces.faces) {
            if (face.surface != surface) continue;
            std::vector<std::size_t> up;
            for (std::size_t f : face.facets)
                if (p.mesh.facet(f).normal.z() > 0.3) up.push_back(f);
            if (up.size() < 4) continue;
            o.facets.insert(o.facets.end(), up.begin(), up.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(up.size(), 12)));
            break;
        }
    }
    REQUIRE(o.facets.size() >= 8);
    collecting_sink<boost_interval> full;
    const part_result r = whole.solve(o, full);
    REQUIRE(r.reason == termination::completed);
    part_options stopped = o;
    stopped.max_boxes = std::max<std::size_t>(1, r.valid / 2);
    collecting_sink<boost_interval> cut;
    const part_result rc = whole.solve(stopped, cut);
    CHECK(rc.reason == termination::box_budget);
    std::uint32_t seed = 5300;
    for (const auto* run : {&full, &cut}) {
        std::size_t members = 0, samples = 0, violations = 0;
        for (const auto& out : run->outcomes) {
            if (!out.record.patch || out.boxes.empty()) continue;
            CHECK(p.cad.faces.face_of[out.record.index] == p.cad.faces.face_of[*out.record.patch]);
            ++members;
            const auto rep = check_valid_boxes(as_result(out.record.index, out.boxes, out.record.valid), p.mesh,
                                               whole.solver().camera(), whole.solver().range(),
                                               camera.task.min_view_angle, 2, seed++, true, 10);
            samples += rep.samples;
            violations += rep.violations;
        }
        MESSAGE(std::string(run == &full ? "completed" : "budget-stopped") << ": " << (run == &full ? r : rc).patched << " of " << o.facets.size()
                                                                        << " facets patched; " << members << " checked, "
                                                                        << samples << " poses, " << violations
                                                                        << " violations");
        CHECK(members >= 2);
        CHECK(violations == 0);
    }
}
