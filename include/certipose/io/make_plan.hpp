// certipose/io/make_plan.hpp — a camera plan (PLAN.json's document) from candidate boxes: what
// certipose-plan does once it has its candidates, shared by the program and the Python module
// (docs/coverage.md).
//
// The steps: each candidate is cut down to the installation tolerance around its centre (a
// sub-box, so still certified for what the whole box is); C(B) of every cut candidate is computed
// (coverage/inspect_boxes.hpp), plus the candidate's own facet when the run that gave it is
// trusted to be of this very part; the plan is greedy maximum coverage (coverage/deployment.hpp),
// replaced by GLPK's exact answer when one with fewer cameras is proven within `exact_seconds`,
// with the best lower bound at hand (area, greedy, the LP relaxation within `lp_seconds`, or the
// exact optimum); the facets no chosen camera certifies are listed with the reason, read from the
// run's facet records. `check_part_run` refuses a run made for another mesh, camera, task or scene;
// `add_run_candidates` reads a checked run's boxes as candidates.
//
// GLPK is GPL: a program that includes this header links -lglpk (coverage/glpk_deployment.hpp).
#pragma once

#include "certipose/coverage/candidates.hpp"
#include "certipose/coverage/deployment.hpp"
#include "certipose/coverage/glpk_deployment.hpp"
#include "certipose/coverage/inspect_boxes.hpp"
#include "certipose/coverage/thinning.hpp"
#include "certipose/io/box_store.hpp"
#include "certipose/io/plan_export.hpp"
#include "certipose/io/plan_files.hpp"
#include "certipose/occlusion/mesh_survey.hpp"
#include "certipose/occlusion/resting_contact.hpp"
#include "certipose/part/part_solver.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace certipose {

namespace detail {
/// The same double, bit for bit (so both +inf, for an unbounded d_max): a run whose camera differs
/// in the last bit of d_min certified its boxes against other constraints, and the difference is
/// exactly where its box edges sit. summary.json round-trips every double (shortest digits written,
/// read back in round-to-nearest), so a run of this camera always compares equal.
inline bool same_double(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

/// The run's occluders and camera regions must be the plan's: a box certified without an occluder
/// may be hidden by it, and one restricted to other regions may stand where the plan forbids.
/// Occluders are compared by digest and scale (bit for bit), regions exactly, each list in any order.
inline void check_run_scene(const certipose::scene_record& run, const certipose::scene_record& here, const std::string& where) {
    const auto mismatch = [&](const std::string& what, const std::string& theirs, const std::string& ours) {
        throw certipose::invalid_argument(what, where + ": the run's " + what + " (" + theirs + ") is not this plan's (" + ours +
                                                    "): plan with the --occluder, --keep-in and --keep-out the run used");
    };
    using occluder = certipose::occluder_record;
    const auto occluder_key = [](const occluder& o) { return std::pair(o.digest, std::bit_cast<std::uint64_t>(o.scale)); };
    const auto occluders = [&](std::vector<occluder> list) {
        std::sort(list.begin(), list.end(), [&](const occluder& a, const occluder& b) { return occluder_key(a) < occluder_key(b); });
        return list;
    };
    const auto occluders_text = [](const std::vector<occluder>& list) {
        std::string s;
        for (const auto& o : list)
            s += (s.empty() ? "" : ", ") + o.path + ":" + certipose::detail::format_double(o.scale) + " digest " + o.digest;
        return s.empty() ? std::string("none") : s;
    };
    const auto a = occluders(run.occluders), b = occluders(here.occluders);
    if (!std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [&](const occluder& x, const occluder& y) { return occluder_key(x) == occluder_key(y); }))
        mismatch("occluders", occluders_text(run.occluders), occluders_text(here.occluders));
    const auto region_key = [](const certipose::camera_region& r) {
        std::array<std::uint64_t, 7> k{static_cast<std::uint64_t>(r.shape)};
        for (std::size_t i = 0; i < 6; ++i) k[i + 1] = std::bit_cast<std::uint64_t>(r.values[i]);
        return k;
    };
    const auto regions = [&](std::vector<certipose::camera_region> list) {
        std::sort(list.begin(), list.end(), [&](const auto& x, const auto& y) { return region_key(x) < region_key(y); });
        return list;
    };
    const auto regions_text = [](const std::vector<certipose::camera_region>& list) {
        std::string s;
        for (const auto& r : list) s += (s.empty() ? "" : " ") + certipose::to_string(r);
        return s.empty() ? std::string("none") : s;
    };
    for (const auto& [key, theirs, ours] : {std::tuple{"keep_in", &run.regions.keep_in, &here.regions.keep_in},
                                            std::tuple{"keep_out", &run.regions.keep_out, &here.regions.keep_out}}) {
        const auto x = regions(*theirs), y = regions(*ours);
        if (!std::equal(x.begin(), x.end(), y.begin(), y.end(),
                        [&](const auto& p, const auto& q) { return region_key(p) == region_key(q); }))
            mismatch(key, regions_text(*theirs), regions_text(*ours));
    }
}
}  // namespace detail

/// A whole-part run (its summary.json, read from `where`) must be of this mesh, camera and task,
/// with occlusion checked and the same occluders and camera regions: otherwise its boxes certify
/// something else. `here` holds the plan's records. Throws invalid_argument naming the first
/// field that differs, the run's value and the plan's.
inline void check_part_run(const part_summary& run, const part_summary& here, const std::string& where) {
    const auto mismatch = [&](const std::string& what, const std::string& theirs, const std::string& ours) {
        throw certipose::invalid_argument(what, where + ": the run's " + what + " (" + theirs + ") is not this plan's (" + ours +
                                                    "): plan with the mesh, --scale, --part-pose and camera the run used");
    };
    const auto text = [](double v) { return certipose::detail::format_double(v); };
    if (run.mesh.faces != here.mesh.faces)
        mismatch("mesh.faces", std::to_string(run.mesh.faces), std::to_string(here.mesh.faces));
    if (!detail::same_double(run.mesh.scale, here.mesh.scale)) mismatch("mesh.scale", text(run.mesh.scale), text(here.mesh.scale));
    if (run.mesh.pose != here.mesh.pose) {
        const auto pose_text = [](const std::optional<std::array<double, 16>>& m) {
            if (!m) return std::string("none");
            std::string s;
            for (std::size_t i = 0; i < 12; ++i) s += (i ? (i % 4 ? "," : ";") : "") + certipose::detail::format_double((*m)[i]);
            return s;
        };
        mismatch("mesh.pose", pose_text(run.mesh.pose), pose_text(here.mesh.pose));
    }
    if (!run.mesh.digest.empty() && run.mesh.digest != here.mesh.digest)
        mismatch("mesh.digest", run.mesh.digest, here.mesh.digest);
    const auto& a = run.camera;
    const auto& b = here.camera;
    if (!detail::same_double(a.width_px, b.width_px) || !detail::same_double(a.height_px, b.height_px))
        mismatch("camera size", text(a.width_px) + "x" + text(a.height_px), text(b.width_px) + "x" + text(b.height_px));
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (!detail::same_double(a.K[r][c], b.K[r][c])) mismatch("camera.K", text(a.K[r][c]), text(b.K[r][c]));
    // The lens: boxes certified through one distortion (or none) do not hold through another.
    const auto lens = [&](const auto& cam) {
        std::string s = "none";
        if (cam.distortion) {
            s.clear();
            for (double k : cam.distortion->opencv()) s += (s.empty() ? "" : ",") + text(k);
        }
        return s + ", margin " + text(cam.image_margin_px) + " px";
    };
    if (!(a.distortion == b.distortion) || !detail::same_double(a.image_margin_px, b.image_margin_px))
        mismatch("camera.distortion_coefficients", lens(a), lens(b));
    if (!detail::same_double(a.d_min, b.d_min) || !detail::same_double(a.d_max, b.d_max))
        mismatch("camera distance range", text(a.d_min) + ".." + text(a.d_max), text(b.d_min) + ".." + text(b.d_max));
    // The mount offset changes no box (they are of the projection centre), but the plan's mount
    // poses are computed with it: a run of another offset is another camera installation.
    if (a.mount_offset != b.mount_offset) {
        const auto point = [&](const std::array<double, 3>& p) { return "[" + text(p[0]) + ", " + text(p[1]) + ", " + text(p[2]) + "]"; };
        mismatch("camera.mount_offset", point(a.mount_offset), point(b.mount_offset));
    }
    if (!detail::same_double(run.task.min_view_angle, here.task.min_view_angle))
        mismatch("task.min_view_angle", text(run.task.min_view_angle), text(here.task.min_view_angle));
    // Boxes certified for another placement tolerance (or none) are not this plan's: fewer
    // placements than asked would be covered, or cameras lost to a tolerance not asked for.
    if (!(run.task.placement == here.task.placement)) {
        const auto tol = [&](const std::optional<certipose::placement_tolerance>& t) -> std::string {
            if (!t) return "none";
            std::string s = text(t->translation[0]) + "," + text(t->translation[1]) + "," + text(t->translation[2]) + "," +
                            text(t->rotation);
            if (t->axis)
                s += " turning about " + text(t->axis->x()) + "," + text(t->axis->y()) + "," + text(t->axis->z()) + " tilting " +
                     text(t->tilt);
            if (t->datum) s += " about " + text(t->datum->x()) + "," + text(t->datum->y()) + "," + text(t->datum->z());
            return s;
        };
        mismatch("task.placement_tolerance", tol(run.task.placement), tol(here.task.placement));
    }
    if (!run.settings.occlusion_checked)
        throw certipose::invalid_argument("settings.occlusion", where + ": the run did not check occlusion (--occlusion none); "
                                                                        "its boxes certify no facet: run it with occlusion");
    detail::check_run_scene(run.scene, here.scene, where);
}

/// Adds the VALID, occlusion-checked boxes of the certipose-part folder `dir` to `pool`: `run`
/// is its summary.json, already compared with the plan by check_part_run, and `num_faces` the
/// part's face count. The run had the plan's `regions`, so its boxes are already allowed; they
/// are cut anyway, as a run made for the plan is, so that no candidate can leave the allowed
/// space. Throws out_of_range for a box of a facet beyond the part, and what read_part_boxes
/// throws for a damaged store.
template <Interval I>
void add_run_candidates(candidate_pool<I>& pool, const std::filesystem::path& dir, const part_summary& run,
                        std::size_t num_faces, const camera_regions& regions) {
    read_part_boxes(dir, run.settings.box_store, [&](const part_box& b) {
        if (b.facet >= num_faces) throw out_of_range("facet", b.facet, num_faces);
        if (b.box.cls != box_class::valid || !b.occlusion_checked) return;
        pose_box<I> box;
        for (std::size_t k = 0; k < 3; ++k) {
            box.position.x[k] = I(b.box.position[k][0], b.box.position[k][1]);
            box.orientation.x[k] = I(b.box.orientation[k][0], b.box.orientation[k][1]);
        }
        if (regions.empty()) return pool.add(b.facet, box);
        const auto pieces = split_by_regions(box.position, regions, regions.width(run.settings.position_eps));
        for (const auto& p : pieces.allowed) pool.add(b.facet, pose_box<I>{p, box.orientation});
    });
}

/// The choices of certipose-plan (its options of the same names).
struct plan_options {
    /// At most this many cameras (maximum coverage); with neither this nor `coverage`, the
    /// fewest cameras for 95 % of the coverable area.
    std::optional<std::size_t> cameras{};
    /// The fewest cameras certifying this share of the coverable area, in (0, 1].
    std::optional<double> coverage{};
    /// Half-widths (metres, radians) candidates are cut to around their centres; none: whole boxes.
    std::optional<std::array<double, 2>> tolerance = std::array<double, 2>{0.005, 0.02};
    /// Time for GLPK's LP lower bound; a bound not proven by then is not claimed.
    double lp_seconds = 60;
    /// Which facet classes the LP bound may leave out on a large part (a relaxation, still a bound).
    lp_relaxation relaxation{};
    /// Time for GLPK's exact answer; none: greedy only.
    std::optional<double> exact_seconds{};
    std::size_t threads = 0;  ///< C(B) worker threads; 0: every core
    /// Skip the candidates whose facet an inspected candidate already certifies
    /// (coverage/thinning.hpp); none: C(B) of every candidate.
    std::optional<thinning_options> thinning = thinning_options{};
    /// The scene's fixed occluders (as given to the solver): an uncovered facet lying face to face
    /// on one is reported as resting on it (occlusion/resting_contact.hpp), not as a matter of ε.
    std::span<const triangle_mesh> occluders{};
    std::stop_token stop{};
    /// C(B) progress (candidates done, all), from a worker thread; false stops the plan.
    std::function<bool(std::size_t, std::size_t)> inspection_progress{};
    /// Called with the greedy plan's size before the LP bound (which may take lp_seconds), and
    /// once the bound is known.
    std::function<void(std::size_t)> before_lp{};
    std::function<void()> after_lp{};

    /// Throws invalid_argument naming the field for an impossible value.
    void validate() const {
        if (cameras && coverage) throw invalid_argument("cameras", "plan_options: give cameras or coverage, not both");
        if (cameras && *cameras < 1) throw invalid_argument("cameras", "plan_options: cameras must be at least 1");
        if (coverage && !(*coverage > 0.0 && *coverage <= 1.0))
            throw invalid_argument("coverage", "plan_options: coverage must be a share in (0, 1], got " + detail::format_double(*coverage));
        if (tolerance)
            for (std::size_t k = 0; k < 2; ++k)
                if (!((*tolerance)[k] > 0.0) || !std::isfinite((*tolerance)[k]))
                    throw invalid_argument("tolerance", std::string("plan_options: tolerance ") + (k ? "orientation" : "position") +
                                                            " half-width must be positive and finite, got " +
                                                            detail::format_double((*tolerance)[k]));
        if (!(lp_seconds > 0.0) || !std::isfinite(lp_seconds))
            throw invalid_argument("lp_seconds", "plan_options: lp_seconds must be positive and finite, got " + detail::format_double(lp_seconds));
        if (exact_seconds && (!(*exact_seconds > 0.0) || !std::isfinite(*exact_seconds)))
            throw invalid_argument("exact_seconds",
                                   "plan_options: exact_seconds must be positive and finite, got " + detail::format_double(*exact_seconds));
        if (thinning) thinning->validate();
        relaxation.validate();
    }
};

/// What make_plan measured (seconds) and decided.
struct plan_report {
    double seconds_inspection = 0, seconds_choice = 0;
    std::size_t inspected = 0;  ///< candidates whose C(B) was computed (all of them without thinning)
    bool exact = false;      ///< GLPK's exact answer was found within exact_seconds
    bool completed = true;   ///< false: stopped (options.stop, or the progress returned false)
};

/// Fills `doc`'s candidates, inspected, tolerance, max_cameras, target_coverage, cameras, coverage and
/// uncovered from `candidates` (their facets and VALID boxes, e.g. candidate_pool::boxes())
/// and the run's facet `records` (for the reasons of the uncovered). `trust_run`: the run is
/// known to be of this very mesh, so a candidate's own facet counts as certified by it. The
/// caller fills the mesh, camera, task and scene records. Returns report.completed == false,
/// with `doc`'s plan fields not all set, when stopped (options.stop, or the progress callback):
/// during C(B) at once, during GLPK's steps once the step ends.
template <class Policies>
plan_report make_plan(plan_document& doc, const pose_solver<Policies>& solver,
                      const std::vector<candidate_box<typename pose_solver<Policies>::interval_type>>& candidates,
                      const std::vector<facet_record>& records, bool trust_run, const plan_options& options) {
    using I = typename pose_solver<Policies>::interval_type;
    using clock = std::chrono::steady_clock;
    const auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
    options.validate();
    plan_report report;
    const std::size_t num_faces = solver.part().num_faces();
    doc.candidates = candidates.size();
    doc.tolerance = options.tolerance;

    // C(B) of every candidate (or of those thinning keeps), plus its own facet when the run is trusted.
    const auto t1 = clock::now();
    std::vector<pose_box<I>> boxes;
    boxes.reserve(candidates.size());
    for (const auto& c : candidates) {
        if (!options.tolerance) {
            boxes.push_back(c.box);
            continue;
        }
        const double p = (*options.tolerance)[0], o = (*options.tolerance)[1];
        boxes.push_back(around_centre(c.box, {p, p, p, o, o, o}));
    }
    inspection_options iopt;
    iopt.threads = options.threads;
    iopt.stop = options.stop;
    iopt.possible_sets = false;  // the plan needs C(B) only
    iopt.progress = options.inspection_progress;
    std::vector<char> kept(candidates.size(), 1);  // the candidates inspected
    inspection_run inspected;
    if (options.thinning) {
        std::vector<std::size_t> facets;
        facets.reserve(candidates.size());
        for (const auto& c : candidates) facets.push_back(c.facet);
        thinning_options thinning = *options.thinning;
        thinning.own_facet = thinning.own_facet && trust_run;
        thinned_inspection t = inspect_thinned(solver, boxes, facets, thinning, iopt);
        kept = std::move(t.inspected);
        inspected = std::move(t);
    } else {
        inspected = inspect_boxes(solver, boxes, iopt);
    }
    if (options.stop.stop_requested() || !inspected.completed) {
        report.completed = false;
        return report;
    }
    report.seconds_inspection = since(t1);
    report.inspected = static_cast<std::size_t>(std::count(kept.begin(), kept.end(), char{1}));
    doc.inspected = report.inspected;
    // The inspector's areas: a duplicated face counts once (coverage/inspection.hpp).
    const std::vector<double> areas = facet_inspector<Policies>(solver).areas();
    std::vector<deployment_candidate> sets(candidates.size());
    for (std::size_t j = 0; j < candidates.size(); ++j) {
        if (!kept[j]) continue;  // skipped by thinning: no choice of the plan
        sets[j].facets = inspected.coverage[j].certified;
        auto& fs = sets[j].facets;
        if (trust_run && !std::binary_search(fs.begin(), fs.end(), candidates[j].facet))
            fs.insert(std::lower_bound(fs.begin(), fs.end(), candidates[j].facet), candidates[j].facet);
    }

    // The choice and its lower bound.
    const auto t2 = clock::now();
    deployment_options dopt;
    dopt.cameras = options.cameras;
    dopt.coverage = options.coverage;
    doc.max_cameras = options.cameras;
    doc.target_coverage = options.cameras ? options.coverage : std::optional<double>(options.coverage.value_or(0.95));
    deployment_plan plan = plan_greedy(sets, areas, dopt);
    std::string method = plan.lower_bound > area_lower_bound(sets, areas, plan.certified_area) ? "greedy" : "area";
    // GLPK cannot be interrupted: a stop is honoured before and after each of its steps.
    const auto stopped = [&] {
        if (!options.stop.stop_requested()) return false;
        report.completed = false;
        return true;
    };
    if (stopped()) return report;
    if (options.before_lp) options.before_lp(plan.chosen.size());
    const auto lp_limit = std::chrono::milliseconds(static_cast<long long>(std::min(options.lp_seconds, 1e6) * 1000));
    const std::size_t lp = lp_lower_bound(sets, areas, plan.certified_area * (1 - 1e-9),
                                          {.time_limit = lp_limit, .relaxation = options.relaxation});
    if (options.after_lp) options.after_lp();
    if (lp > plan.lower_bound) plan.lower_bound = lp, method = "lp";
    if (stopped()) return report;
    if (options.exact_seconds && plan.chosen.size() > plan.lower_bound) {
        const auto limit = std::chrono::milliseconds(static_cast<long long>(std::min(*options.exact_seconds, 1e6) * 1000));
        if (const auto best = plan_exact(sets, areas, plan.certified_area * (1 - 1e-9), limit)) {
            report.exact = true;
            if (best->size() < plan.chosen.size()) {
                const std::size_t bound = plan.lower_bound;
                plan = plan_of(sets, areas, *best);
                plan.lower_bound = std::max(bound, best->size());
            } else {
                plan.lower_bound = plan.chosen.size();  // proven optimal
            }
            method = "exact";
        }
        if (stopped()) return report;
    }
    report.seconds_choice = since(t2);

    doc.cameras.clear();
    for (std::size_t k = 0; k < plan.chosen.size(); ++k) {
        const std::size_t j = plan.chosen[k];
        const auto record = to_record(classified_box<I>{box_class::valid, boxes[j]});
        plan_document::camera_box cam;
        cam.position = record.position;
        cam.orientation = record.orientation;
        for (std::size_t i = 0; i < 3; ++i) {
            cam.nominal[i] = 0.5 * (record.position[i][0] + record.position[i][1]);
            cam.nominal[i + 3] = 0.5 * (record.orientation[i][0] + record.orientation[i][1]);
        }
        cam.facets = sets[j].facets;
        for (std::size_t f : cam.facets) cam.certified_area += areas[f];
        cam.from_facet = candidates[j].facet;
        cam.aim = plan_aim(solver.part(), cam);
        doc.cameras.push_back(std::move(cam));
    }
    doc.coverage = {plan.certified_area, plan.coverable_area, plan.total_area, plan.lower_bound, method, plan.curve};

    // The facets no chosen camera certifies, and why.
    std::vector<char> coverable(num_faces, 0);
    for (const auto& s : sets)
        for (std::size_t f : s.facets) coverable[f] = 1;
    std::vector<const facet_record*> record_of(num_faces, nullptr);
    for (const auto& r : records)
        if (r.index < record_of.size()) record_of[r.index] = &r;
    doc.uncovered.clear();
    for (std::size_t f = 0; f < num_faces; ++f) {
        if (plan.covered_by[f] != deployment_plan::npos) continue;
        uncovered_reason why = uncovered_reason::not_solved;
        if (coverable[f]) why = uncovered_reason::not_selected;
        else if (const auto* r = record_of[f]; r && r->termination == facet_termination::skipped)
            why = uncovered_reason::never_visible;  // the run's screen proved that no pose inspects it
        else if (r) {
            if (r->valid > 0) why = uncovered_reason::not_selected;  // VALID boxes, none a candidate that proves it
            else if (r->boundary > 0) why = uncovered_reason::boundary_only;
            else if (r->termination != facet_termination::completed) why = uncovered_reason::not_finished;
            else why = uncovered_reason::never_visible;
        }
        doc.uncovered.push_back({f, why});
    }
    if (!options.occluders.empty()) {
        std::vector<char> ask(num_faces, 0);
        for (const auto& u : doc.uncovered)
            ask[u.facet] = u.reason == uncovered_reason::boundary_only || u.reason == uncovered_reason::never_visible;
        const auto resting = resting_on_occluders(solver.part(), options.occluders, ask);
        for (auto& u : doc.uncovered)
            if (resting[u.facet]) u.reason = uncovered_reason::rests_on_occluder;
    }
    // Facets with material in front of them: the occlusion's survey of a triangle soup proved
    // them buried in, or covered by, another body, so no camera can stand where it would see
    // them, at any ε. The survey decides; this only names it.
    if constexpr (requires { solver.occlusion().survey(); })
        if (const mesh_survey* survey = solver.occlusion().survey())
            for (auto& u : doc.uncovered)
                if ((u.reason == uncovered_reason::never_visible || u.reason == uncovered_reason::boundary_only) &&
                    u.facet < survey->hidden.size() && material_in_front(survey->hidden[u.facet]))
                    u.reason = uncovered_reason::buried;
    return report;
}

}  // namespace certipose
