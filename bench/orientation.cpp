// The orientation stage (include/certipose/orientation/): one 6D certification (`certify_fov`)
// on the two paths it takes — the centred form (narrow roll) and the roll-free cone (β over the
// whole circle) — and the orientation work per certified position box for the default policy
// (`paper_orientation`) and the paving policy. A 3 cm facet 0.5–0.55 m from a 5 cm position
// box, the case-study camera, ε_o = 0.38 rad; boost_interval. Counters: certify_fov calls
// per position box, and the certified widths of φ, γ, β.
#include <benchmark/benchmark.h>

#include <certipose/camera/thin_lens_camera.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/orientation/certify.hpp>
#include <certipose/orientation/paper_orientation.hpp>
#include <certipose/orientation/paving_orientation.hpp>

#include <array>
#include <cstddef>
#include <random>
#include <vector>

namespace {

using I = certipose::boost_interval;

certipose::thin_lens_camera camera() {
    return certipose::thin_lens_camera({.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6,
                                        .max_blur_circle = 6.9e-6, .pixel_pitch = 3.45e-6, .width_px = 2448,
                                        .height_px = 2048});
}

certipose::facet make_facet(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    certipose::facet f;
    f.v = {a, b, c};
    const Eigen::Vector3d n = (b - a).cross(c - a);
    f.normal = n.normalized();
    f.area = n.norm() / 2;
    f.centroid = (a + b + c) / 3.0;
    f.bbox.setEmpty();
    for (const auto& p : f.v) f.bbox.extend(p);
    return f;
}

const certipose::facet facet3cm = make_facet({0, 0, 0}, {0.03, 0, 0}, {0, 0.03, 0});

certipose::position_box<I> position5cm() {
    return certipose::position_box<I>::from_bounds({{{0.20, 0.25}, {0.10, 0.15}, {0.50, 0.55}}});
}

/// The certified box of the default policy for the benchmark's position box, with its roll
/// narrowed to `roll` (so the centred form, not the cone, decides).
certipose::orientation_box<I> certified_box(double roll) {
    auto e = certipose::paper_orientation{}.orient(position5cm(), facet3cm, camera(), 0.38).boxes.at(0);
    const certipose::rounding_guard<I> guard;
    e[1] = I(certipose::mid(e[1]) - 0.05, certipose::mid(e[1]) + 0.05);
    e[0] = I(certipose::mid(e[0]) - 0.05, certipose::mid(e[0]) + 0.05);
    if (roll < 3.0) e[2] = I(-roll, roll);
    return e;
}

void BM_certify_fov(benchmark::State& state) {
    const auto cam = camera();
    const certipose::fov_frustum<I> frustum(cam);
    const auto p = position5cm();
    const auto e = certified_box(0.2);
    std::size_t satisfied = 0;
    for (auto _ : state) {
        const auto v = certipose::certify_fov(p, e, facet3cm, frustum);
        satisfied += v == certipose::verdict::satisfied;
        benchmark::DoNotOptimize(v);
    }
    state.counters["satisfied"] = benchmark::Counter(static_cast<double>(satisfied), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_certify_fov);

void BM_certify_fov_any_roll(benchmark::State& state) {
    const auto cam = camera();
    const certipose::fov_frustum<I> frustum(cam);
    const auto p = position5cm();
    const auto e = certified_box(4.0);  // β over the whole circle: the roll-free cone decides
    std::size_t satisfied = 0;
    for (auto _ : state) {
        const auto v = certipose::certify_fov(p, e, facet3cm, frustum);
        satisfied += v == certipose::verdict::satisfied;
        benchmark::DoNotOptimize(v);
    }
    state.counters["satisfied"] = benchmark::Counter(static_cast<double>(satisfied), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_certify_fov_any_roll);

template <class Policy>
void per_position_box(benchmark::State& state) {
    const auto cam = camera();
    const auto p = position5cm();
    const Policy policy;
    certipose::orientation_result<I> r;
    for (auto _ : state) {
        r = policy.orient(p, facet3cm, cam, 0.38);
        benchmark::DoNotOptimize(r);
    }
    state.counters["certifications"] = static_cast<double>(r.certifications);
    state.counters["boxes"] = static_cast<double>(r.boxes.size());
    if (!r.boxes.empty()) {
        state.counters["phi_width"] = certipose::width(r.boxes[0][0]);
        state.counters["gamma_width"] = certipose::width(r.boxes[0][1]);
        state.counters["beta_width"] = certipose::width(r.boxes[0][2]);
    }
}

void BM_paper_orientation_per_position_box(benchmark::State& state) {
    per_position_box<certipose::paper_orientation>(state);
}
BENCHMARK(BM_paper_orientation_per_position_box);

/// The same over 64 random facets (5 mm – 12 cm) and position boxes (≤ 10 cm) 0.45–0.85 m
/// away, every fourth straight down or up the z axis; time per position box.
void BM_paper_orientation_random_boxes(benchmark::State& state) {
    const auto cam = camera();
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
    std::vector<std::pair<certipose::facet, certipose::position_box<I>>> cases;
    for (int i = 0; i < 64; ++i) {
        const Eigen::Vector3d c(0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng));
        const double s = 0.005 + 0.115 * u01(rng);
        const auto f = make_facet(c + s * Eigen::Vector3d(u(rng), u(rng), u(rng)), c + s * Eigen::Vector3d(u(rng), u(rng), u(rng)),
                                  c + s * Eigen::Vector3d(u(rng), u(rng), u(rng)));
        Eigen::Vector3d dir = i % 4 == 1 ? Eigen::Vector3d(0.01, 0, 1) : i % 4 == 3 ? Eigen::Vector3d(0, 0.01, -1)
                                                                                     : Eigen::Vector3d(u(rng), u(rng), u(rng));
        const Eigen::Vector3d centre = f.centroid + (0.45 + 0.4 * u01(rng)) * dir.normalized();
        const double r = 0.05 * u01(rng);
        cases.emplace_back(f, certipose::position_box<I>::from_bounds(
                                  {{{centre.x() - r, centre.x() + r}, {centre.y() - r, centre.y() + r},
                                    {centre.z() - r, centre.z() + r}}}));
    }
    const certipose::paper_orientation policy;
    std::size_t certifications = 0, certified = 0, calls = 0;
    for (auto _ : state) {
        for (const auto& [f, p] : cases) {
            const auto r = policy.orient(p, f, cam, 0.38);
            certifications += r.certifications;
            certified += !r.boxes.empty();
            ++calls;
            benchmark::DoNotOptimize(r);
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(calls));
    state.counters["certifications_per_box"] = static_cast<double>(certifications) / static_cast<double>(calls);
    state.counters["certified_fraction"] = static_cast<double>(certified) / static_cast<double>(calls);
}
BENCHMARK(BM_paper_orientation_random_boxes);

/// The eight octants of the 5 cm box one after the other, as the small boxes of one cell of ε_p
/// reach the orientation stage: arg 0 searches each from scratch, arg 1 carries a
/// paper_orientation::hint from box to box (what pose_solver does per cell). Time per octant.
void BM_paper_orientation_octants(benchmark::State& state) {
    const auto cam = camera();
    const auto whole = position5cm();
    std::vector<certipose::position_box<I>> octants;
    for (std::size_t k = 0; k < 8; ++k) {
        certipose::position_box<I> q;
        for (std::size_t d = 0; d < 3; ++d) {
            const double m = certipose::mid(whole[d]);
            q[d] = (k >> d) & 1 ? I(m, certipose::upper(whole[d])) : I(certipose::lower(whole[d]), m);
        }
        octants.push_back(q);
    }
    const certipose::paper_orientation policy;
    const bool hinted = state.range(0) != 0;
    std::size_t certifications = 0, certified = 0, calls = 0;
    double phi = 0;
    for (auto _ : state) {
        certipose::paper_orientation::hint hint;
        for (const auto& p : octants) {
            const auto r = hinted ? policy.orient(p, facet3cm, cam, 0.38, hint) : policy.orient(p, facet3cm, cam, 0.38);
            certifications += r.certifications;
            certified += !r.boxes.empty();
            if (!r.boxes.empty()) phi += certipose::width(r.boxes[0][0]);
            ++calls;
            benchmark::DoNotOptimize(r);
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(calls));
    state.counters["certifications_per_box"] = static_cast<double>(certifications) / static_cast<double>(calls);
    state.counters["certified_fraction"] = static_cast<double>(certified) / static_cast<double>(calls);
    state.counters["mean_phi_width"] = certified ? phi / static_cast<double>(certified) : 0.0;
}
BENCHMARK(BM_paper_orientation_octants)->Arg(0)->Arg(1);

void BM_paving_orientation_per_position_box(benchmark::State& state) {
    per_position_box<certipose::paving_orientation>(state);
}
BENCHMARK(BM_paving_orientation_per_position_box)->Unit(benchmark::kMillisecond);

}  // namespace
