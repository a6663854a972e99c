// certipose/paver/paver.hpp — the paper's Algorithm 1: branch and bound over boxes that
// classifies a search box into VALID boxes (every point satisfies the constraints, certified),
// BOUNDARY boxes (undecided and narrower than the precision) and discarded parts (certified to
// hold no solution).
//
// `paver<Box, Contractor, InnerTest, Bisector, Buffer>` takes a box from the list of
// unclassified boxes (Algorithm 1 line 10), contracts it (line 5; emptiness discards it), asks
// the inner test (line 11: satisfied → VALID; violated → discarded), and otherwise asks the
// bisector for a split (line 21) — when the bisector declines because every dimension is
// narrower than its precision the box is BOUNDARY (line 16). Past the paper, the inner test
// may instead be an *inner contractor* (IBEX's CtcNotIn used as the inner half of a
// separator): a contractor of the complement of the constraint set; what it removes from a box
// is certified VALID and emitted as up to 2N boxes, and only the rest is bisected (on the
// spherical shell at ε = 0.05: VALID volume 0.365 instead of 0.299, of 0.41). The most general
// inner test is an *inner separator* (`InnerSeparator`): it carries a state of its own along the
// paving (the halves of a bisected box inherit it) and may carve any pieces off a box — VALID,
// discarded, or pending with their own state — before it answers for the rest; the solver's
// position stage is one (constraint set, complement contraction and occlusion in one step).
// The buffer policy (`depth_first`, `breadth_first`, `largest_volume_first`, or a user type with
// a nested `buffer<T>`) orders the unclassified boxes.
// Runs stop on a box budget, a deadline, a progress callback returning false or a
// `std::stop_token`; boxes still unclassified are then returned as `pending`, so that VALID ∪
// BOUNDARY ∪ pending always covers every solution in the initial box. Statistics, and
// optionally the whole bisection tree, come back with the boxes. The paver owns copies of its
// policy objects, so two pavers on two threads share no mutable state; one paver must not run
// on two threads at once. `run` holds a `rounding_guard` for the whole run.
#pragma once

#include <algorithm>
#include <chrono>
#include <concepts>
#include <cstddef>
#include <deque>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/bisection/concept.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/outcome.hpp"  // box_class, termination, verdict

namespace certipose {

namespace detail {
template <class Box>
double paving_volume(const Box& b);
}  // namespace detail

// ---- buffer policies ------------------------------------------------------------------------

/// Depth-first: the last box pushed is processed next (a stack; memory grows with the depth
/// of the tree, not its width).
struct depth_first {
    template <class T>
    class buffer {
    public:
        void push(T&& v) { v_.push_back(std::move(v)); }
        T pop() {
            T t = std::move(v_.back());
            v_.pop_back();
            return t;
        }
        bool empty() const noexcept { return v_.empty(); }
        std::size_t size() const noexcept { return v_.size(); }

    private:
        std::vector<T> v_;
    };
};

/// Breadth-first: boxes are processed in the order they were made (a queue; a run stopped
/// early has refined the whole box evenly).
struct breadth_first {
    template <class T>
    class buffer {
    public:
        void push(T&& v) { v_.push_back(std::move(v)); }
        T pop() {
            T t = std::move(v_.front());
            v_.pop_front();
            return t;
        }
        bool empty() const noexcept { return v_.empty(); }
        std::size_t size() const noexcept { return v_.size(); }

    private:
        std::deque<T> v_;
    };
};

/// Largest volume first: the unclassified box with the largest volume is processed next (a
/// heap). A run stopped by a budget has then decided the largest undecided boxes first, so the
/// volume left undecided shrinks as fast as bisection allows: the buffer of an *anytime* run
/// (`solve_options::refine`). Ties keep no particular order.
struct largest_volume_first {
    template <class T>
    class buffer {
    public:
        void push(T&& v) {
            double key = 0.0;
            if constexpr (requires { v.box; }) key = detail::paving_volume(v.box);  // the paver's entries
            else key = detail::paving_volume(v);                                    // plain boxes
            v_.push_back({key, std::move(v)});
            std::push_heap(v_.begin(), v_.end(), less);
        }
        T pop() {
            std::pop_heap(v_.begin(), v_.end(), less);
            T t = std::move(v_.back().second);
            v_.pop_back();
            return t;
        }
        bool empty() const noexcept { return v_.empty(); }
        std::size_t size() const noexcept { return v_.size(); }

    private:
        static bool less(const std::pair<double, T>& a, const std::pair<double, T>& b) { return a.first < b.first; }
        std::vector<std::pair<double, T>> v_;
    };
};

/// A buffer policy: a nested `buffer<T>` with push/pop/empty/size.
template <class P, class T>
concept PavingBuffer = std::default_initializable<typename P::template buffer<T>> &&
                       requires(typename P::template buffer<T>& b, const typename P::template buffer<T>& cb, T&& t) {
                           b.push(std::move(t));
                           { b.pop() } -> std::same_as<T>;
                           { cb.empty() } -> std::convertible_to<bool>;
                           { cb.size() } -> std::convertible_to<std::size_t>;
                       };

/// What the paver needs of a box: an interval type, a size and indexed components
/// (`interval_box<I, N>` models it).
template <class B>
concept PavingBox = std::copyable<B> && Interval<typename B::interval_type> &&
                    requires(B& b, const B& cb, std::size_t i) {
                        { cb.size() } -> std::convertible_to<std::size_t>;
                        { b[i] } -> std::same_as<typename B::interval_type&>;
                        { cb[i] } -> std::same_as<const typename B::interval_type&>;
                    };

/// An inner contractor narrows a box to a part that holds every point of the box *violating*
/// the constraints (a contractor of the complement, IBEX's CtcNotIn); the removed part is
/// certified VALID. The paver uses `contract_inner` when the InnerTest provides it.
template <class T, class Box>
concept InnerContractor = requires(T& t, Box& box) {
    { t.contract_inner(box) } -> std::same_as<void>;
};

/// Makes any `Contractor` of the complement of the constraint set an `InnerContractor`, e.g.
/// for `e ∈ [a, b]`: `inner_contractor{hc4(e <= a) | hc4(e >= b)}`.
/// VALID pieces are closed boxes sharing a face with the rest; for a closed constraint set
/// (non-strict inequalities, `∈ [a, b]`) every point of that face is a solution too, since the
/// complement is open; with a strict inequality the face may hold points where it is an equality.
template <class C>
struct inner_contractor {
    C complement;
    template <class Box>
        requires Contractor<C, Box>
    void contract_inner(Box& box) { complement.contract(box); }
};
template <class C>
inner_contractor(C) -> inner_contractor<C>;

/// Where an inner separator puts the pieces it carves off a box (see `InnerSeparator`): each
/// piece must lie inside the box as it was given to `separate`; pieces may share faces with
/// each other and with what is left of the box.
template <class Box, class State>
class piece_sink {
public:
    /// `f(Box&&, box_class, State&&)` receives each piece.
    template <class F>
    explicit piece_sink(F& f) noexcept
        : ctx_(&f), fn_([](void* c, Box&& b, box_class k, State&& s) { (*static_cast<F*>(c))(std::move(b), k, std::move(s)); }) {}

    /// Every point of `b` is a solution (certified).
    void valid(Box b) { fn_(ctx_, std::move(b), box_class::valid, State{}); }
    /// `b` holds no solution (certified); only counted.
    void discarded(Box b) { fn_(ctx_, std::move(b), box_class::discarded, State{}); }
    /// `b` is to be paved further, starting from state `s`.
    void pending(Box b, State s) { fn_(ctx_, std::move(b), box_class::pending, std::move(s)); }

private:
    void* ctx_;
    void (*fn_)(void*, Box&&, box_class, State&&);
};

/// The most general inner test: a type with a `state` (what it knows about a box, e.g. "the
/// constraint set holds everywhere in it"; default-constructed for the initial box, inherited by
/// both halves of a bisected box) and `verdict separate(Box& box, state& s, piece_sink<Box,
/// state>& sink)`. It may narrow `box` (removing only points that are not solutions, or that
/// it hands to `sink` as pieces) and update `s`; the verdict is for what is left of `box`:
/// satisfied — VALID, violated — discarded, undecided — bisected, or BOUNDARY when the
/// bisector declines. The paver calls it instead of the contractor and the inner test, so a
/// separator contracts for itself (the contractor given to the paver is then usually
/// `identity`) and the paver's `contractions` count stays at the number of boxes.
template <class T, class Box>
concept InnerSeparator = std::semiregular<typename T::state> &&
                         requires(T& t, Box& box, typename T::state& s, piece_sink<Box, typename T::state>& sink) {
                             { t.separate(box, s, sink) } -> std::same_as<verdict>;
                         };

namespace detail {
struct no_paving_state {};
template <class T>
struct paving_state {
    using type = no_paving_state;
};
template <class T>
    requires requires { typename T::state; }
struct paving_state<T> {
    using type = typename T::state;
};
}  // namespace detail

// ---- options, statistics, result ------------------------------------------------------------

/// Counters of a run. Volumes are floating-point sums of products of widths (each width
/// rounded up): a measure of the paving, not certified bounds.
struct paver_stats {
    std::size_t boxes = 0;         ///< boxes taken from the unclassified list and processed
    std::size_t contractions = 0;  ///< calls to the contractor
    std::size_t inner_tests = 0;   ///< calls to the inner test (or inner contractor)
    std::size_t bisections = 0;    ///< boxes split in two
    std::size_t valid = 0, boundary = 0, discarded = 0;
    std::size_t pending = 0;       ///< unclassified boxes (at the end: left when the run stopped)
    std::size_t peak_pending = 0;  ///< largest size the unclassified list reached
    double valid_volume = 0.0, boundary_volume = 0.0;
    double discarded_volume = 0.0;  ///< volume removed by contraction or by a violated test
    double pending_volume = 0.0;    ///< filled in at the end of the run only
    std::chrono::nanoseconds elapsed{0};
    termination reason = termination::completed;

    double seconds() const noexcept { return std::chrono::duration<double>(elapsed).count(); }
};

struct paver_options {
    static constexpr std::size_t unlimited = std::numeric_limits<std::size_t>::max();

    /// Stop after processing this many boxes (`termination::box_budget`).
    std::size_t max_boxes = unlimited;
    /// Stop when this much time has passed since `run` started (`termination::deadline`).
    std::optional<std::chrono::nanoseconds> time_limit;
    /// Stop at this instant (`termination::deadline`); with `time_limit`, the earlier wins.
    std::optional<std::chrono::steady_clock::time_point> deadline;
    /// Called every `progress_every` processed boxes with the current statistics (in
    /// round-to-nearest, outside the rounding guard); returning false cancels the run.
    std::function<bool(const paver_stats&)> progress;
    std::size_t progress_every = 1024;
    /// Record the bisection tree in `paving::tree`.
    bool record_tree = false;
};

/// One node of the bisection tree: the root is the initial box, the children of a bisected
/// node tile its contracted box.
template <class Box>
struct paving_node {
    static constexpr std::size_t no_parent = std::numeric_limits<std::size_t>::max();
    std::size_t parent = no_parent;
    Box box;         ///< as cut from the parent (the initial box at the root)
    Box contracted;  ///< after the contractor: empty when it proved no solution; `box` if pending
    box_class classification = box_class::pending;
};

/// The result of a run. Every solution in the initial box lies in a `valid`, `boundary` or
/// `pending` box; every point of a `valid` box is a solution.
template <class Box>
struct paving {
    std::vector<Box> valid;
    std::vector<Box> boundary;
    std::vector<Box> pending;             ///< unclassified boxes left by an early stop
    std::vector<paving_node<Box>> tree;   ///< empty unless `paver_options::record_tree`
    paver_stats stats;
};

namespace detail {

/// Product of the widths, 0 for an empty box (any empty component). Called inside `run`, where
/// the rounding guard holds the mode upward, so every width and product is rounded up without
/// the cost of `width`'s nextafter.
template <class Box>
double paving_volume(const Box& b) {
    double v = 1.0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        if (is_empty(b[i])) return 0.0;
        v *= upper(b[i]) - lower(b[i]);
    }
    return v;
}

template <class Box>
bool paving_empty(const Box& b) {
    for (std::size_t i = 0; i < b.size(); ++i)
        if (is_empty(b[i])) return true;
    return false;
}

template <class Box>
bool same_box(const Box& a, const Box& b) {
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(lower(a[i]) == lower(b[i]) && upper(a[i]) == upper(b[i]))) return false;
    return true;
}

/// Calls `emit` with boxes covering `outer` \ `inner` (inner ⊆ outer, non-empty): for each
/// dimension in turn, the slabs below and above `inner`, bounded in the dimensions before by
/// `inner` and after by `outer`. At most 2N boxes, overlapping only on faces.
template <class Box, class F>
void box_difference(const Box& outer, const Box& inner, F&& emit) {
    using I = typename Box::interval_type;
    Box rest = outer;
    for (std::size_t i = 0; i < outer.size(); ++i) {
        const double lo = lower(outer[i]), hi = upper(outer[i]);
        const double in_lo = lower(inner[i]), in_hi = upper(inner[i]);
        if (lo < in_lo) {
            Box piece = rest;
            piece[i] = I(lo, in_lo);
            emit(std::move(piece));
        }
        if (in_hi < hi) {
            Box piece = rest;
            piece[i] = I(in_hi, hi);
            emit(std::move(piece));
        }
        rest[i] = inner[i];
    }
}

}  // namespace detail

// ---- the paver ------------------------------------------------------------------------------

/// The inner test of a paver: a `BoxTest` (the paper) or an `InnerContractor`.
template <class T, class Box>
concept InnerTest = BoxTest<T, Box> || InnerContractor<T, Box> || InnerSeparator<T, Box>;

template <PavingBox Box, Contractor<Box> C, InnerTest<Box> T, Bisector<Box> B, class Buffer = depth_first>
class paver {
public:
    /// What an InnerSeparator carries along the paving (an empty struct for other inner tests).
    using state_type = typename detail::paving_state<T>::type;

private:
    struct entry {
        Box box;
        std::size_t node;  // index in the tree, or no_parent when no tree is recorded
        bisection_context context;
        [[no_unique_address]] state_type state{};
    };
    static_assert(PavingBuffer<Buffer, entry>, "certipose::paver: Buffer must provide buffer<T> with push/pop/empty/size");

public:
    using box_type = Box;
    using interval_type = typename Box::interval_type;
    using contractor_type = C;
    using inner_test_type = T;
    using bisector_type = B;
    using buffer_type = Buffer;

    /// The paver keeps its own copies of the policies (no state shared with the caller).
    paver(C contractor, T inner_test, B bisector, paver_options options = {})
        : contractor_(std::move(contractor)), test_(std::move(inner_test)), bisector_(std::move(bisector)),
          options_(std::move(options)) {
        check_options(options_);
    }

    /// Paves `initial` (Algorithm 1). Throws what the policies throw, and `invalid_argument` /
    /// `out_of_range` when the bisector returns a split outside the box.
    paving<Box> run(const Box& initial, std::stop_token stop = {}) {
        return run_from(std::span<const Box>(&initial, 1), {}, std::move(stop));
    }

    /// Paves several boxes at once (e.g. the BOUNDARY boxes of an earlier run, refined further),
    /// each starting from its state in `states` (the same length as `boxes`; empty: the default
    /// state for all). They are one run: one budget, one buffer, one result; with
    /// `record_tree` each is a root of the tree.
    paving<Box> run_from(std::span<const Box> boxes, std::span<const state_type> states, std::stop_token stop = {}) {
        using clock = std::chrono::steady_clock;
        if (!states.empty() && states.size() != boxes.size())
            throw invalid_argument("states", "paver::run_from: " + std::to_string(states.size()) + " states for " +
                                                 std::to_string(boxes.size()) + " boxes");
        check_options(options_);  // options() may have been edited since construction
        const rounding_guard<interval_type> guard{};
        const auto start = clock::now();
        std::optional<clock::time_point> deadline = options_.deadline;
        // A limit beyond the clock's range (e.g. nanoseconds::max()) means no limit, not overflow.
        if (const auto& limit = options_.time_limit;
            limit && *limit < std::chrono::duration_cast<std::chrono::nanoseconds>(clock::time_point::max() - start)) {
            const auto t = start + std::chrono::duration_cast<clock::duration>(*limit);
            if (!deadline || t < *deadline) deadline = t;
        }
        // Reading the clock costs ~20 ns; a box costs hundreds. Every 16th box keeps the check
        // cheap and the overshoot to a few microseconds.
        constexpr std::size_t clock_period = 16;

        paving<Box> out;
        paver_stats& st = out.stats;
        typename Buffer::template buffer<entry> list;
        const bool tree = options_.record_tree;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            std::size_t node = paving_node<Box>::no_parent;
            if (tree) {
                node = out.tree.size();
                out.tree.push_back(paving_node<Box>{paving_node<Box>::no_parent, boxes[i], boxes[i], box_class::pending});
            }
            list.push(entry{boxes[i], node, bisection_context{}, states.empty() ? state_type{} : states[i]});
        }
        // Only now: `states` may be this paver's own boundary_states() of its last run.
        boundary_states_.clear();
        st.peak_pending = list.size();

        termination reason = termination::completed;
        while (!list.empty()) {
            if (stop.stop_requested()) { reason = termination::cancelled; break; }
            if (st.boxes >= options_.max_boxes) { reason = termination::box_budget; break; }
            if (deadline && st.boxes % clock_period == 0 && clock::now() >= *deadline) {
                reason = termination::deadline;
                break;
            }

            entry e = list.pop();
            ++st.boxes;
            const double volume_in = detail::paving_volume(e.box);
            Box b = std::move(e.box);
            contractor_.contract(b);  // line 5: narrow before classifying
            ++st.contractions;
            const bool empty = detail::paving_empty(b);
            const double volume_kept = empty ? 0.0 : detail::paving_volume(b);
            if (const double removed = volume_in - volume_kept; removed > 0) st.discarded_volume += removed;
            std::size_t node = e.node;  // the tree node whose fate is decided below

            box_class cls = box_class::pending;  // undecided until the inner test or bisector speaks
            double volume_after = volume_kept;   // what the inner test left of b
            if (empty) {
                cls = box_class::discarded;
            } else {
                ++st.inner_tests;
                if constexpr (InnerSeparator<T, Box>) {
                    // Pieces carved off b become children of its tree node, like the pieces of an
                    // inner contractor; pending ones join the list with the state they were given.
                    const Box before = b;
                    bool carved = false;
                    double carved_volume = 0.0;
                    auto on_piece = [&](Box&& piece, box_class k, state_type&& ps) {
                        if (tree && !carved) {
                            out.tree[node].contracted = before;
                            out.tree[node].classification = box_class::bisected;
                        }
                        carved = true;
                        carved_volume += detail::paving_volume(piece);
                        std::size_t pn = paving_node<Box>::no_parent;
                        if (tree) {
                            pn = out.tree.size();
                            out.tree.push_back(paving_node<Box>{node, piece, piece, k});
                        }
                        switch (k) {
                            case box_class::valid: add_valid(out, std::move(piece)); break;
                            case box_class::discarded:
                                ++st.discarded;
                                st.discarded_volume += detail::paving_volume(piece);
                                break;
                            default:
                                list.push(entry{std::move(piece), pn, e.context, std::move(ps)});
                                if (list.size() > st.peak_pending) st.peak_pending = list.size();
                                break;
                        }
                    };
                    piece_sink<Box, state_type> sink(on_piece);
                    const verdict v = test_.separate(b, e.state, sink);
                    for (std::size_t i = 0; i < b.size(); ++i) b[i] = intersect(b[i], before[i]);
                    if (carved && tree) {
                        const std::size_t rest_node = out.tree.size();
                        out.tree.push_back(paving_node<Box>{node, b, b, box_class::pending});
                        node = rest_node;
                    }
                    const bool rest_empty = detail::paving_empty(b);
                    volume_after = rest_empty ? 0.0 : detail::paving_volume(b);
                    if (const double removed = volume_kept - carved_volume - volume_after; removed > 0)
                        st.discarded_volume += removed;
                    if (rest_empty) {
                        cls = box_class::discarded;
                        volume_after = 0.0;
                    } else if (v == verdict::satisfied) {
                        cls = box_class::valid;
                    } else if (v == verdict::violated) {
                        cls = box_class::discarded;
                    }
                } else if constexpr (InnerContractor<T, Box>) {
                    Box rest = b;
                    test_.contract_inner(rest);
                    // box_difference needs rest ⊆ b, even from a user contractor that widens.
                    for (std::size_t i = 0; i < rest.size(); ++i) rest[i] = intersect(rest[i], b[i]);
                    if (detail::paving_empty(rest)) {
                        cls = box_class::valid;  // no point of b violates the constraints
                    } else if (!detail::same_box(rest, b)) {
                        // b \ rest is certified VALID: emit it, keep classifying the rest.
                        std::size_t rest_node = node;
                        if (tree) {
                            out.tree[node].contracted = b;
                            out.tree[node].classification = box_class::bisected;
                        }
                        detail::box_difference(b, rest, [&](Box&& piece) {
                            if (tree)
                                out.tree.push_back(paving_node<Box>{node, piece, piece, box_class::valid});
                            add_valid(out, std::move(piece));
                        });
                        if (tree) {
                            rest_node = out.tree.size();
                            out.tree.push_back(paving_node<Box>{node, rest, rest, box_class::pending});
                        }
                        node = rest_node;
                        b = std::move(rest);
                    }
                } else {
                    switch (test_.test(std::as_const(b))) {  // lines 10–11
                        case verdict::satisfied: cls = box_class::valid; break;
                        case verdict::violated: cls = box_class::discarded; break;
                        case verdict::undecided: break;
                    }
                }
            }
            if (cls == box_class::pending) {
                std::optional<split> s;
                if constexpr (ContextualBisector<B, Box>)
                    s = bisector_.choose(std::as_const(b), e.context);
                else
                    s = bisector_.choose(std::as_const(b));
                if (!s) {
                    cls = box_class::boundary;  // line 16: every dimension narrower than ε
                } else {
                    cls = box_class::bisected;
                    check_split(b, *s);
                    ++st.bisections;
                    const std::size_t d = s->dimension;
                    Box left = b, right = b;
                    left[d] = interval_type(lower(b[d]), s->point);
                    right[d] = interval_type(s->point, upper(b[d]));
                    const bisection_context child{e.context.depth + 1, d};
                    std::size_t ln = paving_node<Box>::no_parent, rn = ln;
                    if (tree) {
                        ln = out.tree.size();
                        out.tree.push_back(paving_node<Box>{node, left, left, box_class::pending});
                        rn = out.tree.size();
                        out.tree.push_back(paving_node<Box>{node, right, right, box_class::pending});
                    }
                    // Second half first, so a depth-first buffer explores the first half first.
                    list.push(entry{std::move(right), rn, child, e.state});
                    list.push(entry{std::move(left), ln, child, std::move(e.state)});
                    if (list.size() > st.peak_pending) st.peak_pending = list.size();
                }
            }

            if (tree) {
                auto& n = out.tree[node];
                n.contracted = b;
                n.classification = cls;
            }
            switch (cls) {
                case box_class::valid: add_valid(out, std::move(b)); break;
                case box_class::boundary:
                    ++st.boundary;
                    st.boundary_volume += detail::paving_volume(b);
                    out.boundary.push_back(std::move(b));
                    if constexpr (InnerSeparator<T, Box>) boundary_states_.push_back(std::move(e.state));
                    break;
                case box_class::discarded:
                    ++st.discarded;
                    if (!empty) st.discarded_volume += volume_after;  // the test proved it infeasible
                    break;
                default: break;
            }

            if (options_.progress && st.boxes % options_.progress_every == 0) {
                st.pending = list.size();
                st.elapsed = std::chrono::duration_cast<std::chrono::nanoseconds>(clock::now() - start);
                // User code expects the ordinary rounding mode.
                const detail::round_to_nearest_scope nearest{};
                if (!options_.progress(std::as_const(st))) {
                    reason = termination::cancelled;
                    break;
                }
            }
        }

        // Whatever is left is unclassified: return it so no solution is lost.
        st.pending = 0;
        while (!list.empty()) {
            entry e = list.pop();
            ++st.pending;
            st.pending_volume += detail::paving_volume(e.box);
            out.pending.push_back(std::move(e.box));
        }
        st.reason = reason;
        st.elapsed = std::chrono::duration_cast<std::chrono::nanoseconds>(clock::now() - start);
        return out;
    }

    const paver_options& options() const noexcept { return options_; }
    paver_options& options() noexcept { return options_; }
    C& contractor() noexcept { return contractor_; }
    const C& contractor() const noexcept { return contractor_; }
    T& inner_test() noexcept { return test_; }
    const T& inner_test() const noexcept { return test_; }
    B& bisector() noexcept { return bisector_; }
    const B& bisector() const noexcept { return bisector_; }
    /// With an InnerSeparator: the state of each BOUNDARY box of the last run, in the order of
    /// `paving::boundary` (empty for other inner tests).
    const std::vector<state_type>& boundary_states() const noexcept { return boundary_states_; }

private:
    static void check_options(const paver_options& o) {
        if (o.progress && o.progress_every == 0)
            throw invalid_argument("progress_every",
                                   "paver: progress_every must be positive when a progress callback is set, got 0");
    }

    static void add_valid(paving<Box>& out, Box&& b) {
        ++out.stats.valid;
        out.stats.valid_volume += detail::paving_volume(b);
        out.valid.push_back(std::move(b));
    }

    // A user bisector that returns a split outside the box would make the paver loop forever.
    static void check_split(const Box& b, const split& s) {
        if (s.dimension >= b.size()) throw out_of_range("split dimension", s.dimension, b.size());
        const auto& c = b[s.dimension];
        if (!(lower(c) < s.point && s.point < upper(c)))
            throw invalid_argument("split point", "paver: the bisector's split point " + certipose::detail::format_double(s.point) +
                                                      " is not strictly inside dimension " +
                                                      std::to_string(s.dimension) + " [" + certipose::detail::format_double(lower(c)) +
                                                      ", " + certipose::detail::format_double(upper(c)) + "]");
    }

    C contractor_;
    T test_;
    B bisector_;
    paver_options options_;
    std::vector<state_type> boundary_states_;
};

/// One-call form: `pave(box, contractor, inner_test, bisector, options)`; the buffer policy is
/// the first template argument (`pave<breadth_first>(...)`).
template <class Buffer = depth_first, PavingBox Box, Contractor<Box> C, InnerTest<Box> T, Bisector<Box> B>
paving<Box> pave(const Box& initial, C contractor, T inner_test, B bisector, paver_options options = {},
                 std::stop_token stop = {}) {
    return paver<Box, C, T, B, Buffer>(std::move(contractor), std::move(inner_test), std::move(bisector),
                                       std::move(options))
        .run(initial, std::move(stop));
}

}  // namespace certipose
