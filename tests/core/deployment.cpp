// Deployment plans (coverage/deployment.hpp): greedy maximum coverage against the brute-force
// optimum on small instances, its (1 − 1/e) guarantee, the coverage-target mode, the area lower
// bound, and bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <certipose/coverage/deployment.hpp>

using namespace certipose;

namespace {

struct instance {
    std::vector<deployment_candidate> candidates;
    std::vector<double> areas;
};

instance random_instance(std::mt19937& rng, std::size_t n_candidates, std::size_t n_facets) {
    instance in;
    std::uniform_real_distribution<double> area(0.1, 1.0);
    for (std::size_t f = 0; f < n_facets; ++f) in.areas.push_back(area(rng));
    std::bernoulli_distribution take(0.3);
    for (std::size_t j = 0; j < n_candidates; ++j) {
        deployment_candidate c;
        for (std::size_t f = 0; f < n_facets; ++f)
            if (take(rng)) c.facets.push_back(f);
        in.candidates.push_back(c);
    }
    return in;
}

double covered(const instance& in, unsigned mask) {
    std::vector<char> in_set(in.areas.size(), 0);
    double a = 0;
    for (std::size_t j = 0; j < in.candidates.size(); ++j)
        if (mask >> j & 1U)
            for (std::size_t f : in.candidates[j].facets)
                if (!in_set[f]) in_set[f] = 1, a += in.areas[f];
    return a;
}

}  // namespace

TEST_CASE("greedy maximum coverage is within (1 - 1/e) of the brute-force optimum, and its fields agree") {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 40; ++trial) {
        const instance in = random_instance(rng, 10, 14);
        for (std::size_t k = 1; k <= 4; ++k) {
            double best = 0;
            for (unsigned mask = 0; mask < (1U << in.candidates.size()); ++mask)
                if (static_cast<std::size_t>(__builtin_popcount(mask)) <= k) best = std::max(best, covered(in, mask));
            deployment_options o;
            o.cameras = k;
            const deployment_plan p = plan_greedy(in.candidates, in.areas, o);
            REQUIRE(p.chosen.size() <= k);
            unsigned mask = 0;
            for (std::size_t j : p.chosen) mask |= 1U << j;
            CHECK(p.certified_area == doctest::Approx(covered(in, mask)));
            CHECK(p.certified_area <= best + 1e-12);
            CHECK(p.certified_area >= (1 - 1 / std::exp(1.0)) * best - 1e-12);
            // The curve rises, ends at the certified area; covered_by names a chosen box certifying the facet.
            REQUIRE(p.curve.size() == p.chosen.size());
            for (std::size_t i = 1; i < p.curve.size(); ++i) CHECK(p.curve[i] > p.curve[i - 1]);
            if (!p.curve.empty()) CHECK(p.curve.back() == doctest::Approx(p.certified_area));
            for (std::size_t f = 0; f < in.areas.size(); ++f)
                if (p.covered_by[f] != deployment_plan::npos) {
                    const auto& fs = in.candidates[p.chosen[p.covered_by[f]]].facets;
                    CHECK(std::find(fs.begin(), fs.end(), f) != fs.end());
                }
            // No plan of fewer boxes than the lower bound certifies as much.
            std::size_t fewest = in.candidates.size();
            for (unsigned m = 0; m < (1U << in.candidates.size()); ++m)
                if (covered(in, m) >= p.certified_area * (1 - 1e-12))
                    fewest = std::min<std::size_t>(fewest, static_cast<std::size_t>(__builtin_popcount(m)));
            CHECK(p.lower_bound <= fewest);
            CHECK(fewest <= p.chosen.size());
        }
    }
}

TEST_CASE("a coverage target: greedy stops once the share of the coverable area is certified") {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        const instance in = random_instance(rng, 9, 12);
        deployment_options o;
        o.coverage = 0.9;
        const deployment_plan p = plan_greedy(in.candidates, in.areas, o);
        CHECK(p.coverable_area == doctest::Approx(union_area(in.candidates, in.areas)));
        CHECK(p.certified_area >= 0.9 * p.coverable_area * (1 - 1e-9));
        // It stopped at the first box reaching the target.
        if (p.curve.size() >= 2) CHECK(p.curve[p.curve.size() - 2] < 0.9 * p.coverable_area);
        // plan_of of greedy's choice is the same plan.
        const deployment_plan q = plan_of(in.candidates, in.areas, p.chosen);
        CHECK(q.certified_area == doctest::Approx(p.certified_area));
        CHECK(q.chosen.size() == p.chosen.size());
    }
}

TEST_CASE("the greedy bound never exceeds the fewest boxes certifying a target (brute force)") {
    std::mt19937 rng(19);
    std::size_t above_area_bound = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const instance in = random_instance(rng, 10, 14);
        for (const double share : {0.5, 0.8, 0.95, 1.0}) {
            deployment_options o;
            o.coverage = share;
            const deployment_plan p = plan_greedy(in.candidates, in.areas, o);
            // Targets at and between the curve's points.
            for (std::size_t k = 0; k < p.curve.size(); ++k)
                for (const double t : {p.curve[k], k > 0 ? 0.5 * (p.curve[k - 1] + p.curve[k]) : 0.5 * p.curve[k]}) {
                    std::size_t fewest = in.candidates.size() + 1;
                    for (unsigned m = 0; m < (1U << in.candidates.size()); ++m)
                        if (covered(in, m) >= t * (1 - 1e-12))
                            fewest = std::min<std::size_t>(fewest, static_cast<std::size_t>(__builtin_popcount(m)));
                    const std::size_t bound = greedy_lower_bound(p.curve, t);
                    CAPTURE(trial);
                    CAPTURE(t);
                    CHECK(bound >= 1);
                    CHECK(bound <= fewest);
                    above_area_bound += bound > area_lower_bound(in.candidates, in.areas, t);
                }
            CHECK(greedy_lower_bound(p.curve, p.certified_area) <= p.chosen.size());
        }
    }
    CHECK(above_area_bound > 0);  // it adds something to the area bound
    CHECK(greedy_lower_bound({}, 0.0) == 0);
    CHECK(greedy_lower_bound({1.0, 2.0}, 5.0) == 2);  // out of the curve's reach: at least its length
}

TEST_CASE("deployment input errors name the value") {
    const std::vector<double> areas{1.0, 2.0};
    const std::vector<deployment_candidate> good{{{0}}, {{1}}};
    deployment_options zero;
    zero.cameras = 0;
    CHECK_THROWS_AS(plan_greedy(good, areas, zero), invalid_argument);
    deployment_options share;
    share.coverage = 1.5;
    CHECK_THROWS_WITH_AS(plan_greedy(good, areas, share), doctest::Contains("1.5"), invalid_argument);
    const std::vector<deployment_candidate> bad{{{0, 2}}};
    CHECK_THROWS_AS(plan_greedy(bad, areas), out_of_range);
    CHECK_THROWS_AS(plan_of(good, areas, {5}), out_of_range);
    // A facet listed twice would count its area twice (and GLPK would abort on the repeated entry).
    const std::vector<deployment_candidate> repeated{{{1, 1}}};
    CHECK_THROWS_WITH_AS(plan_greedy(repeated, areas), doctest::Contains("candidate 0 lists facet 1 twice"), invalid_argument);
    CHECK_THROWS_AS(union_area(repeated, areas), invalid_argument);
    // Nothing to cover: an empty plan, not an error.
    const deployment_plan none = plan_greedy({}, areas);
    CHECK(none.chosen.empty());
    CHECK(none.certified_area == 0.0);
    CHECK(none.total_area == doctest::Approx(3.0));
}
