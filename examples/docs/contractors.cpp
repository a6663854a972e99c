// docs/contractors.md: writing and composing contractors.
#include <certipose/certipose.hpp>  // or <certipose/contractors.hpp> + an interval backend

#include <cstdio>
#include <limits>

// A user-written contractor: the camera stays above a table top at height h (z >= h).
// Modelling certipose::Contractor is all it takes to plug into compose / & / | / fixpoint / acid.
struct above_table {
    using certipose_contractor = void;  // opt in to the & and | operators
    double h;

    template <certipose::Interval I, std::size_t N>
    void contract(certipose::interval_box<I, N>& box) const {
        // Only bounds are read and compared: no interval arithmetic, so no rounding_guard needed.
        box[2] = certipose::intersect(box[2], I(h, std::numeric_limits<double>::infinity()));
        if (certipose::is_empty(box[2])) certipose::set_empty(box);
    }
};

static void print(const char* what, const certipose::interval_box<certipose::boost_interval, 3>& b) {
    std::printf("%-28s", what);
    for (const auto& c : b) std::printf(" [%.4f, %.4f]", lower(c), upper(c));
    std::printf("\n");
}

int main() {
    using namespace certipose;
    using I = boost_interval;
    using box = interval_box<I, 3>;
    constexpr var<0> x;
    constexpr var<1> y;
    constexpr var<2> z;

    // The spherical shell around (1, 2, 0.5), radii 0.3 and 0.5, and the same set written with
    // every variable twice (HC4 alone is weak on it; ACID's shaving helps).
    const auto shell = in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25);
    const auto expanded = in(sqr(x) + sqr(y) + sqr(z) - 2.0 * x - 4.0 * y - z + 5.25, 0.09, 0.25);
    const box start = box::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}});

    box b = start;
    hc4(shell).contract(b);  // one HC4 contraction
    print("hc4(shell):", b);

    // Every name is also reachable qualified, without `using namespace` or ADL.
    const auto half_space = certipose::dot(certipose::vec(x, y, z), certipose::vec(1.0, 1.0, 0.0)) <= 2.8;
    const auto shell_q = certipose::in(certipose::sqr(x - 1.0) + certipose::sqr(y - 2.0) + certipose::sqr(z - 0.5), 0.09, 0.25);
    b = start;
    certipose::hc4(shell_q, half_space).contract(b);
    print("hc4(shell, x + y <= 2.8):", b);

    // Compose at compile time: sequence with &, repeat with fixpoint. No virtual call anywhere.
    auto pipeline = fixpoint(above_table{0.6} & hc4(expanded) & acid(hc4(expanded)), 1e-3);
    static_assert(Contractor<decltype(pipeline), box>);
    b = start;
    pipeline.contract(b);
    print("fixpoint(table & hc4 & acid):", b);

    // Union: the hull of what each part keeps (a disjunction).
    auto left_or_right = hc4(x <= 0.7) | hc4(x >= 1.3);
    b = box::from_bounds({{{0.9, 5}, {-5, 5}, {-5, 5}}});
    left_or_right.contract(b);
    print("x <= 0.7 | x >= 1.3:", b);

    // Box tests for the paver: evaluation only, and the stronger negation (CtcNotIn) proof.
    const box inside = box::from_bounds({{{0.99, 1.01}, {2.39, 2.41}, {0.49, 0.51}}});
    const eval_test by_evaluation(expanded);
    const not_in_test by_negation(expanded);
    const verdict v1 = by_evaluation.test(inside), v2 = by_negation.test(inside);
    std::printf("expanded shell, small box: eval_test %s, not_in_test %s\n",
                v1 == verdict::satisfied ? "satisfied" : "undecided",
                v2 == verdict::satisfied ? "satisfied" : "undecided");
    return v2 == verdict::satisfied && lower(b[0]) == 1.3 ? 0 : 1;
}
