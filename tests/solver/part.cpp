// The whole-part solver (part/part_solver.hpp): deterministic across thread counts, memory
// bounded by the facets in flight, cancellation that keeps exactly the finished facets, budgets
// that keep certified boxes, sound skips, and the sampling check over many facets of real meshes.
#include "solver_support.hpp"

#include <certipose/part/part_solver.hpp>
#include <certipose/part/selection.hpp>

#include <cmath>
#include <numeric>
#include <set>

using namespace solver_test;

namespace {

const thin_lens_camera& camera() {
    static const thin_lens_camera c(design_camera_parameters());
    return c;
}

part_options options_for(std::vector<std::size_t> facets, std::size_t threads) {
    part_options o;
    o.facet = {.position_eps = 0.1, .orientation_eps = 0.38};
    o.facets = std::move(facets);
    o.threads = threads;
    return o;
}

std::vector<std::size_t> every(std::size_t step, std::size_t n, std::size_t first = 0) {
    std::vector<std::size_t> v;
    for (std::size_t f = first; f < n; f += step) v.push_back(f);
    return v;
}

/// The volume of the distinct position boxes of the VALID boxes (stats.valid_volume's measure).
double position_volume(const std::vector<classified_box<boost_interval>>& boxes) {
    std::set<std::array<double, 6>> seen;
    double v = 0;
    for (const auto& b : boxes) {
        if (b.cls != box_class::valid) continue;
        const auto& p = b.box.position;
        if (seen.insert({lower(p[0]), upper(p[0]), lower(p[1]), upper(p[1]), lower(p[2]), upper(p[2])}).second)
            v += volume(p);
    }
    return v;
}

/// The 6D volume of the VALID boxes.
double pose_volume(const std::vector<classified_box<boost_interval>>& boxes) {
    double v = 0;
    for (const auto& b : boxes)
        if (b.cls == box_class::valid) v += volume(b.box.position) * volume(b.box.orientation);
    return v;
}

}  // namespace

TEST_CASE("part: the same facets, boxes and order with 1, 2 and 4 threads") {
    const part_solver<> whole(part().mesh, camera(), {.min_view_angle = 0.35});
    const auto facets = every(97, part().mesh.num_faces(), 5);
    std::vector<collecting_sink<boost_interval>> runs(3);
    std::vector<part_result> results;
    for (std::size_t k = 0; k < 3; ++k) {
        auto o = options_for(facets, std::size_t{1} << k);
        o.keep_boundary = true;
        results.push_back(whole.solve(o, runs[k]));
    }
    REQUIRE(runs[0].outcomes.size() == facets.size());
    for (std::size_t k = 1; k < 3; ++k) {
        CAPTURE(k);
        CHECK(results[k].reason == termination::completed);
        REQUIRE(runs[k].outcomes.size() == runs[0].outcomes.size());
        for (std::size_t i = 0; i < facets.size(); ++i) {
            const auto& a = runs[0].outcomes[i];
            const auto& b = runs[k].outcomes[i];
            CHECK(a.record.index == facets[i]);
            CHECK(b.record.index == facets[i]);
            REQUIRE(a.boxes.size() == b.boxes.size());
            for (std::size_t j = 0; j < a.boxes.size(); ++j) {
                CHECK(a.boxes[j].cls == b.boxes[j].cls);
                CHECK(a.boxes[j].reason == b.boxes[j].reason);
                for (std::size_t d = 0; d < 3; ++d) {
                    CHECK(lower(a.boxes[j].box.position[d]) == lower(b.boxes[j].box.position[d]));
                    CHECK(upper(a.boxes[j].box.position[d]) == upper(b.boxes[j].box.position[d]));
                    CHECK(lower(a.boxes[j].box.orientation[d]) == lower(b.boxes[j].box.orientation[d]));
                    CHECK(upper(a.boxes[j].box.orientation[d]) == upper(b.boxes[j].box.orientation[d]));
                }
            }
        }
    }
    // The part run gives each facet it paves on its own exactly what the single-facet solver
    // gives it (a facet that took a translate's boxes has its record say so: see the reuse test).
    std::size_t own = 0;
    while (own < facets.size() && runs[2].outcomes[own].record.reused_from) ++own;
    REQUIRE(own < facets.size());
    const auto single = whole.solver().solve(facets[own], options_for({}, 1).facet);
    CHECK(runs[2].outcomes[own].boxes.size() == single.boxes.size());
    CHECK(runs[2].outcomes[own].record.valid == single.stats.valid);
}

TEST_CASE("part: translate groups: congruent facets group from any first vertex, mirrored and other shapes do not") {
    // Four unit squares side by side, two triangles each; the last square lists its first
    // triangle from another vertex and its second one mirrored (the other normal).
    std::vector<Eigen::Vector3d> v;
    std::vector<face_indices> faces;
    for (std::uint32_t i = 0; i < 4; ++i) {
        const double x = 0.25 * i, jitter = i == 2 ? 3e-12 : 0.0;  // within the grid's quantum
        const auto a = static_cast<std::uint32_t>(v.size());
        v.insert(v.end(), {Eigen::Vector3d(x, 0, 0), Eigen::Vector3d(x + 0.25, 0, 0), Eigen::Vector3d(x + 0.25, 0.25 + jitter, 0),
                           Eigen::Vector3d(x, 0.25, 0)});
        if (i < 3) {
            faces.push_back({a, a + 1, a + 2});
            faces.push_back({a, a + 2, a + 3});
        } else {
            faces.push_back({a + 1, a + 2, a});
            faces.push_back({a, a + 3, a + 2});
        }
    }
    v.insert(v.end(), {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(2.5, 0, 0), Eigen::Vector3d(2.5, 0.25, 0)});
    faces.push_back({16, 17, 18});  // another shape
    const triangle_mesh m(v, faces);
    const translate_groups g = translate_groups::of(m);
    REQUIRE(g.group_of.size() == 9);
    for (std::size_t f : {2, 4, 6}) CHECK(g.group_of[f] == g.group_of[0]);
    CHECK(g.group_of[3] == g.group_of[1]);
    CHECK(g.group_of[5] == g.group_of[1]);
    CHECK(g.group_of[7] != g.group_of[1]);  // mirrored
    CHECK(g.group_of[8] != g.group_of[0]);
    CHECK(g.members[g.group_of[0]] == std::vector<std::size_t>{0, 2, 4, 6});
    CHECK(g.shared_group(0) == g.group_of[0]);
    CHECK(!g.shared_group(7));
    CHECK(!g.shared_group(8));
    CHECK(!g.shared_group(99));
}

TEST_CASE("part: reuse between translates: open facets take a translate's boxes, proven again, sound and as large") {
    const part_solver<> whole(part().mesh, camera(), {.min_view_angle = 0.35});
    const auto facets = every(11, part().mesh.num_faces(), 2);
    collecting_sink<boost_interval> on, off;
    auto o = options_for(facets, 2);
    const auto r_on = whole.solve(o, on);
    o.reuse.translates = false;
    const auto r_off = whole.solve(o, off);
    REQUIRE(on.outcomes.size() == facets.size());
    REQUIRE(off.outcomes.size() == facets.size());
    CHECK(r_off.reused == 0);
    CHECK(r_on.reused > facets.size() / 4);  // the bottom and the outer walls
    std::size_t reused = 0, checked = 0;
    double six_on = 0, six_off = 0;
    for (std::size_t i = 0; i < facets.size(); ++i) {
        const auto& a = on.outcomes[i];
        const auto& b = off.outcomes[i];
        CAPTURE(facets[i]);
        CHECK(!b.record.reused_from);
        if (!a.record.reused_from) {  // paved on its own: what the run without reuse gives
            CHECK(a.boxes.size() == b.boxes.size());
            continue;
        }
        ++reused;
        CHECK(*a.record.reused_from < a.record.index);  // the first open facet of its group
        CHECK(a.record.valid == a.boxes.size());
        // As large as its own paving: the same positions up to rounding; the orientations as
        // its template's, which differ from its own as any two translates' pavings do.
        const double pa = position_volume(a.boxes), pb = position_volume(b.boxes);
        CHECK(pa == doctest::Approx(pb).epsilon(0.01));
        six_on += pose_volume(a.boxes), six_off += pose_volume(b.boxes);
        if (checked < 6 + (i % 2)) {  // sampled poses, box corners included, with ray casting
            ++checked;
            const auto rep = check_valid_boxes(as_result(a.record.index, a.boxes, a.record.valid), part().mesh, camera(),
                                               whole.solver().range(), 0.35, 1, 17 + i, true, 120);
            CHECK(rep.samples > 0);
            CHECK(rep.violations == 0);
        }
    }
    CHECK(reused == r_on.reused);
    CHECK(checked >= 6);
    CHECK(six_on == doctest::Approx(six_off).epsilon(0.03));
    // A bad share is an error naming it.
    auto bad = o;
    bad.reuse.max_loss = 1.5;
    collecting_sink<boost_interval> none;
    try {
        whole.solve(bad, none);
        FAIL("no throw");
    } catch (const invalid_argument& e) {
        CHECK(e.field() == "reuse.max_loss");
        CHECK(std::string(e.what()).find("1.5") != std::string::npos);
    }
    CHECK(none.outcomes.empty());
    // A facet's boxes do not depend on the selection: alone, a reused facet gets the same.
    std::size_t k = 0;
    while (!on.outcomes[k].record.reused_from) ++k;
    collecting_sink<boost_interval> alone;
    o.reuse.translates = true;
    o.facets = {facets[k]};
    whole.solve(o, alone);
    REQUIRE(alone.outcomes.size() == 1);
    CHECK(alone.outcomes[0].record.reused_from == on.outcomes[k].record.reused_from);
    REQUIRE(alone.outcomes[0].boxes.size() == on.outcomes[k].boxes.size());
    for (std::size_t j = 0; j < alone.outcomes[0].boxes.size(); ++j)
        for (std::size_t d = 0; d < 3; ++d) {
            CHECK(lower(alone.outcomes[0].boxes[j].box.position[d]) == lower(on.outcomes[k].boxes[j].box.position[d]));
            CHECK(upper(alone.outcomes[0].boxes[j].box.orientation[d]) == upper(on.outcomes[k].boxes[j].box.orientation[d]));
        }
}

TEST_CASE("part: boxes stream to the sink, at most in_flight facets exist at once") {
    const part_solver<> whole(part().mesh, camera(), {.min_view_angle = 0.35});
    struct counting_sink {
        std::size_t facets = 0, boxes = 0, last = 0;
        bool ordered = true;
        void facet(const facet_outcome<boost_interval>& o) {
            ordered = ordered && (facets == 0 || o.record.index > last);
            last = o.record.index;
            ++facets;
            boxes += o.boxes.size();
        }
    } sink;
    auto o = options_for(every(23, part().mesh.num_faces()), 2);
    o.keep_boundary = true;
    o.in_flight = 3;
    const auto r = whole.solve(o, sink);
    CHECK(sink.ordered);
    CHECK(sink.facets == o.facets.size());
    CHECK(sink.boxes == r.valid + r.boundary);
    CHECK(sink.boxes > 50 * sink.facets);  // many boxes went by ...
    CHECK(r.peak_in_flight >= 1);
    CHECK(r.peak_in_flight <= 3);  // ... but never more than three facets' worth at once
}

TEST_CASE("part: the progress estimate weighs each facet by its search box, and ends at zero") {
    // part_progress::seconds_left = elapsed × (work left / work done), each facet's work its
    // contracted search box volume (part_solver::work_estimate); a facet no position can
    // inspect counts as little. With two equal halves done, the estimate is the elapsed time.
    const part_solver<> whole(part().mesh, camera(), {.min_view_angle = 0.35});
    for (std::size_t f : {std::size_t{0}, part().facet_of_interest}) CHECK(whole.work_estimate(f) > 0.0);
    const std::vector<std::size_t> two{part().facet_of_interest, part().facet_of_interest};
    const detail::work_meter meter(two, [&](std::size_t f) { return whole.work_estimate(f); });
    CHECK(meter.seconds_left(1, 3.0) == doctest::Approx(3.0));
    CHECK(meter.seconds_left(2, 3.0) == 0.0);
    CHECK(meter.seconds_left(0, 3.0) == 0.0);
    auto o = options_for(every(97, part().mesh.num_faces(), 0), 2);
    double last = -1.0;
    std::size_t calls = 0;
    o.progress = [&](const part_progress& p) {
        CHECK(std::isfinite(p.seconds_left));
        CHECK(p.seconds_left >= 0.0);
        last = p.seconds_left;
        ++calls;
        return true;
    };
    collecting_sink<boost_interval> sink;
    const auto r = whole.solve(o, sink);
    CHECK(calls == r.facets.size());
    CHECK(last == 0.0);
}

TEST_CASE("part: cancellation returns exactly the finished facets, as the full run has them") {
    const part_solver<> whole(part().mesh, camera(), {.min_view_angle = 0.35});
    const auto facets = every(41, part().mesh.num_faces(), 3);
    collecting_sink<boost_interval> full_sink, cut_sink;
    const auto full = whole.solve(options_for(facets, 2), full_sink);
    REQUIRE(full.reason == termination::completed);
    auto o = options_for(facets, 2);
    o.progress = [](const part_progress& p) {
        CHECK(p.facets_total > 0);
        CHECK(p.seconds >= 0.0);
        CHECK(std::isfinite(p.seconds_left));
        CHECK(p.seconds_left >= 0.0);
        return p.facets_done < 5;
    };
    const auto cut = whole.solve(o, cut_sink);
    CHECK(cut.reason == termination::cancelled);
    REQUIRE(cut.facets.size() == 5);
    REQUIRE(cut_sink.outcomes.size() == 5);
    for (std::size_t i = 0; i < 5; ++i) {
        CHECK(cut.facets[i].index == facets[i]);
        CHECK(cut.facets[i].termination == facet_termination::completed);
        CHECK(cut_sink.outcomes[i].record.valid == full_sink.outcomes[i].record.valid);
        CHECK(cut_sink.outcomes[i].boxes.size() == full_sink.outcomes[i].boxes.size());
    }
    // A stop requested before the run finishes nothing.
    std::stop_source stop;
    stop.request_stop();
    auto stopped = options_for(facets, 2);
    stopped.stop = stop.get_token();
    collecting_sink<boost_interval> none;
    const auto nothing = whole.solve(stopped, none);
    CHECK(nothing.facets.empty());
    CHECK(nothing.reason == termination::cancelled);
    // The run's box budget ends it after a deterministic prefix of facets.
    auto budget = options_for(facets, 2);
    budget.max_boxes = full.facets[0].valid + full.facets[0].boundary + 1;
    collecting_sink<boost_interval> two;
    const auto short_run = whole.solve(budget, two);
    CHECK(short_run.reason == termination::box_budget);
    CHECK(short_run.facets.size() == 2);
}

TEST_CASE("part: a facet that hits its budget keeps its certified VALID boxes, and they are sound") {
    const part_solver<> whole(part().mesh, camera(), {.min_view_angle = 0.35});
    auto o = options_for({part().facet_of_interest, 120, 1500}, 2);
    o.facet.max_boxes = 400;
    collecting_sink<boost_interval> sink;
    const auto r = whole.solve(o, sink);
    REQUIRE(sink.outcomes.size() == 3);
    std::size_t budget_hits = 0;
    for (const auto& out : sink.outcomes) {
        if (out.record.termination != facet_termination::box_budget) continue;
        ++budget_hits;
        CHECK(out.record.valid > 0);
        CHECK(out.record.boundary_reasons[static_cast<std::size_t>(boundary_reason::budget)] > 0);
        const auto rep = check_valid_boxes(as_result(out.record.index, out.boxes, out.record.valid), part().mesh,
                                           camera(), whole.solver().range(), 0.35, 20, 31);
        CHECK(rep.samples >= 20 * out.record.valid);
        CHECK(rep.violations == 0);
    }
    CHECK(budget_hits >= 1);
    CHECK(r.valid > 0);
}

TEST_CASE("part: facets no pose can inspect are skipped with the reason, and the solver agrees") {
    // A cube with 1.5 m edges: no face fits the case-study camera's image from within d_max = 0.77 m.
    std::vector<Eigen::Vector3d> v;
    for (int k = 0; k < 8; ++k) v.emplace_back(k & 1 ? 1.5 : 0.0, k & 2 ? 1.5 : 0.0, k & 4 ? 1.5 : 0.0);
    const triangle_mesh cube(v, {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}});
    const part_solver<with_occlusion<no_occlusion>> whole(cube, camera(), {.min_view_angle = 0.35});
    std::size_t skipped = 0, checked = 0;
    for (std::size_t f = 0; f < cube.num_faces(); ++f) {
        const auto why = whole.uninspectable(f);
        if (!why) continue;
        ++skipped;
        CHECK(why->find("larger than the image") != std::string::npos);
        if (checked < 5) {
            ++checked;
            CHECK(whole.solver().solve(f, {.position_eps = 0.1, .orientation_eps = 0.38}).stats.valid == 0);
        }
    }
    CHECK(skipped == cube.num_faces());
    collecting_sink<boost_interval> sink;
    const auto r = whole.solve(options_for({}, 2), sink);
    CHECK(r.skipped == skipped);
    for (const auto& rec : r.facets)
        if (rec.termination == facet_termination::skipped) {
            CHECK_FALSE(rec.reason.empty());
            CHECK(rec.valid == 0);
        }
    // The case-study facet is inspectable: it must not be skipped.
    const part_solver<> sample(part().mesh, camera(), {.min_view_angle = 0.35});
    CHECK_FALSE(sample.uninspectable(part().facet_of_interest));
}

TEST_CASE("part: facet selections parse and name what is wrong") {
    CHECK(parse_facet_selection("0,5,17-19,5", 100) == std::vector<std::size_t>{0, 5, 17, 18, 19});
    CHECK_THROWS_AS(parse_facet_selection("", 10), certipose::invalid_argument);
    CHECK_THROWS_AS(parse_facet_selection("3-1", 10), certipose::invalid_argument);
    CHECK_THROWS_AS(parse_facet_selection("1,x", 10), certipose::invalid_argument);
    try {
        (void)parse_facet_selection("2,10", 10);
        FAIL("an index out of range was accepted");
    } catch (const certipose::invalid_argument& e) {
        CHECK(std::string(e.what()).find("facet 10 is out of range") != std::string::npos);
    }
}

TEST_CASE("part: sampled poses in the VALID boxes of 50+ random facets of two real meshes are valid") {
    for (const char* name : {"idler_riser.off", "angle_block.off"}) {
        CAPTURE(name);
        const triangle_mesh mesh = rescaled_to_diagonal(read_mesh(std::string(CERTIPOSE_SHARED_MESHES) + "/" + name), 0.3);
        const part_solver<> whole(mesh, camera(), {.min_view_angle = 0.35});
        std::mt19937 rng(77);
        std::vector<std::size_t> facets(mesh.num_faces());
        std::iota(facets.begin(), facets.end(), 0);
        std::shuffle(facets.begin(), facets.end(), rng);
        facets.resize(50);
        collecting_sink<boost_interval> sink;
        const auto r = whole.solve(options_for(facets, 2), sink);
        REQUIRE(r.facets.size() == 50);
        std::size_t samples = 0, violations = 0, with_valid = 0;
        for (const auto& out : sink.outcomes) {
            if (out.boxes.empty()) continue;
            ++with_valid;
            solve_result<boost_interval> as_result;
            as_result.facet_index = out.record.index;
            as_result.boxes = out.boxes;
            // A random 40 of each facet's VALID boxes (corners included): the boxes since the
            // inner contraction are many and small, and every one is as likely to be checked.
            const auto rep = check_valid_boxes(as_result, mesh, camera(), whole.solver().range(), 0.35, 3, 40, true, 40);
            samples += rep.samples;
            violations += rep.violations;
        }
        MESSAGE(std::string(name) << ": 50 facets, " << with_valid << " with VALID boxes, " << r.skipped << " skipped, " << samples
                     << " sampled poses, " << violations << " violations");
        CHECK(with_valid >= 10);
        CHECK(samples >= 1000);
        CHECK(violations == 0);
    }
}

TEST_CASE("run_context: one token for the caller's stop and the run's own, the first reason kept") {
    std::stop_source caller;
    run_context run(caller.get_token(), std::chrono::hours(1));
    CHECK_FALSE(run.out_of_time());
    CHECK(run.reason() == termination::completed);
    CHECK(run.deadline().has_value());
    run.stop(termination::box_budget);
    run.stop(termination::cancelled);  // later reasons do not replace the first
    CHECK(run.token().stop_requested());
    CHECK(run.reason() == termination::box_budget);
    CHECK_FALSE(caller.stop_requested());  // the run's stop does not touch the caller's token

    std::stop_source user;
    const run_context cancelled(user.get_token());
    user.request_stop();
    CHECK(cancelled.token().stop_requested());
    CHECK(cancelled.reason() == termination::cancelled);
    const run_context late({}, std::chrono::steady_clock::duration(0));
    CHECK(late.past_deadline());
    CHECK(late.out_of_time());
    CHECK(late.reason() == termination::completed);  // a deadline is a reason once someone stops for it
}

TEST_CASE("part_schedule: the selection, the box budget in order, and what the sink sees") {
    part_options o;
    o.facets = {4, 2, 9};
    o.max_boxes = 5;
    const auto unit = [](std::size_t) { return 1.0; };
    part_schedule schedule(o, 10, unit);
    CHECK(schedule.selection() == std::vector<std::size_t>{4, 2, 9});
    collecting_sink<boost_interval> sink;
    std::vector<std::size_t> issued;
    while (const auto w = schedule.next()) {
        REQUIRE(schedule.plan().members(w->item).size() == 1);
        const std::size_t f = schedule.plan().members(w->item)[0];
        issued.push_back(f);
        facet_outcome<boost_interval> out;
        out.record.index = f;
        out.record.valid = 3;
        schedule.emit(sink, out);
    }
    // 3 + 3 boxes cross the budget of 5 after the second facet: the third is never handed out.
    CHECK(issued == std::vector<std::size_t>{4, 2});
    REQUIRE(sink.outcomes.size() == 2);
    const part_result r = schedule.finish(1);
    CHECK(r.reason == termination::box_budget);
    CHECK(r.valid == 6);
    CHECK(r.facets_selected == 3);
    CHECK(r.facets.size() == 2);

    part_options all;
    part_schedule every(all, 4, unit);
    CHECK(every.selection() == std::vector<std::size_t>{0, 1, 2, 3});
    part_options outside;
    outside.facets = {7};
    CHECK_THROWS_AS(part_schedule(outside, 4, unit), certipose::out_of_range);
    part_options zero;
    zero.max_boxes = 0;
    CHECK_THROWS_WITH_AS(part_schedule(zero, 4, unit), doctest::Contains("max_boxes"), certipose::invalid_argument);
}
