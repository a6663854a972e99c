// certipose/part/facet_steps.hpp — what a part run does with one work item, as named steps,
// each a type with its own options (docs/part.md, "The steps of a part run"):
//
//   screen        skip a facet provably uninspectable, with the reason  (part_options::skip_uninspectable)
//   reuse         take a translate's boxes, each proven again          (part_options::reuse)
//   solve         otherwise pave it with the facet pipeline             (part_options::facet)
//   regions       restrict its VALID boxes to the camera regions        (part_options::regions)
//   keep largest  keep its K largest VALID boxes                        (part_options::keep_largest)
//
// `facet_steps` chains them for one work item, in a worker thread; the scheduler
// (part/scheduler.hpp) hands the outcome to the sink in selection order. A work item that the
// run's stop or deadline cuts short is dropped, never reported half done.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <concepts>
#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "certipose/constraints/concept.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/orientation/paper_orientation.hpp"
#include "certipose/part/part_run.hpp"
#include "certipose/part/scheduler.hpp"
#include "certipose/part/translates.hpp"
#include "certipose/solver/camera_regions.hpp"
#include "certipose/solver/keep_largest.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

/// Skips a facet that provably no pose can inspect (part_solver::uninspectable), with the reason.
struct screen_step {
    bool skip_uninspectable = true;

    template <class Part>
    std::optional<std::string> operator()(const Part& part, work_item w) const {
        if (!skip_uninspectable) return std::nullopt;
        return part.uninspectable(w.facet);
    }
};

/// Paves a facet with the part's facet pipeline (pose_solver::solve).
struct solve_step {
    template <class Part>
    auto operator()(const Part& part, work_item w, const solve_options& options) const {
        return part.solver().solve(w.facet, options);
    }
};

/// Restricts a result's VALID boxes to the camera regions (solver/camera_regions.hpp): nothing
/// without regions.
struct regions_step {
    camera_regions regions{};

    template <Interval I>
    void operator()(solve_result<I>& r, double position_eps) const {
        restrict_to_regions(r, regions, position_eps);
    }
};

/// Keeps a result's K largest VALID boxes (solver/keep_largest.hpp); returns how many it dropped.
struct keep_largest_step {
    std::optional<std::size_t> k{};

    template <Interval I>
    std::size_t operator()(solve_result<I>& r) const {
        return k ? keep_largest_valid(r, *k) : 0;
    }
};

/// The reuse step (part/translates.hpp): per group of translates, its template, the first open
/// member by index in the whole part (found once, by whichever worker asks first), and the
/// template's result, solved once and kept until every selected member of the group is done.
/// Without a translate group, or with a placement tolerance (whose proofs are per placement,
/// placement_stage.hpp), every facet is paved on its own.
template <class Part>
class reuse_step {
public:
    using I = typename Part::interval_type;

    reuse_step(const Part& part, const reuse_options& options, bool keep_boundary, const std::vector<std::size_t>& selection)
        : part_(&part), options_(options), keep_boundary_(keep_boundary) {
        if (!options.translates || part.solver().placement_proofs() != nullptr) return;
        groups_ = &part.translates();
        slots_.resize(groups_->members.size());
        for (std::size_t f : selection)
            if (const auto g = groups_->shared_group(f)) {
                if (!slots_[*g]) slots_[*g] = std::make_unique<slot>();
                ++slots_[*g]->users;
            }
    }

    /// Facet w's boxes as a translate's, proven again (`from` names the translate); nothing when
    /// it has no open translate, or the template's boxes not proven for it hold more than
    /// reuse.max_loss of its VALID volume. `options` solves the template when w asks first.
    std::optional<solve_result<I>> operator()(work_item w, const solve_options& options, std::optional<std::size_t>& from) {
        using clock = std::chrono::steady_clock;
        const std::size_t f = w.facet;
        const auto g = groups_ ? groups_->shared_group(f) : std::nullopt;
        if (!g) return std::nullopt;
        slot& s = *slots_[*g];
        std::call_once(s.found, [&] {
            for (std::size_t m : groups_->members[*g])
                if (part_->open_box(m)) {
                    s.facet = m;
                    return;
                }
        });
        if (!s.facet) return std::nullopt;
        const std::size_t t = *s.facet;
        std::optional<position_box<I>> search;
        if (t != f && !(search = part_->open_box(f))) return std::nullopt;
        std::call_once(s.solved, [&] {
            s.result = part_->solver().solve(t, options);
            if (!keep_boundary_)  // BOUNDARY boxes are only counted: the stats keep them
                std::erase_if(s.result->boxes, [](const classified_box<I>& b) { return b.cls != box_class::valid; });
        });
        const solve_result<I>& template_result = *s.result;
        if (t == f) return template_result;
        if (template_result.stats.reason != termination::completed) return std::nullopt;
        const auto t0 = clock::now();
        const auto& solver = part_->solver();
        const facet& target = solver.part().facet(f);
        auto set = make_constraint_set<typename Part::solver_type::constraint_set_type>(
            position_problem{target, solver.range(), solver.task()}, solver.constraints());
        auto moved = certify_translated<decltype(set), I>(set, *search, target, fov_frustum<I>(solver.camera()),
                                                         template_result.boxes,
                                                         target.centroid - solver.part().facet(t).centroid, keep_boundary_,
                                                         tiling_budget(), options_.max_loss);
        if (!moved) return std::nullopt;
        solve_result<I> r;
        r.facet_index = f;
        r.stats = template_result.stats;
        r.stats.valid = moved->valid;
        r.stats.boundary += moved->unproven;
        for (std::size_t k = 0; k < boundary_reason_count; ++k) r.stats.boundary_reasons[k] += moved->unproven_reasons[k];
        r.boxes = std::move(moved->boxes);
        if (moved->unproven > 0) {  // the positions the unproven boxes held alone are no longer certified
            std::set<std::array<double, 6>> seen;
            r.stats.valid_volume = 0;
            for (const auto& b : r.boxes) {
                const auto& p = b.box.position;
                if (b.cls == box_class::valid &&
                    seen.insert({lower(p[0]), upper(p[0]), lower(p[1]), upper(p[1]), lower(p[2]), upper(p[2])}).second)
                    r.stats.valid_volume += volume(p);
            }
        }
        r.stats.seconds = std::chrono::duration<double>(clock::now() - t0).count();
        from = t;
        return r;
    }

    /// Facet w is done (however its run ended): the group's last selected member frees the
    /// template's result.
    void done(work_item w) {
        const auto g = groups_ ? groups_->shared_group(w.facet) : std::nullopt;
        if (!g) return;
        slot& s = *slots_[*g];
        if (--s.users == 0) s.result.reset();
    }

private:
    struct slot {
        std::once_flag found, solved;
        std::optional<std::size_t> facet;  ///< the template (nothing: no member is open)
        std::optional<solve_result<I>> result;
        std::atomic<std::size_t> users{0};  ///< selected members not done yet
    };

    /// What one proof of constraint 5 may take: the orientation policy's own budget when it has
    /// one (so that what it proved can be proven again), else paper_orientation's default.
    std::size_t tiling_budget() const {
        if constexpr (requires { part_->solver().orientation().options().tiling_budget; })
            return part_->solver().orientation().options().tiling_budget;
        else
            return paper_orientation_options{}.tiling_budget;
    }

    const Part* part_;
    reuse_options options_;
    bool keep_boundary_;
    const translate_groups* groups_ = nullptr;
    std::vector<std::unique_ptr<slot>> slots_;
};

/// The steps of a part run for one work item (see the header comment), configured from the
/// run's part_options.
template <class Part>
class facet_steps {
public:
    using I = typename Part::interval_type;

    facet_steps(const Part& part, const part_options& options, const part_schedule& schedule)
        : part_(&part),
          schedule_(&schedule),
          facet_options_(options.facet),
          keep_boundary_(options.keep_boundary),
          screen_{options.skip_uninspectable},
          reuse_(part, options.reuse, options.keep_boundary, schedule.selection()),
          regions_{options.regions},
          largest_{options.keep_largest} {}

    /// Item w, in a worker: skipped, solved (or reused), or dropped when the run ends while it
    /// is in flight.
    work_result<I> operator()(work_item w) {
        using clock = std::chrono::steady_clock;
        struct member_done {
            reuse_step<Part>& reuse;
            work_item w;
            ~member_done() { reuse.done(w); }
        } done{reuse_, w};
        work_result<I> out;
        facet_record& rec = out.outcome.record;
        rec.index = w.facet;
        const auto t0 = clock::now();
        if (schedule_->context().stop_requested()) return dropped(out);
        if (auto reason = screen_(*part_, w)) {
            rec.termination = facet_termination::skipped;
            rec.reason = std::move(*reason);
            rec.seconds = std::chrono::duration<double>(clock::now() - t0).count();
            return out;
        }
        const solve_options options = schedule_->item_options(facet_options_);
        std::optional<solve_result<I>> r = reuse_(w, options, rec.reused_from);
        if (!r) r = solve_(*part_, w, options);
        if (schedule_->cut_short(r->stats)) return dropped(out);
        regions_(*r, options.position_eps);
        rec.dropped = largest_(*r);
        record(*r, out);
        return out;
    }

private:
    static work_result<I> dropped(work_result<I>& out) {
        out.dropped = true;
        return std::move(out);
    }

    /// The record and the boxes the sink receives (VALID, and BOUNDARY when the run keeps them).
    void record(solve_result<I>& r, work_result<I>& out) const {
        facet_record& rec = out.outcome.record;
        rec.seconds = r.stats.seconds;
        rec.valid = r.stats.valid;
        rec.boundary = r.stats.boundary;
        rec.boundary_reasons = r.stats.boundary_reasons;
        rec.termination = r.stats.reason == termination::box_budget ? facet_termination::box_budget
                          : r.stats.reason == termination::deadline ? facet_termination::deadline
                                                                    : facet_termination::completed;
        out.outcome.boxes.reserve(keep_boundary_ ? r.boxes.size() : r.stats.valid);
        for (auto& b : r.boxes)
            if (b.cls == box_class::valid || keep_boundary_) out.outcome.boxes.push_back(std::move(b));
    }

    const Part* part_;
    const part_schedule* schedule_;
    solve_options facet_options_;
    bool keep_boundary_;
    screen_step screen_;
    reuse_step<Part> reuse_;
    solve_step solve_{};
    regions_step regions_;
    keep_largest_step largest_;
};

}  // namespace certipose
