// certipose/solver/orientation_schedule.hpp — the orientation half of the paper's Algorithm 3
// (lines 28–36) as named steps: in which order, and with what help, the orientation policy is
// asked about each certified position box.
//
// The paper asks once per VALID position box; when nothing certifies, the box is bisected (down
// to the split width) and its halves asked again — halves of a certified position box stay
// certified for constraints 1–4 and 6, so only orientation is asked again — and a box that still
// fails is BOUNDARY (reason field_of_view). The schedule runs that as `orient_each`, and for
// `carving` (solver/paving.hpp), whose pieces, corner boxes and refined leaves are many and
// small, two steps before it:
//   merge_positions   touching position boxes that tile a larger box are merged back: fewer
//                     searches, and a wider installation tolerance;
//   orient_groups     the small boxes of one cell of ε_p are oriented together first: an
//                     orientation certified over their hull holds for each (constraint 5 over a
//                     position box holds over every box inside it); a hull that fails is split
//                     at its median member down to `min_group` boxes, then the rest go one by one.
// How one box is asked is the schedule type's choice (a policy slot, solver/policies.hpp):
//   hinted_schedule   (default) a hint per cell of ε_p: a box searches from what its cell's
//                     searches found; a box whose own search failed in a cell where none
//                     certified yet borrows the hints of the 26 cells around it (carving only).
//                     Needs a BorrowingOrientationPolicy (paper_orientation is one).
//   per_box_schedule  one independent search per box: any OrientationPolicy.
// A hint changes which box is found and how fast, never whether it is certified.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <stop_token>
#include <utility>
#include <vector>

#include "certipose/bisection/concept.hpp"
#include "certipose/camera/camera_model.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/orientation/concept.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/detail/growth.hpp"
#include "certipose/solver/paving.hpp"
#include "certipose/solver/run_context.hpp"
#include "certipose/solver/result.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

/// Tuning of the schedule's steps for `carving` (pose_solver::setup::schedule).
struct schedule_options {
    /// Merge touching certified position boxes that tile a larger box before orienting.
    bool merge_positions = true;
    /// Orient the boxes of one cell of ε_p together first (orient_groups).
    bool groups = true;
    /// A group whose hull fails is split while it has at least twice this many boxes.
    std::size_t min_group = 4;
    /// A box whose own search failed borrows the hints of the cells around it (hinted_schedule).
    bool borrowing = true;

    void validate() const {
        if (min_group < 1) throw invalid_argument("schedule.min_group", "schedule_options: min_group must be at least 1");
    }
};

/// One search per box, from a hint per cell of ε_p, borrowing neighbours' hints (see the header).
struct hinted_schedule {
    template <class O, class I, class C>
    static constexpr bool accepts = BorrowingOrientationPolicy<O, I, C>;
};

/// One independent search per box: any OrientationPolicy.
struct per_box_schedule {
    template <class O, class I, class C>
    static constexpr bool accepts = OrientationPolicy<O, I, C>;
};

/// A schedule type S that can drive orientation policy O (over I, for camera C).
template <class S, class O, class I, class C>
concept OrientationScheduleFor = OrientationPolicy<O, I, C> && requires { requires S::template accepts<O, I, C>; };

namespace detail {

/// The hint type of an orientation policy (HintedOrientationPolicy), an empty one otherwise.
template <class O, class I, class C>
struct orientation_hint_of {
    struct type {};
};
template <class O, class I, class C>
    requires HintedOrientationPolicy<O, I, C>
struct orientation_hint_of<O, I, C> {
    using type = typename O::hint;
};

/// The BOUNDARY 6D box of an undecided position box: every orientation (nothing was decided
/// about aiming there), and why.
template <Interval I>
void push_boundary(solve_result<I>& out, const position_box<I>& p, boundary_reason why) {
    const rounding_guard<I> rounding;
    const double pi_hi = std::nextafter(std::numbers::pi, 4.0);
    const orientation_box<I> all = orientation_box<I>::from_bounds({{{-pi_hi, pi_hi}, {0.0, pi_hi}, {-pi_hi, pi_hi}}});
    out.boxes.push_back(classified_box<I>{box_class::boundary, pose_box<I>{p, all}, why});
    ++out.stats.boundary;
    out.stats.boundary_volume += volume(p);
    ++out.stats.boundary_reasons[static_cast<std::size_t>(why)];
}

}  // namespace detail

/// The orientation stage of one run: `merge_positions`, `orient_groups`, then `orient_each`,
/// writing VALID and BOUNDARY 6D boxes to the result. Built per run (it holds the run's hints).
template <class Schedule, class Orientation, CameraModel Camera, Interval I, class Bisector>
    requires OrientationScheduleFor<Schedule, Orientation, I, Camera>
class orientation_stage {
    static constexpr bool hinted = std::same_as<Schedule, hinted_schedule>;

public:
    /// `carving_steps`: the run paves with carving, so the steps meant for its boxes run (as
    /// `tuning` says); `done`: boxes the run has processed so far (both stages count).
    orientation_stage(const Orientation& policy, const facet& f, const Camera& camera, const solve_options& options,
                      const schedule_options& tuning, const run_context& clock, Bisector bisector,
                      solve_result<I>& out, std::size_t done)
        : policy_(policy),
          facet_(f),
          camera_(camera),
          options_(options),
          clock_(clock),
          bisector_(std::move(bisector)),
          out_(out),
          done_(done),
          carving_(carving_of(options.paving) != nullptr),
          tuning_(tuning) {}

    /// Merges touching position boxes that tile a larger one (carving, schedule_options).
    void merge_positions(std::vector<position_box<I>>& valid) {
        if (carving_ && tuning_.merge_positions)
            out_.stats.position_merges = detail::growth::merge_touching_positions(valid, options_.position_eps);
    }

    /// Orients the boxes of each cell of ε_p together (carving, schedule_options::groups),
    /// largest cell volume first; what no group certifies waits for `orient_each`.
    void orient_groups(const std::vector<position_box<I>>& valid);

    /// Orients the waiting boxes one by one, largest first, bisecting a box no orientation fits
    /// down to the bisector's width. A box budget stops the bisection (the rest is asked once);
    /// a deadline or cancellation leaves the rest BOUNDARY (reason budget).
    void orient_each();

    std::size_t done() const noexcept { return done_; }

private:
    using cell_key = std::array<long long, 3>;
    using hint_type = typename detail::orientation_hint_of<Orientation, I, Camera>::type;

    cell_key cell_of(const position_box<I>& p) const {
        cell_key key{};
        for (std::size_t k = 0; k < 3; ++k) key[k] = detail::growth::cell_index(mid(p[k]), options_.position_eps);
        return key;
    }
    bool halted() const {
        return out_.stats.reason == termination::deadline || out_.stats.reason == termination::cancelled;
    }
    /// Every orientation box of `o` is VALID over position box `p`.
    void accept(const position_box<I>& p, const orientation_result<I>& o);
    orientation_result<I> orient(const position_box<I>& p, bool single);
    orientation_result<I> borrow(const position_box<I>& p, const cell_key& key);

    const Orientation& policy_;
    const facet& facet_;
    const Camera& camera_;
    const solve_options& options_;
    const run_context& clock_;
    Bisector bisector_;
    solve_result<I>& out_;
    std::size_t done_;
    bool carving_;
    schedule_options tuning_;
    std::vector<position_box<I>> todo_;
    std::map<cell_key, hint_type> hints_;
    std::set<cell_key> oriented_;  // cells where a search of their own certified
};

template <class Schedule, class Orientation, CameraModel Camera, Interval I, class Bisector>
    requires OrientationScheduleFor<Schedule, Orientation, I, Camera>
void orientation_stage<Schedule, Orientation, Camera, I, Bisector>::accept(const position_box<I>& p,
                                                                           const orientation_result<I>& o) {
    for (const auto& e : o.boxes) {
        out_.boxes.push_back(classified_box<I>{box_class::valid, pose_box<I>{p, e}});
        ++out_.stats.valid;
    }
    out_.stats.valid_volume += volume(p);
}

template <class Schedule, class Orientation, CameraModel Camera, Interval I, class Bisector>
    requires OrientationScheduleFor<Schedule, Orientation, I, Camera>
orientation_result<I> orientation_stage<Schedule, Orientation, Camera, I, Bisector>::orient(const position_box<I>& p,
                                                                                          bool single) {
    if constexpr (hinted) {
        const cell_key key = cell_of(p);
        auto at = hints_.find(key);
        if (at == hints_.end()) at = hints_.emplace(key, policy_.new_hint(options_.position_eps)).first;
        orientation_result<I> o = policy_.orient(p, facet_, camera_, options_.orientation_eps, at->second);
        if (!o.boxes.empty()) {
            oriented_.insert(key);
            return o;
        }
        // Not for a group's hull: a hull oriented with a borrowed scale would give its members
        // that scale instead of their own searches'. What is borrowed is not kept: the next box
        // of the cell searches for itself.
        if (single && carving_ && tuning_.borrowing && !oriented_.contains(key)) {
            orientation_result<I> b = borrow(p, key);
            if (b.certifications > 0 || !b.boxes.empty()) {
                b.certifications += o.certifications;
                return b;
            }
        }
        return o;
    } else {
        return policy_.orient(p, facet_, camera_, options_.orientation_eps);
    }
}

template <class Schedule, class Orientation, CameraModel Camera, Interval I, class Bisector>
    requires OrientationScheduleFor<Schedule, Orientation, I, Camera>
orientation_result<I> orientation_stage<Schedule, Orientation, Camera, I, Bisector>::borrow(const position_box<I>& p,
                                                                                          const cell_key& key) {
    if constexpr (hinted) {
        std::array<const hint_type*, 26> lent{};
        std::size_t n = 0;
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy)
                for (long long dz = -1; dz <= 1; ++dz) {
                    const cell_key k{key[0] + dx, key[1] + dy, key[2] + dz};
                    if (k != key && oriented_.contains(k)) lent[n++] = &hints_.at(k);
                }
        if (n == 0) return {};
        orientation_result<I> b = policy_.orient_borrowed(p, facet_, camera_, options_.orientation_eps,
                                                          std::span<const hint_type* const>(lent.data(), n));
        if (!b.boxes.empty()) ++out_.stats.orientation_borrowed;
        return b;
    } else {
        return {};
    }
}

template <class Schedule, class Orientation, CameraModel Camera, Interval I, class Bisector>
    requires OrientationScheduleFor<Schedule, Orientation, I, Camera>
void orientation_stage<Schedule, Orientation, Camera, I, Bisector>::orient_groups(
    const std::vector<position_box<I>>& valid) {
    todo_.reserve(todo_.size() + valid.size());
    std::map<cell_key, std::vector<std::size_t>> cells;
    for (std::size_t i = 0; i < valid.size(); ++i) cells[cell_of(valid[i])].push_back(i);
    // Largest position volume first, in groups and one by one: a run that a deadline stops in
    // this stage (refinement hands it many small boxes) has certified the most it could.
    std::vector<std::pair<double, const std::vector<std::size_t>*>> by_volume;
    for (const auto& [key, members] : cells) {
        double v = 0;
        for (std::size_t i : members) v += volume(valid[i]);
        by_volume.emplace_back(v, &members);
    }
    std::stable_sort(by_volume.begin(), by_volume.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const bool grouping = carving_ && tuning_.groups;
    const auto one_by_one = [&](std::span<const std::size_t> members) {
        for (std::size_t i : members) todo_.push_back(valid[i]);
    };
    const auto group = [&](auto& self, std::span<std::size_t> members) -> void {
        if (members.size() < 2 || !grouping || halted() || clock_.out_of_time()) return one_by_one(members);
        position_box<I> h = valid[members[0]];
        for (std::size_t i : members) h = hull(h, valid[i]);
        ++done_;
        const orientation_result<I> o = orient(h, false);
        out_.stats.orientation_certifications += o.certifications;
        if (!o.boxes.empty()) {
            ++out_.stats.orientation_groups;
            for (std::size_t i : members) accept(valid[i], o);
            return;
        }
        if (members.size() < 2 * tuning_.min_group) return one_by_one(members);
        const std::size_t k = widest_dimension(h);
        const auto half = members.begin() + static_cast<std::ptrdiff_t>(members.size() / 2);
        std::nth_element(members.begin(), half, members.end(),
                         [&](std::size_t a, std::size_t b) { return mid(valid[a][k]) < mid(valid[b][k]); });
        self(self, members.first(members.size() / 2));
        self(self, members.subspan(members.size() / 2));
    };
    for (auto& [cell_volume, members_ptr] : by_volume) {
        std::vector<std::size_t> members = *members_ptr;
        group(group, members);
    }
    // Popped from the back: largest first (ties in cell order).
    std::reverse(todo_.begin(), todo_.end());
    std::stable_sort(todo_.begin(), todo_.end(), [](const auto& a, const auto& b) { return volume(a) < volume(b); });
}

template <class Schedule, class Orientation, CameraModel Camera, Interval I, class Bisector>
    requires OrientationScheduleFor<Schedule, Orientation, I, Camera>
void orientation_stage<Schedule, Orientation, Camera, I, Bisector>::orient_each() {
    solve_stats& st = out_.stats;
    bool stopped = halted();
    while (!todo_.empty()) {
        if (!stopped) {
            if (options_.stop.stop_requested()) {
                st.reason = termination::cancelled, stopped = true;
            } else if (clock_.past_deadline()) {
                st.reason = termination::deadline, stopped = true;
            } else if (options_.progress && done_ % 64 == 0 &&
                       !options_.progress(solve_progress{"orientation", done_, todo_.size(), st.valid, st.boundary,
                                                         clock_.seconds()})) {
                st.reason = termination::cancelled, stopped = true;
            } else if (st.reason == termination::completed && done_ >= options_.max_boxes) {
                st.reason = termination::box_budget;
            }
        }
        position_box<I> p = std::move(todo_.back());
        todo_.pop_back();
        if (stopped) {
            detail::push_boundary(out_, p, boundary_reason::budget);
            continue;
        }
        ++done_;
        const orientation_result<I> o = orient(p, true);
        st.orientation_certifications += o.certifications;
        if (!o.boxes.empty()) {
            accept(p, o);
            continue;
        }
        if (st.reason != termination::completed) {  // a budget forbids bisecting further
            detail::push_boundary(out_, p, boundary_reason::budget);
            continue;
        }
        const std::optional<split> s = bisector_.choose(p);
        if (!s) {
            detail::push_boundary(out_, p, boundary_reason::field_of_view);
            continue;
        }
        ++st.bisections;
        auto [left, right] = bisect_at(p, s->dimension, s->point);
        todo_.push_back(std::move(right));
        todo_.push_back(std::move(left));
    }
}

}  // namespace certipose
