// docs/paver.md — paving the spherical shell (x−1)² + (y−2)² + (z−0.5)² ∈ [0.09, 0.25] with the
// paper's Algorithm 1: HC4 outer contractor, a proof-of-inclusion inner contractor,
// largest-first bisection, depth-first; then budgets, progress, cancellation and the tree.
#include <certipose/certipose.hpp>

#include <chrono>
#include <cstdio>
#include <stop_token>

int main() {
    using namespace certipose;
    using box = interval_box<boost_interval, 3>;

    constexpr var<0> x;
    constexpr var<1> y;
    constexpr var<2> z;
    const auto shell = in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25);
    const box search = box::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}});

    // 1. One call: contractor, inner test (here an inner contractor), bisector.
    const paving<box> r = pave(search, hc4(shell), inner_contractor{not_in(shell)}, largest_first(0.05));
    std::printf("valid %zu boxes (volume %.4f), boundary %zu (%.4f), %zu boxes processed in %.2f ms\n",
                r.stats.valid, r.stats.valid_volume, r.stats.boundary, r.stats.boundary_volume, r.stats.boxes,
                r.stats.seconds() * 1e3);
    const box& first = r.valid.front();  // every point of it satisfies the constraint
    std::printf("first VALID box [%g, %g] x [%g, %g] x [%g, %g]\n", lower(first[0]), upper(first[0]),
                lower(first[1]), upper(first[1]), lower(first[2]), upper(first[2]));

    // 2. A paver object: policies are copied in; breadth-first; a per-dimension precision and
    //    IBEX's split ratio; limits, a progress callback and the bisection tree.
    paver_options options;
    options.max_boxes = 100'000;
    options.time_limit = std::chrono::seconds(1);
    options.progress_every = 2'000;
    options.progress = [](const paver_stats& s) {
        std::printf("  ... %zu boxes, %zu valid, %zu pending\n", s.boxes, s.valid, s.pending);
        return true;  // false would cancel the run
    };
    options.record_tree = true;
    paver<box, decltype(hc4(shell)), decltype(eval_test(shell)), round_robin, breadth_first> p{
        hc4(shell), eval_test(shell), round_robin({0.05, 0.05, 0.1}, 0.45), options};
    std::stop_source stop;  // stop.request_stop() from any thread cancels the run
    const paving<box> t = p.run(search, stop.get_token());
    std::printf("%s after %zu boxes; tree of %zu nodes\n", to_string(t.stats.reason), t.stats.boxes, t.tree.size());

    // 3. Walk the tree: the depth of the deepest BOUNDARY leaf.
    std::size_t deepest = 0;
    for (const auto& node : t.tree) {
        if (node.classification != box_class::boundary) continue;
        std::size_t depth = 0;
        for (std::size_t k = node.parent; k != paving_node<box>::no_parent; k = t.tree[k].parent) ++depth;
        if (depth > deepest) deepest = depth;
    }
    std::printf("deepest boundary leaf at depth %zu\n", deepest);

    // 4. A budget: what was not classified comes back as `pending`, so VALID ∪ BOUNDARY ∪
    //    pending still covers every solution.
    options = {};
    options.max_boxes = 500;
    const paving<box> cut = pave(search, hc4(shell), eval_test(shell), largest_first(0.05), options);
    std::printf("%s: %zu valid, %zu boundary, %zu pending boxes\n", to_string(cut.stats.reason), cut.valid.size(),
                cut.boundary.size(), cut.pending.size());
    return r.stats.valid > 0 && cut.stats.reason == termination::box_budget ? 0 : 1;
}
