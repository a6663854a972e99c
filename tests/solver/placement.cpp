// Part placement tolerance (pose/placement_tolerance.hpp, solver/placement_stage.hpp): every VALID
// box of a run with a tolerance is sampled against the part MOVED by motions the tolerance admits
// (the mesh is moved and ray cast against; fixed occluders stay), box corners included, with
// the independent checker (verify/point_check.hpp). And the check sees what the feature fixes: a
// run without the tolerance fails it once the part moves.
#include "solver_support.hpp"

#include <certipose/coverage/candidates.hpp>
#include <certipose/coverage/inspect_boxes.hpp>
#include <certipose/coverage/inspection.hpp>
#include <certipose/io/json.hpp>

#include <Eigen/Geometry>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

using namespace solver_test;

namespace {

using I = boost_interval;
using case_solver = pose_solver<with_camera<calibrated_camera>>;

std::string shared_path(const std::string& rest) {
    return std::filesystem::weakly_canonical(std::string(CERTIPOSE_SHARED_MESHES) + "/" + rest).string();
}

struct placed_case {
    const char* mesh;
    double scale;
    std::size_t facet;
    const char* camera;
};

constexpr placed_case reference_cases[] = {
    {"idler_riser.off", 0.0994878, 102, "camera.json"},
    {"featuretype.off", 0.0694832, 3262, "camera.json"},
    {"angle_block.off", 0.186104, 520, "camera_wide.json"},
    {"plate_holes.off", 0.00109127, 7, "camera.json"},
};

/// ±3 mm, ±0.02 rad about the part's centroid: the motion the issue measured breaking the
/// nominal boxes of featuretype.
placement_tolerance issue_tolerance() { return {.translation = {0.003, 0.003, 0.003}, .rotation = 0.02}; }

}  // namespace

TEST_CASE("placement reach: every camera position in the part frame and every moved vertex is inside the grown boxes") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    // 200 random boxes and facets, 50 admitted motions each (every other one extreme).
    const auto sample = [&](const resolved_placement& tol) {
        std::size_t checked = 0;
        for (int trial = 0; trial < 200; ++trial) {
            position_box<I> p;
            for (std::size_t i = 0; i < 3; ++i) {
                const double a = -1 + 2 * u(rng), w = 0.2 * u(rng);
                p[i] = I(a, a + w);
            }
            const position_box<I> q = camera_reach(p, tol);
            const std::array<Eigen::Vector3d, 3> v{Eigen::Vector3d(u(rng), u(rng), u(rng)), Eigen::Vector3d(u(rng), u(rng), u(rng)),
                                                   Eigen::Vector3d(u(rng), u(rng), u(rng))};
            const auto r = facet_reach<I>(v, tol);
            for (int k = 0; k < 50; ++k) {
                const motion m = draw_motion(tol, rng, k % 2 == 0);
                Eigen::Vector3d x;
                for (int i = 0; i < 3; ++i) x[i] = lower(p[static_cast<std::size_t>(i)]) + u(rng) * width(p[static_cast<std::size_t>(i)]);
                const Eigen::Vector3d back = m.R.transpose() * (x - m.c - m.t) + m.c;  // M⁻¹ x
                for (std::size_t i = 0; i < 3; ++i) CHECK(contains(q[i], back[static_cast<Eigen::Index>(i)]));
                for (const auto& y : v)
                    for (std::size_t i = 0; i < 3; ++i)
                        CHECK(std::abs(m(y)[static_cast<Eigen::Index>(i)] - y[static_cast<Eigen::Index>(i)]) <= r[i]);
                ++checked;
            }
        }
        return checked;
    };
    const resolved_placement tol = resolve({.translation = {0.003, 0.001, 0.005}, .rotation = 0.035, .datum = Eigen::Vector3d(0.1, -0.2, 0.05)},
                                           Eigen::Vector3d::Zero());
    CHECK(tol.datum == Eigen::Vector3d(0.1, -0.2, 0.05));
    CHECK(sample(tol) == 10000);
    // The fixture form: a turn about a tilted axis and a small tip.
    const resolved_placement fixture = resolve({.translation = {0.002, 0.001, 0.0005}, .rotation = 0.03,
                                                .axis = Eigen::Vector3d(0.2, -0.1, 1.0), .tilt = 0.002,
                                                .datum = Eigen::Vector3d(0.1, -0.2, 0.05)},
                                               Eigen::Vector3d::Zero());
    CHECK(sample(fixture) == 10000);
    {
        // About z with no tilt: z reaches only T_z, x and y the turn across; any-axis: every axis the whole turn.
        const resolved_placement plate = resolve({.translation = {0.002, 0.002, 0.0}, .rotation = 0.01, .axis = Eigen::Vector3d(0, 0, 1)},
                                                 Eigen::Vector3d::Zero());
        const resolved_placement any = resolve({.translation = {0.002, 0.002, 0.0}, .rotation = 0.01}, Eigen::Vector3d::Zero());
        const std::array<Eigen::Vector3d, 3> high{Eigen::Vector3d(0.1, 0, 0.3), Eigen::Vector3d(0.1, 0.01, 0.3),
                                                  Eigen::Vector3d(0.11, 0, 0.3)};
        const auto rp = facet_reach<I>(high, plate), ra = facet_reach<I>(high, any);
        CHECK(rp[2] == 0.0);  // exactly: a facet resting on the plate must not reach into it
        CHECK(ra[2] > 0.003);  // 0.01 rad at ~0.32 m
        CHECK(rp[0] < ra[0]);
        CHECK(rp[0] <= 0.002 + 0.01 * 0.1101);
    }
    // Bad values are refused, naming the field.
    const placement_tolerance negative{.translation = {0.001, -0.001, 0}}, degrees{.rotation = 2.0},
        not_a_number{.rotation = std::nan("")};
    CHECK_THROWS_WITH_AS(negative.validate(), doctest::Contains("translation along y must be >= 0"), certipose::invalid_argument);
    CHECK_THROWS_WITH_AS(degrees.validate(), doctest::Contains("got 2 (degrees? give radians)"), certipose::invalid_argument);
    CHECK_THROWS_AS(not_a_number.validate(), certipose::invalid_argument);
    const placement_tolerance tilt_alone{.rotation = 0.01, .tilt = 0.001}, zero_axis{.rotation = 0.01, .axis = Eigen::Vector3d::Zero()},
        tilt_degrees{.rotation = 0.01, .axis = Eigen::Vector3d::UnitZ(), .tilt = 3.0};
    CHECK_THROWS_WITH_AS(tilt_alone.validate(), doctest::Contains("a tilt goes with an axis"), certipose::invalid_argument);
    CHECK_THROWS_WITH_AS(zero_axis.validate(), doctest::Contains("finite non-zero direction"), certipose::invalid_argument);
    CHECK_THROWS_WITH_AS(tilt_degrees.validate(), doctest::Contains("(degrees? give radians)"), certipose::invalid_argument);
}

TEST_CASE("placement: a run without the tolerance fails the moved-part check, one with it passes (featuretype, facet 3262)") {
    const placed_case c = reference_cases[1];
    const auto in = read_camera_task(shared_path("../cases/" + std::string(c.camera)));
    const triangle_mesh mesh = read_mesh(shared_path(c.mesh), {.scale = c.scale});
    inspection_task task = in.task;
    const case_solver nominal(mesh, in.calibrated(), task);
    task.placement = issue_tolerance();
    const case_solver placed(mesh, in.calibrated(), task);
    REQUIRE(placed.placement());
    const resolved_placement tol = *placed.placement();
    const solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};

    const auto before = nominal.solve(c.facet, o);
    const auto broken = check_placed(before, mesh, nominal.camera(), nominal.range(), task.min_view_angle, tol, {}, 2, 2, 11);
    MESSAGE("without the tolerance: " << before.stats.valid << " VALID, " << broken.samples << " poses under motions, "
                                      << broken.violations << " violations (" << broken.occluded << " occluded, " << broken.fov
                                      << " out of the image, " << broken.position << " distance or angle)");
    CHECK(broken.violations > 0);

    const auto after = placed.solve(c.facet, o);
    const auto ok = check_placed(after, mesh, placed.camera(), placed.range(), task.min_view_angle, tol, {}, 2, 2, 12);
    MESSAGE("with it: " << after.stats.valid << " VALID (" << after.stats.placement_split << " nominal boxes split, "
                        << after.boundary_because(boundary_reason::placement) << " pieces left BOUNDARY placement), "
                        << ok.samples << " poses, " << ok.violations << " violations");
    CHECK(after.stats.valid > 0);
    CHECK(ok.valid_boxes == after.stats.valid);
    CHECK(ok.violations == 0);
}

TEST_CASE("placement soundness: the reference cases and the case study, default / paper paving / refined+grown / budget-stopped") {
    struct run {
        const char* mode;
        solve_options options;
    };
    std::vector<run> runs;
    runs.push_back({"default", {.position_eps = 0.1, .orientation_eps = 0.38}});
    {
        solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
        o.paving = paper_paving{};
        runs.push_back({"paper paving", o});
    }
    {
        solve_options o{.position_eps = 0.4, .orientation_eps = 0.38};
        o.refine = refinement{};
        o.grow = growth_options{};
        runs.push_back({"refined and grown", o});
    }
    {
        solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
        o.max_boxes = 400;
        runs.push_back({"box budget", o});
    }
    std::size_t total_boxes = 0, total_samples = 0, total_violations = 0;
    std::uint32_t seed = 1000;
    const auto one = [&](const std::string& label, const triangle_mesh& mesh, const calibrated_camera& camera,
                         inspection_task task, std::size_t facet) {
        task.placement = issue_tolerance();
        const case_solver solver(mesh, camera, task);
        for (const auto& [mode, options] : runs) {
            const auto r = solver.solve(facet, options);
            const auto rep = check_placed(r, mesh, solver.camera(), solver.range(), task.min_view_angle, *solver.placement(), {},
                                          1, 2, seed++, 150);
            MESSAGE(label << " | " << std::string(mode) << ": " << r.stats.valid << " VALID, " << rep.valid_boxes << " checked, " << rep.samples
                          << " poses, " << rep.violations << " violations; placement split " << r.stats.placement_split
                          << ", left " << r.boundary_because(boundary_reason::placement) << " BOUNDARY placement; "
                          << r.stats.seconds << " s");
            CHECK(rep.violations == 0);
            total_boxes += rep.valid_boxes, total_samples += rep.samples, total_violations += rep.violations;
        }
    };
    for (const auto& c : reference_cases) {
        const auto in = read_camera_task(shared_path("../cases/" + std::string(c.camera)));
        const triangle_mesh mesh = read_mesh(shared_path(c.mesh), {.scale = c.scale});
        one(c.mesh, mesh, in.calibrated(), in.task, c.facet);
    }
    one("case study", part().mesh, calibrated(thin_lens_camera(design_camera_parameters())), inspection_task{.min_view_angle = 0.35},
        part().facet_of_interest);
    MESSAGE("placement matrix: " << total_boxes << " VALID boxes checked, " << total_samples << " poses under motions, "
                                 << total_violations << " violations");
    CHECK(total_boxes > 0);
}

TEST_CASE("placement with a fixed occluder: the fixture plate stays while the part moves") {
    // The sample part on a plate that does not move with it (examples/data/fixture_plate.off).
    const triangle_mesh plate = read_mesh(std::string(CERTIPOSE_SOURCE_DIR) + "/examples/data/fixture_plate.off");
    const std::array<triangle_mesh, 1> fixed{plate};
    inspection_task task{.min_view_angle = 0.35};
    task.placement = placement_tolerance{.translation = {0.003, 0.003, 0.0}, .rotation = 0.01};
    const case_solver solver(part().mesh, calibrated(thin_lens_camera(design_camera_parameters())), task,
                             {.occluders = fixed});
    REQUIRE(solver.placement_proofs());
    CHECK(solver.placement_proofs()->fixed.triangles.size() == plate.num_faces());
    std::size_t checked = 0;
    std::uint32_t seed = 77;
    // The facet of interest and the three lowest side facets a camera is certified for under the
    // tolerance (their sight lines pass low over the plate, which the moving part comes close
    // to). A side facet reaching down to the plate gets none: sight_region_clear cannot separate
    // the plate from where such a facet may move, so the test looks from 4 mm up.
    std::vector<std::size_t> facets{part().facet_of_interest}, sides;
    for (std::size_t i = 0; i < part().mesh.num_faces(); ++i)
        if (std::abs(part().mesh.facet(i).normal.z()) < 0.1 && part().mesh.facet(i).bbox.min().z() > 0.004) sides.push_back(i);
    std::sort(sides.begin(), sides.end(), [&](std::size_t a, std::size_t b) {
        return part().mesh.facet(a).bbox.min().z() < part().mesh.facet(b).bbox.min().z();
    });
    for (std::size_t i : sides) {
        if (facets.size() == 4) break;
        if (solver.solve(i, {.position_eps = 0.1, .orientation_eps = 0.38}).stats.valid > 0) facets.push_back(i);
    }
    MESSAGE("lowest side facets certified: " << facets[1] << " (z from " << part().mesh.facet(facets[1]).bbox.min().z()
                                            << " m), " << facets[2] << ", " << facets[3]);
    REQUIRE(facets.size() == 4);
    for (std::size_t facet : facets) {
        const auto r = solver.solve(facet, {.position_eps = 0.1, .orientation_eps = 0.38});
        const auto rep = check_placed(r, part().mesh, solver.camera(), solver.range(), task.min_view_angle, *solver.placement(),
                                      fixed, 1, 2, seed++, 60);
        MESSAGE("facet " << facet << ": " << r.stats.valid << " VALID, " << rep.samples << " poses, " << rep.violations
                         << " violations");
        CHECK(rep.violations == 0);
        checked += rep.valid_boxes;
    }
    CHECK(checked > 0);
}

TEST_CASE("placement, fixture form: the part slides, turns about the plate's normal and tips a little, the plate stays") {
    // The tolerance of a part on a fixture plate (--part-axis 0,0,1 --part-tilt): ±3 mm across
    // the plate, ±0.02 rad about its normal, 1 mrad of tip. The facet of interest and the three
    // lowest side facets certified under it (down to 0.5 mm over the plate, where the any-axis
    // form needs 4 mm), completed and budget-stopped, sampled against motions of that form (box
    // corners against extreme ones) with the plate in place.
    const triangle_mesh plate = read_mesh(std::string(CERTIPOSE_SOURCE_DIR) + "/examples/data/fixture_plate.off");
    const std::array<triangle_mesh, 1> fixed{plate};
    inspection_task task{.min_view_angle = 0.35};
    task.placement = placement_tolerance{.translation = {0.003, 0.003, 0.0}, .rotation = 0.02,
                                         .axis = Eigen::Vector3d::UnitZ(), .tilt = 0.001};
    const case_solver solver(part().mesh, calibrated(thin_lens_camera(design_camera_parameters())), task,
                             {.occluders = fixed});
    REQUIRE(solver.placement());
    REQUIRE(solver.placement()->axis);
    std::vector<std::size_t> facets{part().facet_of_interest}, sides;
    for (std::size_t i = 0; i < part().mesh.num_faces(); ++i)
        if (std::abs(part().mesh.facet(i).normal.z()) < 0.1 && part().mesh.facet(i).bbox.min().z() > 0.0005) sides.push_back(i);
    std::sort(sides.begin(), sides.end(), [&](std::size_t a, std::size_t b) {
        return part().mesh.facet(a).bbox.min().z() < part().mesh.facet(b).bbox.min().z();
    });
    for (std::size_t i : sides) {
        if (facets.size() == 4) break;
        if (solver.solve(i, {.position_eps = 0.1, .orientation_eps = 0.38}).stats.valid > 0) facets.push_back(i);
    }
    REQUIRE(facets.size() == 4);
    MESSAGE("lowest side facets certified under the fixture form: " << facets[1] << " (z from "
                                                                     << part().mesh.facet(facets[1]).bbox.min().z() << " m), "
                                                                     << facets[2] << ", " << facets[3]);
    std::size_t checked = 0;
    std::uint32_t seed = 91;
    for (std::size_t facet : facets)
        for (const std::size_t budget : {std::size_t{0}, std::size_t{300}}) {
            solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
            if (budget) o.max_boxes = budget;
            const auto r = solver.solve(facet, o);
            const auto rep = check_placed(r, part().mesh, solver.camera(), solver.range(), task.min_view_angle, *solver.placement(),
                                          fixed, 1, 2, seed++, 60);
            MESSAGE("facet " << facet << std::string(budget ? " (budget-stopped)" : "") << ": " << r.stats.valid << " VALID, " << rep.samples
                             << " poses, " << rep.violations << " violations");
            CHECK(rep.violations == 0);
            checked += rep.valid_boxes;
        }
    CHECK(checked > 0);
}

TEST_CASE("placement, fixture form without tilt: side facets resting on the plate keep boxes, sight lines ending on it") {
    // Sliding and turning on the plate only (no tilt, no motion along its normal): a facet that
    // rests on the plate is not moved into it, so its sight lines may end where the plate's top
    // touches it (sight_region_clear lets a triangle touch the targets' side, the camera strictly
    // beyond). The lowest side facets, those reaching down to z = 0 among them, completed and
    // budget-stopped, sampled with the plate in place; the any-axis form gets none of them.
    const triangle_mesh plate = read_mesh(std::string(CERTIPOSE_SOURCE_DIR) + "/examples/data/fixture_plate.off");
    const std::array<triangle_mesh, 1> fixed{plate};
    inspection_task task{.min_view_angle = 0.35}, any_axis = task;
    task.placement = placement_tolerance{.translation = {0.002, 0.002, 0.0}, .rotation = 0.01, .axis = Eigen::Vector3d::UnitZ()};
    any_axis.placement = placement_tolerance{.translation = {0.002, 0.002, 0.0}, .rotation = 0.01};
    const auto camera = calibrated(thin_lens_camera(design_camera_parameters()));
    const case_solver solver(part().mesh, camera, task, {.occluders = fixed});
    const case_solver any_solver(part().mesh, camera, any_axis, {.occluders = fixed});
    std::vector<std::size_t> resting;
    for (std::size_t i = 0; i < part().mesh.num_faces(); ++i)
        if (std::abs(part().mesh.facet(i).normal.z()) < 0.1 && part().mesh.facet(i).bbox.min().z() == 0.0) resting.push_back(i);
    REQUIRE(!resting.empty());
    const solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
    std::vector<std::size_t> kept;
    std::size_t any_kept = 0;
    for (std::size_t i : resting) {
        if (kept.size() == 3) break;
        if (solver.solve(i, o).stats.valid > 0) {
            kept.push_back(i);
            any_kept += any_solver.solve(i, o).stats.valid > 0;
        }
    }
    MESSAGE(resting.size() << " side facets rest on the plate; certified under the fixture form: " << kept.size()
                           << " of the first tried, under any axis: " << any_kept);
    REQUIRE(kept.size() == 3);
    CHECK(any_kept == 0);
    std::size_t checked = 0;
    std::uint32_t seed = 131;
    for (std::size_t facet : kept)
        for (const std::size_t budget : {std::size_t{0}, std::size_t{300}}) {
            solve_options b = o;
            if (budget) b.max_boxes = budget;
            const auto r = solver.solve(facet, b);
            const auto rep = check_placed(r, part().mesh, solver.camera(), solver.range(), task.min_view_angle, *solver.placement(),
                                          fixed, 2, 2, seed++, 60);
            MESSAGE("facet " << facet << std::string(budget ? " (budget-stopped)" : "") << ": " << r.stats.valid << " VALID, "
                             << rep.samples << " poses, " << rep.violations << " violations");
            CHECK(rep.violations == 0);
            checked += rep.valid_boxes;
        }
    CHECK(checked > 0);
}

TEST_CASE("placement: a plan's tolerance boxes and every facet they certify, for every placement") {
    // As certipose-plan builds its candidates (tests/solver/soundness.cpp has the nominal twin):
    // VALID boxes of a run with the tolerance, cut to ±5 mm / ±0.02 rad about their centres (the
    // 4 largest, 2 on featuretype: each claim costs a moved copy of the part per pose); each
    // certifies its own facet and whatever inspect_boxes certifies besides, all under the
    // tolerance. Every such claim is sampled against the moved part. The case study and
    // featuretype (heavy self-occlusion).
    std::size_t claims = 0, samples = 0, violations = 0;
    const auto one = [&](const triangle_mesh& mesh, const calibrated_camera& camera, inspection_task task, std::size_t facet,
                         std::size_t count, std::uint32_t seed) {
        task.placement = placement_tolerance{.translation = {0.001, 0.001, 0.001}, .rotation = 0.0087};
        const case_solver solver(mesh, camera, task);
        const auto r = solver.solve(facet, {.position_eps = 0.1, .orientation_eps = 0.38});
        std::vector<pose_box<I>> boxes;
        for (const auto& b : r.boxes)
            if (b.cls == box_class::valid) boxes.push_back(around_centre(b.box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02}));
        std::sort(boxes.begin(), boxes.end(), [](const auto& x, const auto& y) { return volume(x.position) > volume(y.position); });
        if (boxes.size() > count) boxes.resize(count);
        REQUIRE(!boxes.empty());
        const inspection_run run = inspect_boxes(solver, boxes, {.threads = 1});
        REQUIRE(run.completed);
        for (std::size_t j = 0; j < boxes.size(); ++j) {
            std::vector<std::size_t> facets = run.coverage[j].certified;
            if (std::find(facets.begin(), facets.end(), facet) == facets.end()) facets.push_back(facet);
            for (const std::size_t fi : facets) {
                solve_result<I> claim;
                claim.facet_index = fi;
                claim.boxes.push_back({box_class::valid, boxes[j]});
                const auto rep = check_placed(claim, mesh, solver.camera(), solver.range(), task.min_view_angle,
                                              *solver.placement(), {}, 2, 1, seed + static_cast<std::uint32_t>(fi));
                ++claims, samples += rep.samples, violations += rep.violations;
            }
        }
    };
    one(part().mesh, calibrated(thin_lens_camera(design_camera_parameters())), inspection_task{.min_view_angle = 0.35},
        part().facet_of_interest, 4, 500);
    {
        const placed_case c = reference_cases[1];
        const auto in = read_camera_task(shared_path("../cases/" + std::string(c.camera)));
        const triangle_mesh mesh = read_mesh(shared_path(c.mesh), {.scale = c.scale});
        one(mesh, in.calibrated(), in.task, c.facet, 2, 900);
    }
    MESSAGE(claims << " (box, facet) claims of a plan's boxes sampled under motions: " << samples << " poses, " << violations
                   << " violations");
    CHECK(claims > 8);
    CHECK(violations == 0);
}

TEST_CASE("placement with a distorted lens, refined and grown: every mode combined") {
    // The tolerance, a strongly distorted lens (both signs) and the most complete mode together,
    // on the case study, every VALID box sampled against the moved part through the lens.
    std::size_t checked = 0;
    std::uint32_t seed = 4100;
    for (const brown_conrady& d : {brown_conrady{.k1 = 0.3, .k2 = 0.1}, brown_conrady{.k1 = -0.3}}) {
        inspection_task task{.min_view_angle = 0.35};
        task.placement = issue_tolerance();
        const calibrated_camera camera(distorted_camera(thin_lens_camera(design_camera_parameters()), d), "thin_lens");
        const case_solver solver(part().mesh, camera, task);
        solve_options o{.position_eps = 0.4, .orientation_eps = 0.38};
        o.refine = refinement{};
        o.grow = growth_options{};
        const auto r = solver.solve(part().facet_of_interest, o);
        const auto rep = check_placed(r, part().mesh, solver.camera(), solver.range(), task.min_view_angle, *solver.placement(),
                                      {}, 1, 2, seed++, 300);
        MESSAGE("k1 = " << d.k1 << ": " << r.stats.valid << " VALID, " << rep.samples << " poses, " << rep.violations
                        << " violations");
        CHECK(rep.violations == 0);
        checked += rep.valid_boxes;
    }
    CHECK(checked > 0);
}

TEST_CASE("placement: a ready occlusion policy is refused, its fixed occluders being unknown") {
    inspection_task task{.min_view_angle = 0.35};
    task.placement = issue_tolerance();
    case_solver::setup s;
    s.occlusion.emplace(part().mesh, std::span<const triangle_mesh>{});
    CHECK_THROWS_WITH_AS(case_solver(part().mesh, calibrated(thin_lens_camera(design_camera_parameters())), task, std::move(s)),
                         doctest::Contains("not a ready occlusion policy"), certipose::invalid_argument);
}
