// One whole solve in the CGAL suite: the debug preset runs this suite under ASan + UBSan with
// assertions on (the solver suite runs in Release only, where compiling the pipelines once more
// would not fit CI's time), so the default pipeline — its paving, inner contraction, occlusion
// cuts, corner boxes and orientation stage, header-only here — is exercised sanitized too.
#include "dirty_scene.hpp"
#include "solver_support.hpp"

#include <certipose/io/box_store.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/run_journal.hpp>
#include <certipose/part/part_solver.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <variant>

using namespace solver_test;

TEST_CASE("one solve: the case study's VALID boxes pass the sampling check, corners included") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(part().mesh, camera, task);
    const auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    REQUIRE(r.stats.reason == termination::completed);
    REQUIRE(r.stats.valid > 50);
    CHECK(r.stats.inner_pieces + r.stats.occlusion_pieces + r.stats.corner_boxes > 0);
    const auto rep = check_valid_boxes(r, part().mesh, camera, solver.range(), task.min_view_angle, 4, 5, true, 60);
    MESSAGE("case study: " << r.stats.valid << " VALID; " << rep.samples << " poses checked, " << rep.violations
                           << " violations");
    CHECK(rep.violations == 0);
}

TEST_CASE("a refinement that completes both passes, sanitized: the issue's angle_block command") {
    // certipose-solve --mesh angle_block.off --scale 0.186104 --facet 520 --camera camera_wide.json
    //   --position-eps 0.4 --orientation-eps 0.38 --refine 400 --max-boxes 4000000
    // Its second pass starts from the first pass's states; they once held shadows from a cache
    // the first pass's paver had freed (ASan: heap-use-after-free), and certified occluded poses.
    const std::string shared = CERTIPOSE_SHARED_MESHES;
    const auto in = read_camera_task(shared + "/../cases/camera_wide.json");
    const auto camera = std::get<thin_lens_camera>(in.camera);
    const auto mesh = read_mesh(shared + "/angle_block.off", {.scale = 0.186104});
    const pose_solver<> solver(mesh, camera, in.task);
    solve_options o{.position_eps = 0.4, .orientation_eps = 0.38, .max_boxes = 4'000'000};
    o.refine = refinement{.time_limit = std::chrono::seconds(400)};
    const auto r = solver.solve(520, o);
    REQUIRE(r.stats.reason == termination::completed);
    CHECK(r.stats.refinement_passes == 2);
    REQUIRE(r.stats.valid > 1000);
    const auto rep = check_valid_boxes(r, mesh, camera, solver.range(), in.task.min_view_angle, 4, 7, true, 400);
    MESSAGE("refined angle_block: " << r.stats.valid << " VALID; " << rep.samples << " poses checked, "
                                    << rep.violations << " violations");
    CHECK(rep.violations == 0);
}

TEST_CASE("a placement tolerance with a fixed plate, grown and budget-stopped, sanitized") {
    // The placement stage (erode and restore, bisection), the fixed-occluder proof and growth
    // under the tolerance, header-only under ASan + UBSan; VALID boxes sampled against the moved
    // part (the plate stays).
    const thin_lens_camera camera(design_camera_parameters());
    const triangle_mesh plate = read_mesh(std::string(CERTIPOSE_SOURCE_DIR) + "/examples/data/fixture_plate.off");
    const std::array<triangle_mesh, 1> fixed{plate};
    inspection_task task{.min_view_angle = 0.35};
    task.placement = placement_tolerance{.translation = {0.003, 0.003, 0.003}, .rotation = 0.0175};
    const pose_solver<> solver(part().mesh, camera, task, {.occluders = fixed});
    solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
    o.grow = growth_options{};
    const auto r = solver.solve(part().facet_of_interest, o);
    REQUIRE(r.stats.valid > 20);
    CHECK(r.stats.placement_split > 0);
    const auto rep = check_placed(r, part().mesh, camera, solver.range(), task.min_view_angle, *solver.placement(), fixed, 1,
                                  2, 9, 40);
    MESSAGE("case study under ±3 mm, 1° on a fixed plate: " << r.stats.valid << " VALID; " << rep.samples
                                                             << " poses under motions, " << rep.violations << " violations");
    CHECK(rep.violations == 0);
    o.max_boxes = 300;  // stopped in the position stage: what is left undecided is BOUNDARY, never VALID
    const auto cut = solver.solve(part().facet_of_interest, o);
    CHECK(cut.stats.reason == termination::box_budget);
    const auto cut_rep = check_placed(cut, part().mesh, camera, solver.range(), task.min_view_angle, *solver.placement(),
                                      fixed, 1, 2, 10, 40);
    CHECK(cut_rep.violations == 0);
}

TEST_CASE("a dirty mesh read as a triangle soup, sanitized: the survey, skipped facets, completed and budget-stopped") {
    // Overlapping bodies, a face-to-face contact, a duplicated shell and an open sheet
    // (tests/dirty_scene.hpp): the survey, then the piercer's top (next to the overlap) and the prism's top solved
    // with the default paving, completed and stopped by the box budget, every VALID box checked
    // with sight lines cast against the whole soup and no box corner inside material.
    const auto& s = dirty_test::scene();
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(dirty_test::mesh(), camera, task, pose_solver<>::setup{.semantics = mesh_semantics::automatic});
    REQUIRE(solver.occlusion().semantics() == mesh_semantics::soup);
    CHECK(solver.occlusion().survey()->buried == 2);
    CHECK(solver.solve(s.piercer, {.position_eps = 0.4, .orientation_eps = 0.38}).stats.valid == 0);  // buried
    std::size_t checked = 0;
    for (std::size_t f : {s.piercer + 2, s.prism})
        for (std::size_t budget : {std::size_t{0}, std::size_t{200}}) {
            solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
            if (budget) o.max_boxes = budget;
            const auto r = solver.solve(f, o);
            CHECK(r.stats.valid > 0);
            const auto rep = check_valid_boxes(r, dirty_test::mesh(), camera, solver.range(), task.min_view_angle, 2, 7, true, 20);
            CHECK(rep.violations == 0);
            checked += rep.valid_boxes;
            for (const auto& cb : r.boxes)
                if (cb.cls == box_class::valid)
                    for (const Eigen::Vector3d& c : position_corners(cb.box.position))
                        CHECK_FALSE(dirty_test::inside_closed_body(c));
        }
    MESSAGE("dirty mesh, sanitized: " << checked << " VALID boxes checked");
}

TEST_CASE("reuse between translates in a part run, sanitized: completed and stopped by the run's box budget") {
    // Four bottom facets of the sample part, one shape and nothing in front of them: the first
    // is paved, the others take its boxes, each proven again (part/translates.hpp); then the
    // same run stopped by its box budget after the third facet. Every VALID box is checked.
    const thin_lens_camera camera(design_camera_parameters());
    const part_solver<> whole(part().mesh, camera, {.min_view_angle = 0.35});
    for (const std::optional<std::size_t> budget : {std::optional<std::size_t>{}, std::optional<std::size_t>{10000}}) {
        CAPTURE(budget.has_value());
        part_options o;
        o.facet = {.position_eps = 0.1, .orientation_eps = 0.38};
        o.facets = {2, 6, 10, 14};
        o.threads = 2;
        o.keep_boundary = true;
        o.max_boxes = budget;
        collecting_sink<boost_interval> sink;
        const part_result r = whole.solve(o, sink);
        CHECK(r.reused == (budget ? 2u : 3u));
        CHECK(sink.outcomes.size() == (budget ? 3u : 4u));
        std::size_t checked = 0;
        for (const auto& out : sink.outcomes) {
            CAPTURE(out.record.index);
            CHECK(out.record.reused_from == (out.record.index == 2 ? std::nullopt : std::optional<std::size_t>(2)));
            const auto rep = check_valid_boxes(as_result(out.record.index, out.boxes, out.record.valid), part().mesh,
                                               camera, whole.solver().range(), 0.35, 1,
                                               static_cast<std::uint32_t>(out.record.index), true, 25);
            CHECK(rep.valid_boxes > 0);
            CHECK(rep.violations == 0);
            checked += rep.valid_boxes;
        }
        MESSAGE("reuse, sanitized: " << checked << " VALID boxes checked");
    }
}

TEST_CASE("a part run cut short and resumed through its journal, sanitized: the uninterrupted run's store") {
    // What certipose-part --resume does (io/run_journal.hpp), under ASan: a run whose process dies
    // after a checkpoint (the journal destroyed without commit), with a torn journal line and
    // junk after the store's last checkpoint, continued from the journal on the rest of the
    // selection, gives the uninterrupted run's boxes.cpbx byte for byte.
    namespace fs = std::filesystem;
    using I = boost_interval;
    const thin_lens_camera camera(design_camera_parameters());
    const part_solver<> whole(part().mesh, camera, {.min_view_angle = 0.35});
    part_options o;
    o.facet = {.position_eps = 0.4, .orientation_eps = 0.38};
    o.facets = {0, 300, 600, 900, 1200, 1500, 1800, 2100};
    o.threads = 2;
    const nlohmann::json key = {{"settings", {{"position_eps", 0.4}}}};
    const std::vector<std::string> stores{"boxes.cpbx"};
    const fs::path dir = fs::temp_directory_path() / ("certipose-journal-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const auto solve_into = [&](part_run_journal& j, const part_options& opts) {
        auto store = box_store_sink<I>::append_to(j.store("boxes.cpbx"), true);
        j.checkpoint();
        journal_sink<box_store_sink<I>> sink{&store, &j};
        const part_result r = whole.solve(opts, sink);
        store.finish();
        return r;
    };

    {  // uninterrupted
        part_run_journal j = part_run_journal::start(dir / "full", key, stores);
        REQUIRE(solve_into(j, o).reason == termination::completed);
        j.commit("{}\n");
    }
    CHECK_FALSE(fs::exists(dir / "full" / part_run_journal::folder_name));
    {  // dies after a checkpoint of 3 facets
        part_run_journal j = part_run_journal::start(dir / "cut", key, stores);
        part_options cut = o;
        cut.progress = [&](const part_progress& p) {
            if (p.facets_done < 3) return true;
            j.checkpoint();
            return false;
        };
        REQUIRE(solve_into(j, cut).reason == termination::cancelled);
    }  // no commit: the folder stays, as after SIGKILL
    const fs::path unfinished = dir / "cut" / part_run_journal::folder_name;
    {
        std::ofstream(unfinished / "journal", std::ios::app | std::ios::binary) << "0123abcd {\"facets\":[{\"ind";
        std::ofstream(unfinished / "boxes.cpbx", std::ios::app | std::ios::binary) << std::string(777, '\x5a');
    }
    CHECK_THROWS_WITH_AS(
        [&] {
            std::optional<part_run_journal> other;
            (void)part_run_journal::resume(dir / "cut", {{"settings", {{"position_eps", 0.2}}}}, stores, other);
        }(),
        doctest::Contains("settings.position_eps: 0.4 in the run, 0.2 here"), certipose::invalid_argument);
    std::optional<part_run_journal> j;
    REQUIRE(part_run_journal::resume(dir / "cut", key, stores, j) == part_run_journal::found::unfinished);
    REQUIRE(j->done().facets.size() == 3);
    CHECK(j->done().facets[2].index == 600);
    part_options rest = o;
    rest.facets.erase(rest.facets.begin(), rest.facets.begin() + 3);
    REQUIRE(solve_into(*j, rest).reason == termination::completed);
    j->commit("{}\n");
    const auto bytes = [](const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const std::string full = bytes(dir / "full" / "boxes.cpbx");
    CHECK(full.size() > box_store_layout::header_bytes + 100 * box_store_layout::record_bytes);
    CHECK(bytes(dir / "cut" / "boxes.cpbx") == full);
    CHECK_FALSE(fs::exists(unfinished));
    fs::remove_all(dir);
}
