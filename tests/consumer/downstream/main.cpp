// A downstream project as a user of the library writes one, built against the installed package
// (tests/consumer/installed): it recomposes the pipeline without touching certipose::detail.
//  1. its own position constraint set, with a run-time parameter (a floor the camera stays above);
//  2. the contraction swapped for ACID shaving, with its own options;
//  3. a micro-benchmark (Google Benchmark) of the contractor the pipeline really runs;
//  4. a solve, whose VALID boxes it checks against its own constraint.
#include <certipose/cgal.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace downstream {

/// "The camera stays at or above `height`" (metres, the part's frame): a position constraint set
/// with a run-time parameter, modelled on certipose::keep_in_sphere.
template <certipose::Interval I>
class above_floor {
public:
    struct parameters {
        double height = -std::numeric_limits<double>::infinity();
    };

    above_floor(const certipose::position_problem&, const parameters& p)
        : height_(checked(p.height)), contract_(certipose::hc4(z >= height_)), below_(certipose::not_in(z >= height_)) {}

    void contract(certipose::position_box<I>& box) { contract_.contract(box); }
    /// Keeps the positions of `box` that may lie below the floor (inner contraction).
    void contract_complement(certipose::position_box<I>& box) const { below_.contract(box); }
    certipose::verdict test(const certipose::position_box<I>& box) const {
        if (certipose::is_empty(box)) return certipose::verdict::violated;
        if (certipose::lower(box[2]) >= height_) return certipose::verdict::satisfied;
        if (certipose::upper(box[2]) < height_) return certipose::verdict::violated;
        return certipose::verdict::undecided;
    }

private:
    static constexpr certipose::var<2> z{};
    static double checked(double h) {
        if (std::isnan(h)) throw certipose::invalid_argument("height", "above_floor: height must not be NaN");
        return h;
    }
    double height_;
    decltype(certipose::hc4(z >= 0.0)) contract_;
    decltype(certipose::not_in(z >= 0.0)) below_;
};

template <class I>
using floor_set = certipose::all_of<certipose::paper_position_constraints<I>, above_floor<I>>;

// Two changes to the defaults, in any order.
using pipeline = certipose::pose_solver<certipose::policies<
    certipose::with_contraction<certipose::contraction::acid_shaving>, certipose::with_constraints<floor_set>>>;

constexpr double floor_height = 0.4;

const certipose::sample_part& part() {
    static const certipose::sample_part p = certipose::make_sample_part();
    return p;
}

const pipeline& solver() {
    static const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    static const pipeline s(part().mesh, camera, {.min_view_angle = 0.35},
                            {.constraints = {{}, {.height = floor_height}},
                             .contraction = {.options = {.s3b = 20, .scid = 2}}});
    return s;
}

// The contractor the position stage runs for the facet (ACID on the floor set's HC4), on the
// facet's initial search box.
void BM_pipeline_contractor(benchmark::State& state) {
    auto contractor = solver().position_contractor(part().facet_of_interest);
    const certipose::position_box<certipose::boost_interval> start = contractor.constraint_set().initial_box();
    for (auto _ : state) {
        auto box = start;
        contractor.contract(box);
        benchmark::DoNotOptimize(box);
    }
}
BENCHMARK(BM_pipeline_contractor);

int fail(const std::string& what) {
    std::fprintf(stderr, "downstream: %s\n", what.c_str());
    return 1;
}

}  // namespace downstream

using namespace downstream;

int main(int argc, char** argv) {
    static_assert(std::is_same_v<pipeline::contraction_type, certipose::contraction::acid_shaving>);
    if (solver().contraction().options.s3b != 20) return fail("the contraction policy's options were not kept");

    // The contractor the pipeline runs narrows the initial box, and never below the floor.
    auto contractor = solver().position_contractor(part().facet_of_interest);
    auto box = contractor.constraint_set().initial_box();
    const auto initial = box;
    contractor.contract(box);
    if (certipose::is_empty(box) || certipose::lower(box[2]) < floor_height || box == initial)
        return fail("the pipeline's contractor did not narrow the box to the floor");

    const auto result = solver().solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    if (result.stats.valid == 0) return fail("no VALID box");
    // The certifier proves a box again with the solver's proofs ("not proven" is not "invalid":
    // a box the paving certified from its ancestors' shadows may need more than one walk).
    auto certifier = solver().certifier(part().facet_of_interest);
    std::size_t reproved = 0;
    for (const auto& b : result.boxes) {
        if (b.cls != certipose::box_class::valid) continue;
        if (certipose::lower(b.box.position[2]) < floor_height) return fail("a VALID box reaches below the floor");
        reproved += certifier(b.box);
    }
    if (reproved == 0) return fail("the certifier proves none of the VALID boxes");
    std::printf("downstream: %zu VALID boxes above z = %.2f m, %zu proven again by the certifier (%s)\n",
                result.stats.valid, floor_height, reproved, certipose::boundary_summary(result.stats).c_str());

    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
