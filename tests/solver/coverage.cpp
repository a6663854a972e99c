// Coverage and deployment (issue "certified coverage and camera deployment"): the certified facet
// set C(B) of a pose box holds for every pose in it (the single-facet certifier agrees, and
// sampled poses, box corners included, pass the plain evaluator and ray caster for every facet
// claimed), P(B) ⊇ C(B) and holds every facet a sampled pose really inspects, multi-facet
// spaces inspect all of their facets, and a plan's every claim passes the same check; greedy
// against the brute-force optimum on the sample part's candidates; thinning computes the
// inspector's C(B) and skips only candidates whose facet an inspected one certifies.
#include "solver_support.hpp"

#include <certipose/coverage/candidates.hpp>
#include <certipose/coverage/deployment.hpp>
#include <certipose/coverage/inspect_boxes.hpp>
#include <certipose/coverage/inspection.hpp>
#include <certipose/coverage/multi_facet.hpp>
#include <certipose/coverage/thinning.hpp>
#include <certipose/geometry/triangle_mesh.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <stop_token>
#include <string>

using namespace solver_test;

namespace {

using I = boost_interval;
using inspector_type = facet_inspector<default_policies>;

struct claim_report {
    std::size_t boxes = 0, claims = 0, samples = 0, violations = 0;
};

/// Every facet of `facets` checked over `box` by sampling (corners included): the sampling check
/// of the solver tests, on a result holding `box` as its one VALID box.
void check_claims(claim_report& rep, const pose_solver<>& solver, const thin_lens_camera& camera, const pose_box<I>& box,
                  const std::vector<std::size_t>& facets, std::size_t per_box, std::uint32_t seed) {
    ++rep.boxes;
    for (std::size_t f : facets) {
        solve_result<I> one;
        one.facet_index = f;
        one.boxes.push_back({box_class::valid, box});
        const auto s = check_valid_boxes(one, solver.part(), camera, solver.range(), solver.task().min_view_angle, per_box,
                                         seed + static_cast<std::uint32_t>(f));
        ++rep.claims;
        rep.samples += s.samples;
        rep.violations += s.violations;
    }
}

/// Facets really inspected from an exact pose (plain evaluation and ray casting), by brute force.
std::vector<std::size_t> inspected_from(const triangle_mesh& mesh, const verify::pose& x, const verify::camera_view& view,
                                        double min_view_angle) {
    std::vector<std::size_t> out;
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
        const facet& fa = mesh.facet(f);
        if (verify::check_position(x.position, fa, view.d_min, view.d_max, min_view_angle).any()) continue;
        if (!verify::fov_ok(x, fa, view)) continue;
        const auto scene = verify::occluders::of(mesh, f);
        const auto targets = verify::facet_targets(fa);
        if (verify::check_position(x.position, fa, view.d_min, view.d_max, min_view_angle, &scene, targets).any()) continue;
        out.push_back(f);
    }
    return out;
}

pose_box<I> box_of(const std::array<std::array<double, 2>, 6>& b) {
    pose_box<I> out;
    for (std::size_t k = 0; k < 3; ++k) {
        out.position.x[k] = I(b[k][0], b[k][1]);
        out.orientation.x[k] = I(b[k + 3][0], b[k + 3][1]);
    }
    return out;
}

/// Plan candidates of the sample part: the `per_facet` largest VALID boxes of every `step`-th facet.
std::vector<candidate_box<I>> sample_candidates(const pose_solver<>& solver, std::size_t step, std::size_t per_facet) {
    candidate_pool<I> pool(per_facet);
    for (std::size_t f = 0; f < solver.part().num_faces(); f += step) {
        const auto r = solver.solve(f, {.position_eps = 0.1, .orientation_eps = 0.38});
        for (const auto& b : r.boxes)
            if (b.cls == box_class::valid) pool.add(f, b.box);
    }
    return pool.boxes();
}

struct coverage_case {
    std::string name;
    triangle_mesh mesh;
    std::size_t facet;
};

std::vector<coverage_case> coverage_cases() {
    std::vector<coverage_case> out;
    out.push_back({"sample part", part().mesh, part().facet_of_interest});
    for (const char* name : {"idler_riser.off", "featuretype.off"}) {
        triangle_mesh m = rescaled_to_diagonal(read_mesh(std::string(CERTIPOSE_SHARED_MESHES) + "/" + name), 0.3);
        const std::size_t f = upward_facet(m);
        out.push_back({name, std::move(m), f});
    }
    return out;
}

}  // namespace

TEST_CASE("C(B): every claimed facet is certified by the single-facet certifier and passes the sampling check") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    for (const auto& c : coverage_cases()) {
        CAPTURE(c.name);
        const pose_solver<> solver(c.mesh, camera, task);
        const auto r = solver.solve(c.facet, {.position_eps = 0.1, .orientation_eps = 0.38});
        candidate_pool<I> pool(6);
        for (const auto& b : r.boxes)
            if (b.cls == box_class::valid) pool.add(c.facet, b.box);
        const auto candidates = pool.boxes();
        REQUIRE(!candidates.empty());
        inspector_type inspector(solver);
        claim_report rep;
        std::size_t own = 0, disagreements = 0, lost = 0;
        // Each candidate whole, and cut to an installation tolerance (which certifies many more facets).
        std::vector<candidate_box<I>> boxes = candidates;
        for (const auto& cand : candidates)
            boxes.push_back({cand.facet, around_centre(cand.box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02})});
        for (const auto& cand : boxes) {
            const facet_coverage cov = inspector.inspect(cand.box);
            // P(B) ⊇ C(B), both sorted, areas the sums.
            CHECK(std::includes(cov.possible.begin(), cov.possible.end(), cov.certified.begin(), cov.certified.end()));
            CHECK(std::is_sorted(cov.certified.begin(), cov.certified.end()));
            double area = 0;
            for (std::size_t f : cov.certified) area += inspector.areas()[f];
            CHECK(cov.certified_area == doctest::Approx(area));
            CHECK(cov.possible_area >= cov.certified_area);
            own += std::binary_search(cov.certified.begin(), cov.certified.end(), c.facet);
            // The box is VALID for its facet: that facet is possible, whatever the proofs manage.
            CHECK(std::binary_search(cov.possible.begin(), cov.possible.end(), c.facet));
            for (std::size_t f : cov.certified) disagreements += !solver.certify(f, cand.box);
            // Nor does the inspector lose one: the facets it leaves in P(B) only (some refuted by a
            // single sight line, inspection.hpp) are not certified by the full proofs either.
            for (std::size_t f : cov.possible)
                if (!std::binary_search(cov.certified.begin(), cov.certified.end(), f)) lost += solver.certify(f, cand.box);
            check_claims(rep, solver, camera, cand.box, cov.certified, 4, 5);
        }
        MESSAGE(c.name << ": " << rep.boxes << " boxes, " << rep.claims << " facet claims, " << rep.samples << " samples, "
                       << rep.violations << " violations; own facet re-certified in " << own);
        CHECK(rep.violations == 0);
        CHECK(disagreements == 0);
        CHECK(lost == 0);
        // Not vacuous: the boxes of a facet certify some facets, more than one per box. (Not
        // necessarily their own: a VALID box merged from certified neighbours, or carved with
        // its parent's shadows, holds for its facet without one interval proof over all of it,
        // so neither the inspector nor pose_solver::certify may re-prove it; certipose-plan
        // adds a candidate's own facet from the run.)
        CHECK(rep.claims > rep.boxes);
    }
}

TEST_CASE("P(B) holds every facet that a sampled pose of B really inspects (the cull is sound)") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(part().mesh, camera, task);
    const auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    candidate_pool<I> pool(1);
    for (const auto& b : r.boxes)
        if (b.cls == box_class::valid) pool.add(part().facet_of_interest, b.box);
    REQUIRE(!pool.boxes().empty());
    const pose_box<I> valid = pool.boxes().front().box;
    // The VALID box and a much larger one around its centre (wide in every component).
    const auto m = midpoint(valid.as_6d());
    const pose_box<I> wide = box_of({{{m[0] - 0.08, m[0] + 0.08},
                                      {m[1] - 0.08, m[1] + 0.08},
                                      {m[2] - 0.08, m[2] + 0.08},
                                      {m[3] - 0.3, m[3] + 0.3},
                                      {std::max(0.0, m[4] - 0.3), m[4] + 0.3},
                                      {m[5] - 0.5, m[5] + 0.5}}});
    inspector_type inspector(solver);
    const verify::camera_view view{camera.intrinsics(), camera.width_px(), camera.height_px(), solver.range().min,
                                   solver.range().max};
    std::mt19937 rng(9);
    std::size_t poses = 0, inspected = 0, missing = 0;
    for (const pose_box<I>& b : {valid, wide}) {
        const facet_coverage cov = inspector.inspect(b);
        const auto draw = [&](const I& x) { return std::uniform_real_distribution<double>(lower(x), upper(x))(rng); };
        for (int k = 0; k < 6; ++k) {
            verify::pose x;
            for (int d = 0; d < 3; ++d) x.position[d] = draw(b.position[d]);
            x.phi = draw(b.orientation[0]), x.gamma = draw(b.orientation[1]), x.beta = draw(b.orientation[2]);
            const auto seen = inspected_from(part().mesh, x, view, task.min_view_angle);
            ++poses;
            inspected += seen.size();
            for (std::size_t f : seen) missing += !std::binary_search(cov.possible.begin(), cov.possible.end(), f);
        }
    }
    MESSAGE(poses << " sampled poses inspect " << inspected << " facets in all; " << missing << " missing from P(B)");
    CHECK(inspected > poses);  // not vacuous
    CHECK(missing == 0);
}

TEST_CASE("the largest box around a pose keeping its facets: contains the pose, every facet passes the sampling check") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(part().mesh, camera, task);
    const auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    candidate_pool<I> pool(3);
    for (const auto& b : r.boxes)
        if (b.cls == box_class::valid) pool.add(part().facet_of_interest, b.box);
    inspector_type inspector(solver);
    claim_report rep;
    std::size_t grown = 0;
    for (const auto& cand : pool.boxes()) {
        const auto m = midpoint(cand.box.as_6d());
        const std::array<double, 6> pose{m[0], m[1], m[2], m[3], m[4], m[5]};
        const pose_box<I> point = box_of({{{m[0], m[0]}, {m[1], m[1]}, {m[2], m[2]}, {m[3], m[3]}, {m[4], m[4]}, {m[5], m[5]}}});
        const auto facets = inspector.inspect(point).certified;
        if (facets.empty()) continue;
        const auto t = inspector.largest_box_keeping(pose, facets);
        REQUIRE(t.has_value());
        CHECK(contains(t->as_6d(), m));
        grown += volume(t->position) > 0;
        check_claims(rep, solver, camera, *t, facets, 12, 17);
    }
    MESSAGE(rep.boxes << " tolerance boxes, " << rep.claims << " facet claims, " << rep.samples << " samples, " << rep.violations
                      << " violations");
    CHECK(grown >= 1);
    CHECK(rep.violations == 0);
    CHECK_THROWS_AS(inspector.largest_box_keeping({0, 0, 0.5, std::nan(""), 0, 0}, {0}), invalid_argument);
    CHECK_THROWS_AS(inspector.largest_box_keeping({0, 0, 0.5, 0, 0, 0}, {part().mesh.num_faces()}), out_of_range);
}

TEST_CASE("multi-facet inspection spaces of adjacent coplanar facets inspect every facet of the set") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(part().mesh, camera, task);
    const triangle_mesh& mesh = part().mesh;
    // The facet of interest and its coplanar neighbours across an edge (the flat top surface).
    const std::size_t a = part().facet_of_interest;
    std::vector<std::size_t> neighbours;
    const auto& fa = mesh.faces()[a];
    for (std::size_t g = 0; g < mesh.num_faces() && neighbours.size() < 2; ++g) {
        if (g == a || mesh.facet(g).normal.dot(mesh.facet(a).normal) < 1 - 1e-9) continue;
        int shared = 0;
        for (auto u : mesh.faces()[g])
            for (auto v : fa) shared += u == v;
        if (shared == 2) neighbours.push_back(g);
    }
    REQUIRE(neighbours.size() >= 1);
    std::vector<std::vector<std::size_t>> sets{{a, neighbours[0]}};
    if (neighbours.size() >= 2) sets.push_back({a, neighbours[0], neighbours[1]});
    claim_report rep;
    for (const auto& s : sets) {
        CAPTURE(s.size());
        const auto space = multi_facet_space(solver, s, {.position_eps = 0.1, .orientation_eps = 0.38});
        MESSAGE(s.size() << " facets: " << space.size() << " boxes in their common inspection space");
        CHECK(!space.empty());
        for (std::size_t i = 0; i < space.size() && i < 25; ++i) check_claims(rep, solver, camera, space[i], s, 12, 31);
    }
    CHECK(rep.violations == 0);
    CHECK_THROWS_AS(multi_facet_space(solver, {}), invalid_argument);
}

TEST_CASE("intersections take the Euler angles modulo 2 pi, rounding the shifted bounds inward") {
    // A box given past φ = π (a user's box around φ = 3.15) meets one given near φ = −π.
    const pose_box<I> a = box_of({{{0, 1}, {0, 1}, {0, 1}, {3.0, 3.3}, {0.1, 0.5}, {-1, 1}}});
    const pose_box<I> b = box_of({{{0.5, 2}, {0.5, 2}, {0.5, 2}, {-3.2, -2.9}, {0.2, 0.9}, {-1, 1}}});
    const auto r = intersect_spaces(std::vector<pose_box<I>>{a}, std::vector<pose_box<I>>{b});
    REQUIRE(r.size() == 1);
    const double shifted = -3.2 + 2 * std::numbers::pi;
    CHECK(lower(r[0].orientation[0]) >= shifted);  // inward: never below the shifted bound
    CHECK(lower(r[0].orientation[0]) <= shifted + 1e-12);
    CHECK(upper(r[0].orientation[0]) == 3.3);
    CHECK(lower(r[0].orientation[1]) == 0.2);
    CHECK(upper(r[0].position[0]) == 1.0);
    // Disjoint positions: nothing.
    const pose_box<I> c = box_of({{{5, 6}, {0, 1}, {0, 1}, {2.5, 3}, {0.1, 0.5}, {-1, 1}}});
    CHECK(intersect_spaces(std::vector<pose_box<I>>{a}, std::vector<pose_box<I>>{c}).empty());
}

TEST_CASE("a deployment plan on the sample part: every claim of every camera passes the sampling check") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(part().mesh, camera, task);
    // Candidates: the largest VALID box of every 100th facet.
    const auto candidates = sample_candidates(solver, 100, 1);
    REQUIRE(candidates.size() >= 5);
    // Cut to an installation tolerance around their centres: sub-boxes, so still VALID.
    std::vector<pose_box<I>> boxes;
    for (const auto& c : candidates) {
        boxes.push_back(around_centre(c.box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02}));
        CHECK(subset(boxes.back().as_6d(), c.box.as_6d()));
        CHECK(width(boxes.back().position[0]) <= 0.01 + 1e-12);
    }
    CHECK_THROWS_AS(around_centre(boxes[0], {0.005, -1.0, 0.005, 0.02, 0.02, 0.02}), invalid_argument);
    const inspection_run run = inspect_boxes(solver, boxes, {.threads = 2});
    REQUIRE(run.completed);
    // The thread count does not change the answer.
    const inspection_run one = inspect_boxes(solver, boxes, {.threads = 1});
    // Without P(B)'s lists: the same C(B) and areas, no possible list.
    const inspection_run lean = inspect_boxes(solver, boxes, {.threads = 1, .possible_sets = false});
    for (std::size_t j = 0; j < boxes.size(); ++j) {
        CHECK(lean.coverage[j].certified == one.coverage[j].certified);
        CHECK(lean.coverage[j].possible.empty());
        CHECK(lean.coverage[j].possible_area == one.coverage[j].possible_area);
    }
    CHECK(lean.stats.occlusion_tests == one.stats.occlusion_tests);
    CHECK(one.stats.refuted_by_sight_line <= one.stats.occlusion_tests);
    std::vector<deployment_candidate> sets;
    for (std::size_t j = 0; j < boxes.size(); ++j) {
        CHECK(run.coverage[j].certified == one.coverage[j].certified);
        sets.push_back({run.coverage[j].certified});
    }
    inspector_type areas_of(solver);
    const deployment_plan plan = plan_greedy(sets, areas_of.areas(), {.coverage = 0.95});
    REQUIRE(!plan.chosen.empty());
    CHECK(plan.certified_area >= 0.95 * plan.coverable_area * (1 - 1e-9));
    CHECK(plan.lower_bound >= 1);
    CHECK(plan.lower_bound <= plan.chosen.size());
    // Greedy at k = 1, 2, 3 cameras against the brute-force optimum over these candidates.
    for (std::size_t k = 1; k <= 3; ++k) {
        double best = 0;
        const std::size_t n = sets.size();
        const auto area_of = [&](std::initializer_list<std::size_t> chosen) {
            std::vector<deployment_candidate> pick;
            for (std::size_t j : chosen) pick.push_back(sets[j]);
            return union_area(pick, areas_of.areas());
        };
        for (std::size_t a = 0; a < n; ++a) {
            if (k == 1) best = std::max(best, area_of({a}));
            for (std::size_t b = a + 1; k >= 2 && b < n; ++b) {
                if (k == 2) best = std::max(best, area_of({a, b}));
                for (std::size_t c = b + 1; k == 3 && c < n; ++c) best = std::max(best, area_of({a, b, c}));
            }
        }
        const deployment_plan g = plan_greedy(sets, areas_of.areas(), {.cameras = k});
        CAPTURE(k);
        CHECK(g.certified_area <= best * (1 + 1e-12));
        CHECK(g.certified_area >= (1 - 1 / std::exp(1.0)) * best);
        MESSAGE("k = " << k << ": greedy " << g.certified_area << " m^2, optimum " << best << " m^2");
    }
    claim_report rep;
    for (std::size_t j : plan.chosen) check_claims(rep, solver, camera, boxes[j], sets[j].facets, 4, 47);
    MESSAGE("plan: " << plan.chosen.size() << " of " << candidates.size() << " candidate boxes certify "
                     << 100 * plan.certified_area / plan.total_area << " % of the part (lower bound " << plan.lower_bound
                     << "); " << rep.claims << " claims, " << rep.samples << " samples, " << rep.violations << " violations");
    CHECK(rep.claims > 50 * plan.chosen.size());  // a tolerance box certifies many facets
    CHECK(plan.certified_area > 0.3 * plan.total_area);
    CHECK(rep.violations == 0);
}

TEST_CASE("thinning: the C(B) it computes are the inspector's, and every candidate's facet stays certified") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(part().mesh, camera, task);
    // Candidates: the two largest VALID boxes of every 50th facet, cut to a tolerance.
    std::vector<pose_box<I>> boxes;
    std::vector<std::size_t> facets;
    for (const auto& c : sample_candidates(solver, 50, 2)) {
        boxes.push_back(around_centre(c.box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02}));
        facets.push_back(c.facet);
    }
    REQUIRE(boxes.size() > 64);  // more than one round of the default size
    const inspection_run all = inspect_boxes(solver, boxes, {.threads = 2, .possible_sets = false});
    for (const std::size_t round : {std::size_t{1}, std::size_t{4}, std::size_t{64}}) {
        CAPTURE(round);
        const thinned_inspection t = inspect_thinned(solver, boxes, facets, {.round = round}, {.threads = 2, .possible_sets = false});
        REQUIRE(t.completed);
        CHECK(t.inspected_count == static_cast<std::size_t>(std::count(t.inspected.begin(), t.inspected.end(), char{1})));
        CHECK(t.inspected_count >= 1);
        // Neighbouring facets' candidates certify each other's facets: some are skipped.
        CHECK(t.inspected_count < boxes.size());
        for (std::size_t j = 0; j < boxes.size(); ++j) {
            CAPTURE(j);
            if (t.inspected[j]) {
                CHECK(t.coverage[j].certified == all.coverage[j].certified);
                continue;
            }
            CHECK(t.coverage[j].certified.empty());
            // Skipped: an inspected candidate certifies its facet (or is of the same facet).
            bool certified = false;
            for (std::size_t i = 0; i < boxes.size() && !certified; ++i)
                certified = t.inspected[i] && (facets[i] == facets[j] || std::binary_search(t.coverage[i].certified.begin(),
                                                                                            t.coverage[i].certified.end(), facets[j]));
            CHECK(certified);
        }
        // Which candidates are inspected depends on the rounds, not on the threads.
        const thinned_inspection one = inspect_thinned(solver, boxes, facets, {.round = round}, {.threads = 1, .possible_sets = false});
        CHECK(one.inspected == t.inspected);
    }
    // Without a candidate's own facet counting, and asking for more certifications than there
    // are candidates: every candidate is inspected.
    const thinned_inspection every =
        inspect_thinned(solver, boxes, facets, {.certified_by = boxes.size() + 1, .own_facet = false}, {.threads = 2});
    CHECK(every.inspected_count == boxes.size());
    // Stopped before the first round: nothing claimed.
    std::stop_source stop;
    stop.request_stop();
    const thinned_inspection stopped = inspect_thinned(solver, boxes, facets, {}, {.threads = 2, .stop = stop.get_token()});
    CHECK_FALSE(stopped.completed);
    for (const auto& c : stopped.coverage) CHECK(c.certified.empty());
    // Bad input is named.
    CHECK_THROWS_AS(inspect_thinned(solver, boxes, std::vector<std::size_t>(facets.size() - 1), {}), invalid_argument);
    std::vector<std::size_t> beyond = facets;
    beyond[0] = part().mesh.num_faces();
    CHECK_THROWS_AS(inspect_thinned(solver, boxes, beyond, {}), out_of_range);
    CHECK_THROWS_AS(inspect_thinned(solver, boxes, facets, {.round = 0}), invalid_argument);
    CHECK_THROWS_AS(inspect_thinned(solver, boxes, facets, {.certified_by = 0}), invalid_argument);
    CHECK_THROWS_AS(inspect_thinned(solver, boxes, facets, {.sample = 0}), invalid_argument);
}
