// certipose/part/facet_steps.hpp — what a part run does with one work item, as named steps,
// each a type with its own options (docs/part.md, "The steps of a part run"):
//
//   screen        skip a facet provably uninspectable, with the reason  (part_options::skip_uninspectable)
//   reuse         take a translate's boxes, each proven again          (part_options::reuse)
//   solve         otherwise pave it with the facet pipeline             (part_options::facet)
//   regions       restrict its VALID boxes to the camera regions        (part_options::regions)
//   patch         prove the seed's boxes for the patch's other members  (part_options::patches)
//   keep largest  keep its K largest VALID boxes                        (part_options::keep_largest)
//
// `facet_steps` chains them for one work item, in a worker thread. An item of one facet runs
// screen, reuse or solve, regions and keep largest. A patch screens each member, solves its
// seed (the first member left) with reuse or solve and regions, proves the seed's boxes for the
// others (patch), keeps the largest of what the patch holds, and solves each member the patch
// step turned away as an item of its own. The scheduler (part/scheduler.hpp) hands the outcomes
// to the sink in order. A work item that the run's stop or deadline cuts short is dropped,
// never reported half done.
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
#include <span>
#include <tuple>
#include <string>
#include <utility>
#include <vector>

#include "certipose/constraints/concept.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/orientation/paper_orientation.hpp"
#include "certipose/part/part_run.hpp"
#include "certipose/part/patches.hpp"
#include "certipose/part/scheduler.hpp"
#include "certipose/part/translates.hpp"
#include "certipose/solver/camera_regions.hpp"
#include "certipose/solver/keep_largest.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

namespace detail {

/// solve_stats::valid_volume of `boxes`: the volume of the distinct position boxes of the
/// VALID ones (a position box with several orientation boxes counts once).
template <Interval I>
double valid_position_volume(const std::vector<classified_box<I>>& boxes) {
    std::set<std::array<double, 6>> seen;
    double v = 0.0;
    for (const auto& b : boxes) {
        const auto& p = b.box.position;
        if (b.cls == box_class::valid && seen.insert({lower(p[0]), upper(p[0]), lower(p[1]), upper(p[1]), lower(p[2]), upper(p[2])}).second)
            v += volume(p);
    }
    return v;
}

}  // namespace detail

/// Skips a facet that provably no pose can inspect (part_solver::uninspectable), with the reason.
struct screen_step {
    bool skip_uninspectable = true;

    template <class Part>
    std::optional<std::string> operator()(const Part& part, std::size_t f) const {
        if (!skip_uninspectable) return std::nullopt;
        return part.uninspectable(f);
    }
};

/// Paves a facet with the part's facet pipeline (pose_solver::solve).
struct solve_step {
    template <class Part>
    auto operator()(const Part& part, std::size_t f, const solve_options& options) const {
        return part.solver().solve(f, options);
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

/// Proves a patch seed's VALID boxes for the patch's other members (part/patches.hpp). A box
/// not proven for a member is split (its position at the widest component when constraints 1–4
/// or 6 fail, else its orientation) and the halves proven, down to `split_depth` levels: the
/// seed's boxes hug the seed's own boundaries, and a member's lie a little further in. A member
/// joins while the pieces proven for it and for every member before it hold at least
/// (1 − max_loss) of the seed's VALID 6D volume; the pieces left are the patch's.
struct patch_step {
    double max_loss = 0.25;
    std::size_t split_depth = 3;

    struct outcome {
        std::vector<std::size_t> joined, alone;  ///< members (other than the seed), in order
        bool cut_short = false;                  ///< `stopped` said so: the item is dropped
    };

    /// `r` is the seed's result (its VALID boxes become the patch's); `others` the members to
    /// prove them for; `stopped()` is asked between members and every 64 proofs.
    template <class Part, Interval I, class Stopped>
    outcome operator()(const Part& part, solve_result<I>& r, std::span<const std::size_t> others, Stopped&& stopped) const {
        outcome out;
        const auto six = [](const pose_box<I>& b) { return volume(b.position) * volume(b.orientation); };
        std::vector<pose_box<I>> live;  // pieces proven for the seed and every member that joined
        double seed_volume = 0.0;
        for (const auto& b : r.boxes)
            if (b.cls == box_class::valid) {
                live.push_back(b.box);
                seed_volume += six(b.box);
            }
        if (live.empty()) {  // the seed shares nothing
            out.alone.assign(others.begin(), others.end());
            return out;
        }
        std::vector<pose_box<I>> kept;
        std::size_t proofs = 0;
        for (const std::size_t m : others) {
            if (stopped()) {
                out.cut_short = true;
                return out;
            }
            auto certify = part.solver().certifier(m);
            kept.clear();
            double held = 0.0;
            const auto prove = [&](auto& self, const pose_box<I>& b, std::size_t depth) -> void {
                if (certify(b)) {
                    kept.push_back(b);
                    held += six(b);
                    return;
                }
                if (depth == split_depth) return;
                // Split where the proof failed: the position when constraints 1–4 or 6 do not
                // hold over it, else the orientation (constraint 5), at its widest component.
                const bool position_failed = !certify.position(b.position);
                auto [lo, hi] = std::pair{b, b};
                if (position_failed) {
                    const std::size_t k = widest_dimension(b.position);
                    std::tie(lo.position, hi.position) = bisect_at(b.position, k, mid(b.position[k]));
                } else {
                    const std::size_t k = widest_dimension(b.orientation);
                    std::tie(lo.orientation, hi.orientation) = bisect_at(b.orientation, k, mid(b.orientation[k]));
                }
                self(self, lo, depth + 1);
                self(self, hi, depth + 1);
            };
            for (const auto& b : live) {
                if (++proofs % 64 == 0 && stopped()) {
                    out.cut_short = true;
                    return out;
                }
                prove(prove, b, 0);
            }
            if (held >= (1.0 - max_loss) * seed_volume && !kept.empty()) {
                live.swap(kept);
                out.joined.push_back(m);
            } else {
                out.alone.push_back(m);
            }
        }
        if (out.joined.empty()) return out;  // the seed keeps its own result
        // The patch's boxes: the pieces proven for every member; the seed's BOUNDARY boxes stay
        // (they claim nothing), and its count of them.
        std::erase_if(r.boxes, [](const classified_box<I>& b) { return b.cls == box_class::valid; });
        for (auto& b : live) r.boxes.push_back(classified_box<I>{box_class::valid, std::move(b)});
        r.stats.valid = live.size();
        r.stats.valid_volume = detail::valid_position_volume(r.boxes);
        return out;
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

    /// Facet f's boxes as a translate's, proven again (`from` names the translate); nothing when
    /// it has no open translate, or the template's boxes not proven for it hold more than
    /// reuse.max_loss of its VALID volume. `options` solves the template when w asks first.
    std::optional<solve_result<I>> operator()(std::size_t f, const solve_options& options, std::optional<std::size_t>& from) {
        using clock = std::chrono::steady_clock;
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
        if (moved->unproven > 0)  // the positions the unproven boxes held alone are no longer certified
            r.stats.valid_volume = detail::valid_position_volume(r.boxes);
        r.stats.seconds = std::chrono::duration<double>(clock::now() - t0).count();
        from = t;
        return r;
    }

    /// Facet f is done (however its run ended): the group's last selected member frees the
    /// template's result.
    void done(std::size_t f) {
        const auto g = groups_ ? groups_->shared_group(f) : std::nullopt;
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
          patch_{options.patches.max_loss, options.patches.split_depth},
          largest_{options.keep_largest} {}

    /// Item w, in a worker: each facet skipped, solved (or reused), or its patch's; or the whole
    /// item dropped when the run ends while it is in flight.
    work_result<I> operator()(work_item w) {
        using clock = std::chrono::steady_clock;
        const std::span<const std::size_t> members = schedule_->plan().members(w.item);
        struct members_done {
            reuse_step<Part>& reuse;
            std::span<const std::size_t> members;
            ~members_done() {
                for (std::size_t f : members) reuse.done(f);
            }
        } done{reuse_, members};
        work_result<I> out;
        out.outcomes.resize(members.size());
        if (schedule_->context().stop_requested()) return dropped(out);
        // Screen every member; the first left is the seed.
        std::vector<std::size_t> left;  // positions in `members`
        for (std::size_t k = 0; k < members.size(); ++k) {
            facet_record& rec = out.outcomes[k].record;
            rec.index = members[k];
            const auto t0 = clock::now();
            if (auto reason = screen_(*part_, members[k])) {
                rec.termination = facet_termination::skipped;
                rec.reason = std::move(*reason);
                rec.seconds = std::chrono::duration<double>(clock::now() - t0).count();
            } else {
                left.push_back(k);
            }
        }
        if (left.empty()) return out;
        const solve_options options = schedule_->item_options(facet_options_);
        facet_outcome<I>& seed = out.outcomes[left.front()];
        std::optional<solve_result<I>> r = reuse_(seed.record.index, options, seed.record.reused_from);
        if (!r) r = solve_(*part_, seed.record.index, options);
        if (schedule_->cut_short(r->stats)) return dropped(out);
        regions_(*r, options.position_eps);
        std::vector<std::size_t> others, alone;
        for (std::size_t i = 1; i < left.size(); ++i) others.push_back(members[left[i]]);
        std::vector<std::size_t> joined;
        if (!others.empty()) {
            const auto t0 = clock::now();
            auto p = patch_(*part_, *r, others, [&] { return schedule_->context().stop_requested() || schedule_->context().past_deadline(); });
            if (p.cut_short) return dropped(out);
            joined = std::move(p.joined);
            alone = std::move(p.alone);
            r->stats.seconds += std::chrono::duration<double>(clock::now() - t0).count();
        }
        seed.record.dropped = largest_(*r);
        if (!joined.empty()) seed.record.patch = seed.record.index;
        const auto position = [&](std::size_t f) {
            return static_cast<std::size_t>(std::find(members.begin(), members.end(), f) - members.begin());
        };
        for (const std::size_t f : joined) {  // copies of the patch's result: before the seed's boxes move
            facet_outcome<I>& o = out.outcomes[position(f)];
            o.record.patch = seed.record.index;
            o.record.dropped = seed.record.dropped;
            record_copy(*r, o);
            o.record.seconds = 0.0;  // the patch's time is the seed's
        }
        record(*r, seed);
        for (const std::size_t f : alone) {  // turned away by the patch: a facet of its own
            facet_outcome<I>& o = out.outcomes[position(f)];
            std::optional<solve_result<I>> own = reuse_(f, options, o.record.reused_from);
            if (!own) own = solve_(*part_, f, options);
            if (schedule_->cut_short(own->stats)) return dropped(out);
            regions_(*own, options.position_eps);
            o.record.dropped = largest_(*own);
            record(*own, o);
        }
        return out;
    }

private:
    static work_result<I> dropped(work_result<I>& out) {
        out.dropped = true;
        out.outcomes.clear();
        return std::move(out);
    }

    /// The record's counts and termination from result `r`.
    static void count(const solve_result<I>& r, facet_record& rec) {
        rec.seconds = r.stats.seconds;
        rec.valid = r.stats.valid;
        rec.boundary = r.stats.boundary;
        rec.boundary_reasons = r.stats.boundary_reasons;
        rec.termination = r.stats.reason == termination::box_budget ? facet_termination::box_budget
                          : r.stats.reason == termination::deadline ? facet_termination::deadline
                                                                    : facet_termination::completed;
    }

    /// The record and the boxes the sink receives (VALID, and BOUNDARY when the run keeps them),
    /// moved out of `r`.
    void record(solve_result<I>& r, facet_outcome<I>& o) const {
        count(r, o.record);
        o.boxes.reserve(keep_boundary_ ? r.boxes.size() : r.stats.valid);
        for (auto& b : r.boxes)
            if (b.cls == box_class::valid || keep_boundary_) o.boxes.push_back(std::move(b));
    }

    /// The same, copied: a patch member's.
    void record_copy(const solve_result<I>& r, facet_outcome<I>& o) const {
        count(r, o.record);
        o.boxes.reserve(keep_boundary_ ? r.boxes.size() : r.stats.valid);
        for (const auto& b : r.boxes)
            if (b.cls == box_class::valid || keep_boundary_) o.boxes.push_back(b);
    }

    const Part* part_;
    const part_schedule* schedule_;
    solve_options facet_options_;
    bool keep_boundary_;
    screen_step screen_;
    reuse_step<Part> reuse_;
    solve_step solve_{};
    regions_step regions_;
    patch_step patch_;
    keep_largest_step largest_;
};

}  // namespace certipose
