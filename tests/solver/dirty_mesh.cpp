// Dirty meshes (occlusion/mesh_survey.hpp, docs/occlusion.md#dirty-meshes): a synthetic CAD-like
// scene — a slab pierced by a box, a box with a prism sitting face to face on it, a duplicated
// shell and an open sheet — read as a triangle soup. The survey finds what is there; buried and
// covered facets are OCCLUDED from everywhere and skipped by the part solver; and every VALID
// box of the facets next to the overlap, the contact, the duplicate and the sheet passes the
// sampling check with sight lines cast against the full soup (box corners included), in every
// mode a user can select, with no camera position inside a closed body.
#include "dirty_scene.hpp"
#include "solver_support.hpp"

#include <certipose/coverage/candidates.hpp>
#include <certipose/coverage/inspection.hpp>
#include <certipose/io/json.hpp>
#include <certipose/occlusion/cgal_boolean_occlusion.hpp>
#include <certipose/occlusion/cgal_mesh_survey.hpp>
#include <certipose/part/part_solver.hpp>

#include <random>
#include <set>
#include <string>
#include <vector>

using namespace solver_test;
using namespace dirty_test;

namespace {

using I = boost_interval;

thin_lens_camera camera() { return thin_lens_camera(design_camera_parameters()); }

}  // namespace

TEST_CASE("the survey of a dirty mesh: bodies, seams, duplicates, overlaps, buried and covered facets") {
    const dirty_scene& s = scene();
    const mesh_survey sv = survey_mesh(mesh());
    CHECK(sv.faces == s.f.size());
    CHECK(sv.bodies == 5);             // slab, piercer, base+prism, doubled shell, sheet
    CHECK(sv.closed_bodies == 2);      // the slab and the piercer (the base+prism has 4-face edges)
    CHECK(sv.open_edges == 4);         // the sheet's rim
    CHECK(sv.nonmanifold_edges > 0);   // the base's top triangle, shared with the prism, and the doubled shell
    CHECK(sv.duplicate_faces == 13);   // the 12 repeated faces, and the prism's bottom (same vertices, turned)
    CHECK(sv.intersecting_pairs > 0);  // the piercer's walls through the slab's top
    // The piercer's bottom (faces 0 and 1 of it) lies inside the slab.
    CHECK(sv.hidden[s.piercer + 0] == hidden_facet::buried);
    CHECK(sv.hidden[s.piercer + 1] == hidden_facet::buried);
    CHECK(sv.buried == 2);
    // The slab's own faces are not buried: only the piercer pokes into them.
    for (std::size_t k = 0; k < 12; ++k) CHECK(sv.hidden[s.slab + k] == hidden_facet::none);
    // The base's top triangle and the prism's bottom face each other.
    CHECK(sv.hidden[s.base + 2] == hidden_facet::covered);
    CHECK(sv.hidden[s.prism + 1] == hidden_facet::covered);
    CHECK(sv.covered == 2);
    for (std::size_t k = 0; k < 12; ++k) {
        CHECK(sv.hidden[s.doubled + k] == hidden_facet::none);
        CHECK(sv.hidden[s.doubled_copy + k] == hidden_facet::duplicate);
        CHECK(sv.original[s.doubled_copy + k] == s.doubled + k);
    }
    CHECK(sv.why_hidden(s.doubled_copy)->find("duplicate of facet " + std::to_string(s.doubled)) != std::string::npos);
    CHECK(sv.why_hidden(s.piercer)->find("buried") != std::string::npos);
    CHECK_FALSE(sv.why_hidden(s.sheet));
    CHECK_FALSE(sv.clean());
    // Each kind found is named with an example.
    std::string all;
    for (const auto& e : sv.examples) all += e + "\n";
    CHECK(all.find("intersect") != std::string::npos);
    CHECK(all.find("one face (an open seam)") != std::string::npos);
    CHECK(all.find("same vertices") != std::string::npos);
    CHECK(all.find("buried inside the body of face " + std::to_string(s.slab)) != std::string::npos);

    // A clean solid has nothing to report.
    const mesh_survey clean = survey_mesh(part().mesh);
    CHECK(clean.clean());
    CHECK(clean.buried + clean.covered == 0);
}

TEST_CASE("dirty meshes: solid semantics refuses them and names the way out, soup and automatic accept them") {
    const dirty_scene& s = scene();
    const auto message = [](auto&& build) {
        try {
            build();
        } catch (const mesh_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string solid = message([&] { aabb_occlusion o(mesh()); });
    CHECK(solid.find("aabb_occlusion: part:") != std::string::npos);
    CHECK(solid.find("mesh_semantics::soup") != std::string::npos);
    CHECK(solid.find("--mesh-semantics soup") != std::string::npos);
    const std::string boolean = message([&] { boolean_occlusion o(mesh()); });
    CHECK(boolean.find("boolean_occlusion: part:") != std::string::npos);
    CHECK(boolean.find("needs closed, edge-manifold, self-intersection-free, outward-facing meshes") != std::string::npos);
    // The solver refuses the soup for a policy that reads solids only, naming the setting.
    using boolean_solver = pose_solver<with_occlusion<boolean_occlusion, with_camera<calibrated_camera>>>;
    CHECK_THROWS_WITH_AS(boolean_solver(mesh(), calibrated_camera(camera()), inspection_task{.min_view_angle = 0.35},
                                        boolean_solver::setup{.semantics = mesh_semantics::soup}),
                         doctest::Contains("reads closed solids only"), invalid_argument);

    const aabb_occlusion soup(mesh(), {}, mesh_semantics::soup);
    CHECK(soup.semantics() == mesh_semantics::soup);
    REQUIRE(soup.survey() != nullptr);
    CHECK(soup.why_not_solid().empty());
    const aabb_occlusion automatic(mesh(), {}, mesh_semantics::automatic);
    CHECK(automatic.semantics() == mesh_semantics::soup);
    CHECK(automatic.why_not_solid().find("not a closed manifold") != std::string::npos);
    // A clean solid stays a solid under `automatic`.
    const aabb_occlusion clean(part().mesh, {}, mesh_semantics::automatic);
    CHECK(clean.semantics() == mesh_semantics::solid);
    CHECK(clean.survey() == nullptr);

    // Buried and covered facets are OCCLUDED from everywhere, even from inside their body; a
    // duplicate is seen as its original (not hidden from the occlusion, only skipped).
    const Eigen::AlignedBox3d inside(Eigen::Vector3d(0.12, 0.12, 0.005), Eigen::Vector3d(0.18, 0.18, 0.015));
    CHECK(soup.classify(inside, s.piercer) == visibility::occluded);
    const Eigen::AlignedBox3d above(Eigen::Vector3d(0.42, 0.02, 0.5), Eigen::Vector3d(0.48, 0.08, 0.6));
    CHECK(soup.classify(above, s.base + 2) == visibility::occluded);
    CHECK(soup.hidden(s.base + 2).has_value());
    const Eigen::AlignedBox3d over_doubled(Eigen::Vector3d(0.42, 0.22, 0.5), Eigen::Vector3d(0.48, 0.28, 0.6));
    CHECK(soup.classify(over_doubled, s.doubled + 2) == visibility::visible);
    CHECK(soup.classify(over_doubled, s.doubled_copy + 2) == visibility::visible);
    // The prism's top is visible from above; the base's top is under the prism.
    CHECK(soup.classify(above, s.prism) == visibility::visible);
    // Nothing in a soup is "inside": a box behind a facet is PARTIAL, not OCCLUDED.
    const Eigen::AlignedBox3d below(Eigen::Vector3d(0.42, 0.02, -0.6), Eigen::Vector3d(0.48, 0.08, -0.5));
    CHECK(soup.classify(below, s.prism) == visibility::partial);
}

TEST_CASE("dirty meshes: the part solver skips buried, covered and duplicate facets with the reason") {
    const dirty_scene& s = scene();
    const part_solver<> whole(mesh(), camera(), inspection_task{.min_view_angle = 0.35},
                              part_solver<>::setup{.semantics = mesh_semantics::soup});
    part_options opt;
    opt.facet = {.position_eps = 0.4, .orientation_eps = 0.38, .max_boxes = 2000};
    opt.facets = {s.piercer, s.base + 2, s.prism + 1, s.doubled_copy + 2, s.doubled + 2};
    collecting_sink<I> sink;
    const part_result r = whole.solve(opt, sink);
    REQUIRE(r.facets.size() == 5);
    CHECK(r.facets[0].termination == facet_termination::skipped);
    CHECK(r.facets[0].reason.find("buried") != std::string::npos);
    CHECK(r.facets[1].reason.find("covered") != std::string::npos);
    CHECK(r.facets[2].reason.find("covered") != std::string::npos);
    CHECK(r.facets[3].reason == "a duplicate of facet " + std::to_string(s.doubled + 2) + " (same vertices, same orientation)");
    CHECK(r.facets[4].termination != facet_termination::skipped);
    CHECK(r.facets[4].valid > 0);
    CHECK(r.skipped == 4);
}

TEST_CASE("dirty meshes: a duplicated face counts no area in C(B), so a plan counts that surface once") {
    const dirty_scene& s = scene();
    const pose_solver<> solver(mesh(), camera(), inspection_task{.min_view_angle = 0.35},
                               pose_solver<>::setup{.semantics = mesh_semantics::soup});
    facet_inspector<> inspector(solver);
    REQUIRE(inspector.areas().size() == mesh().num_faces());
    for (std::size_t k = 0; k < 12; ++k) {
        CHECK(inspector.areas()[s.doubled + k] == mesh().facet(s.doubled + k).area);
        CHECK(inspector.areas()[s.doubled_copy + k] == 0.0);
    }
    // Above the doubled shell, looking down on its top: the original and its copy are both
    // certified (seen alike), their area once.
    const std::size_t top = s.doubled + 2, copy = s.doubled_copy + 2;
    const auto r = solver.solve(top, {.position_eps = 0.1, .orientation_eps = 0.38});
    std::size_t both = 0;
    for (const auto& b : r.boxes) {
        if (b.cls != box_class::valid) continue;
        // Cut to an installation tolerance, as a plan's candidates are (they certify more).
        const facet_coverage c = inspector.inspect(around_centre(b.box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02}));
        const bool has_top = std::binary_search(c.certified.begin(), c.certified.end(), top);
        const bool has_copy = std::binary_search(c.certified.begin(), c.certified.end(), copy);
        CHECK(has_top == has_copy);
        double area = 0;
        for (std::size_t f : c.certified)  // the copied shell's faces count nothing
            area += f >= s.doubled_copy && f < s.doubled_copy + 12 ? 0.0 : mesh().facet(f).area;
        CHECK(c.certified_area == doctest::Approx(area));
        both += has_top && has_copy;
    }
    CHECK(both > 0);
}

TEST_CASE("dirty meshes: every VALID box holds with sight lines cast against the whole soup, in every mode") {
    const dirty_scene& s = scene();
    const pose_solver<> solver(mesh(), camera(), inspection_task{.min_view_angle = 0.35},
                               pose_solver<>::setup{.semantics = mesh_semantics::automatic});
    // Next to the overlap (the slab's top, the piercer's walls and top), on the sheet (both
    // sides), the prism's top and walls, the doubled shell's top.
    // The slab's and the base's walls that face each other across the sheet see through the gaps.
    const std::vector<std::size_t> facets{s.slab + 2, s.slab + 3,  s.piercer + 2, s.piercer + 4, s.piercer + 10,
                                          s.sheet,    s.sheet + 1, s.prism,       s.prism + 2,   s.doubled + 3,
                                          s.slab + 10, s.base + 8};
    std::vector<solve_options> modes;
    modes.push_back({.position_eps = 0.1, .orientation_eps = 0.38});
    modes.push_back({.position_eps = 0.1, .orientation_eps = 0.38, .paving = paper_paving{}});
    modes.push_back({.position_eps = 0.1, .orientation_eps = 0.38, .max_boxes = 300});  // budget-stopped
    {
        solve_options o{.position_eps = 0.4, .orientation_eps = 0.38, .max_boxes = 400'000};
        o.refine = refinement{.min_width = 0.1};
        o.grow = growth_options{};
        modes.push_back(o);
    }
    std::size_t valid = 0, samples = 0, violations = 0, in_material = 0;
    std::uint32_t seed = 3601;
    for (std::size_t f : facets)
        for (const solve_options& o : modes) {
            CAPTURE(f);
            CAPTURE(o.position_eps);
            const auto r = solver.solve(f, o);
            const sampling_report rep =
                check_valid_boxes(r, mesh(), solver.camera(), solver.range(), 0.35, 2, seed++, true, 60);
            valid += rep.valid_boxes, samples += rep.samples, violations += rep.violations;
            CHECK(rep.violations == 0);
            for (const auto& cb : r.boxes) {
                if (cb.cls != box_class::valid) continue;
                for (const Eigen::Vector3d& c : position_corners(cb.box.position)) in_material += inside_closed_body(c);
            }
        }
    MESSAGE("dirty mesh: " << facets.size() << " facets x " << modes.size() << " modes, " << valid
                           << " VALID boxes checked, " << samples << " poses, " << violations << " violations, "
                           << in_material << " box corners inside material");
    CHECK(valid > 0);
    CHECK(violations == 0);
    CHECK(in_material == 0);
}

TEST_CASE("counter.off, a real CAD export read as a triangle soup: the sampling check on 200 facets") {
    // 83 750 triangles in six overlapping bodies (units mm). The sample: facets next to an
    // overlap (beside a face another body cuts), facets that look at another body (a ray along the
    // normal meets another body within d_max: their cameras see past or between bodies), and
    // random facets; every VALID box of each is checked with sight lines cast against the whole
    // soup (box corners included). Some of them also in the other modes.
    const std::string shared = CERTIPOSE_SHARED_MESHES;
    const triangle_mesh m = read_mesh(shared + "/counter.off", {.scale = 0.001});
    const auto in = read_camera_task(shared + "/../cases/camera.json");
    using solver_t = pose_solver<with_camera<calibrated_camera>>;
    const solver_t solver(m, in.calibrated(), in.task, solver_t::setup{.semantics = mesh_semantics::automatic});
    REQUIRE(solver.occlusion().semantics() == mesh_semantics::soup);
    const mesh_survey& sv = *solver.occlusion().survey();
    CHECK(sv.bodies == 6);
    CHECK(sv.intersecting_pairs == sv.intersecting.size());
    REQUIRE(sv.intersecting_pairs > 0);
    const std::size_t n = m.num_faces();
    const auto usable = [&](std::size_t f) { return sv.hidden[f] == hidden_facet::none; };

    // Bodies, as the survey counts them (faces sharing vertices).
    std::vector<std::uint32_t> parent(m.num_vertices());
    for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
    const auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& t : m.faces()) parent[find(t[1])] = find(t[0]), parent[find(t[2])] = find(t[0]);
    const auto body = [&](std::size_t f) { return find(m.faces()[f][0]); };

    std::mt19937 rng(36);
    std::vector<std::size_t> chosen;
    std::set<std::size_t> taken;
    const auto take = [&](std::size_t f) {
        if (usable(f) && taken.insert(f).second) chosen.push_back(f);
    };
    {  // next to an overlap: sharing a vertex with a face another body cuts, cut by none itself
        // (a face that is cut reaches into material and has no VALID box; its neighbours may)
        std::vector<char> cut(n, 0);
        for (const auto& [a, b] : sv.intersecting) cut[a] = cut[b] = 1;
        std::vector<std::vector<std::uint32_t>> around(m.num_vertices());
        for (std::size_t f = 0; f < n; ++f)
            for (auto v : m.faces()[f]) around[v].push_back(static_cast<std::uint32_t>(f));
        std::vector<std::size_t> next_to;
        for (std::size_t f = 0; f < n; ++f) {
            if (cut[f]) continue;
            bool near = false;
            for (auto v : m.faces()[f])
                for (auto g : around[v]) near = near || cut[g];
            if (near) next_to.push_back(f);
        }
        std::shuffle(next_to.begin(), next_to.end(), rng);
        for (std::size_t i = 0; i < next_to.size() && chosen.size() < 60; ++i) take(next_to[i]);
    }
    const std::size_t near_overlap = chosen.size();
    {  // looking at another body within d_max
        const double reach = solver.range().max;
        std::uniform_int_distribution<std::size_t> any(0, n - 1);
        for (int tries = 0; tries < 4000 && chosen.size() < near_overlap + 60; ++tries) {
            const std::size_t f = any(rng);
            if (!usable(f) || taken.count(f)) continue;
            const facet& fc = m.facet(f);
            const Eigen::Vector3d p = fc.centroid + 1e-6 * fc.normal, q = fc.centroid + reach * fc.normal;
            Eigen::AlignedBox3d seg(p);
            seg.extend(q);
            bool hits = false;
            for (std::size_t t = 0; t < n && !hits; ++t) {
                if (body(t) == body(f)) continue;
                const facet& o = m.facet(t);
                if (!seg.intersects(o.bbox)) continue;
                hits = verify::segment_hits_triangle(p, q, o.v);
            }
            if (hits) take(f);
        }
    }
    const std::size_t facing = chosen.size() - near_overlap;
    {  // random
        std::uniform_int_distribution<std::size_t> any(0, n - 1);
        while (chosen.size() < 200) take(any(rng));
    }
    MESSAGE("counter.off: " << near_overlap << " facets next to an overlap, " << facing
                            << " looking at another body, " << chosen.size() - near_overlap - facing << " random");
    CHECK(near_overlap == 60);
    CHECK(facing >= 20);

    std::size_t valid = 0, samples = 0, violations = 0, with_boxes = 0;
    std::array<std::size_t, 3> group_with_boxes{};
    std::uint32_t seed = 836;
    const auto check = [&](std::size_t f, const solve_options& o) {
        const auto r = solver.solve(f, o);
        const sampling_report rep =
            check_valid_boxes(r, m, solver.camera(), solver.range(), in.task.min_view_angle, 1, seed++, true, 12);
        valid += rep.valid_boxes, samples += rep.samples, violations += rep.violations;
        with_boxes += r.stats.valid > 0;
        CHECK_MESSAGE(rep.violations == 0, "facet " << f);
        return r.stats.valid > 0;
    };
    for (std::size_t i = 0; i < chosen.size(); ++i)
        if (check(chosen[i], {.position_eps = 0.1, .orientation_eps = 0.38}))
            ++group_with_boxes[i < near_overlap ? 0 : i < near_overlap + facing ? 1 : 2];
    // Other modes on a few of each kind: the paper's paving, a box budget, refinement with growth.
    for (std::size_t i : {0, 1, 2, 60, 61, 62, 120, 121}) {
        const std::size_t f = chosen[std::min(i, chosen.size() - 1)];
        check(f, {.position_eps = 0.1, .orientation_eps = 0.38, .paving = paper_paving{}});
        check(f, {.position_eps = 0.1, .orientation_eps = 0.38, .max_boxes = 300});
        solve_options o{.position_eps = 0.4, .orientation_eps = 0.38, .max_boxes = 200'000};
        o.refine = refinement{.min_width = 0.1};
        o.grow = growth_options{};
        check(f, o);
    }
    MESSAGE("counter.off: facets with VALID boxes: " << group_with_boxes[0] << " next to an overlap, " << group_with_boxes[1]
                                                    << " looking at another body, " << group_with_boxes[2] << " random");
    MESSAGE("counter.off: " << chosen.size() << " facets (" << with_boxes << " runs with VALID boxes), " << valid
                            << " VALID boxes checked, " << samples << " poses, " << violations << " violations");
    for (std::size_t g : group_with_boxes) CHECK(g >= 10);  // each kind has facets that are checked
    CHECK(violations == 0);
}

TEST_CASE("dirty meshes: an OCCLUDED answer in a soup holds: every sampled sight line is blocked") {
    // A wall above the facet, its triangle given twice with the same vertices: a rim found by
    // edges used once would be lost, and a wall certificate would call the box OCCLUDED though
    // sight lines pass beside the wall (x + y > 0.75 at the wall's height).
    const triangle_mesh walled({{1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {-1, -1, .5}, {1.75, -1, .5}, {-1, 1.75, .5}},
                               {{{0, 1, 2}}, {{3, 4, 5}}, {{3, 4, 5}}});
    const aabb_occlusion wall_soup(walled, {}, mesh_semantics::soup);
    const Eigen::AlignedBox3d over(Eigen::Vector3d(.3, .3, 1), Eigen::Vector3d(.31, .31, 1.01));
    CHECK(wall_soup.classify(over, 0) == visibility::partial);
    CHECK_FALSE(verify::occluders::of(walled, 0).blocks(Eigen::Vector3d(.305, .305, 1.005), Eigen::Vector3d(1, 0, 0) * 0.999));

    // Every OCCLUDED answer over a grid of boxes around the dirty scene, for facets that are not
    // hidden: 24 sight lines from random box points to random interior points of the facet, all
    // blocked (exact ray casting against the whole soup).
    const dirty_scene& s = scene();
    const aabb_occlusion soup(mesh(), {}, mesh_semantics::soup);
    std::mt19937 rng(3602);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t occluded = 0, lines = 0, free_lines = 0;
    for (std::size_t f : {s.slab + 2, s.slab + 10, s.piercer + 4, s.piercer + 6, s.sheet, s.base + 8, s.prism + 2,
                          s.doubled + 8, s.doubled_copy + 8}) {
        const facet& fc = mesh().facet(f);
        const auto scene_lines = verify::occluders::of(mesh(), f);
        for (int i = 0; i < 10; ++i)
            for (int j = 0; j < 10; ++j)
                for (int k = 0; k < 4; ++k) {
                    const Eigen::Vector3d lo(-0.3 + 0.12 * i, -0.3 + 0.12 * j, -0.1 + 0.1 * k);
                    const Eigen::AlignedBox3d box(lo, lo + Eigen::Vector3d(0.04, 0.04, 0.04));
                    if (soup.classify(box, f) != visibility::occluded) continue;
                    ++occluded;
                    for (int t = 0; t < 24; ++t) {
                        const Eigen::Vector3d p = lo + Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.04;
                        double a = u(rng), b = u(rng);
                        if (a + b > 1) a = 1 - a, b = 1 - b;
                        // Pulled 5 % towards the centroid: a point of the relative interior.
                        const Eigen::Vector3d q =
                            fc.centroid + 0.95 * ((1 - a - b) * fc.v[0] + a * fc.v[1] + b * fc.v[2] - fc.centroid);
                        ++lines;
                        if (!scene_lines.blocks(p, q)) {
                            ++free_lines;
                            if (free_lines <= 3) MESSAGE("free sight line from " << p.transpose() << " to facet " << f);
                        }
                    }
                }
    }
    MESSAGE("soup OCCLUDED answers: " << occluded << " boxes, " << lines << " sight lines, " << free_lines << " free");
    CHECK(occluded > 0);
    CHECK(free_lines == 0);
}

TEST_CASE("dirty meshes: a body resting on a facet with its own vertices covers it, and so its duplicates") {
    // A slab; a box standing on its top with vertices of its own (not welded), its footprint
    // holding the centroid of the slab's top face 2; and that face repeated (a duplicated shell
    // piece). The top face is covered (material in front), its duplicate with it; the slab's
    // other top face, whose centroid is beside the box, is not.
    dirty_scene s;
    s.slab = s.box({0, 0, 0}, {0.3, 0.3, 0.05});
    s.piercer = s.box({0.15, 0.05, 0.05}, {0.25, 0.15, 0.1});
    s.doubled_copy = s.f.size();
    s.f.push_back(s.f[s.slab + 2]);
    const triangle_mesh m(s.v, s.f);
    const mesh_survey sv = survey_mesh(m);
    CHECK(sv.hidden[s.slab + 2] == hidden_facet::covered);
    CHECK(sv.hidden[s.doubled_copy] == hidden_facet::covered);
    CHECK(sv.hidden[s.slab + 3] == hidden_facet::none);
    CHECK(sv.hidden[s.piercer + 0] == hidden_facet::none);  // the box's bottom: the slab is behind it
    const aabb_occlusion soup(m, {}, mesh_semantics::soup);
    const Eigen::AlignedBox3d inside_box(Eigen::Vector3d(0.18, 0.08, 0.06), Eigen::Vector3d(0.22, 0.12, 0.09));
    CHECK(soup.classify(inside_box, s.slab + 2) == visibility::occluded);
    CHECK(soup.classify(inside_box, s.doubled_copy) == visibility::occluded);
}
