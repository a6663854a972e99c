// The covering program of coverage/glpk_deployment.hpp against brute force: the LP bound never
// exceeds the fewest boxes certifying a target, and the exact answer is that fewest number.
#include <doctest/doctest.h>

#include <chrono>
#include <cstddef>
#include <random>
#include <vector>

#include <certipose/coverage/glpk_deployment.hpp>

using namespace certipose;

TEST_CASE("GLPK: the LP bound is a lower bound and the exact plan is optimal (brute force)") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> area(0.1, 1.0);
    std::bernoulli_distribution take(0.3);
    for (int trial = 0; trial < 25; ++trial) {
        std::vector<double> areas;
        for (int f = 0; f < 12; ++f) areas.push_back(area(rng));
        std::vector<deployment_candidate> cands(9);
        for (auto& c : cands)
            for (std::size_t f = 0; f < areas.size(); ++f)
                if (take(rng)) c.facets.push_back(f);
        const double target = 0.8 * union_area(cands, areas);
        std::size_t fewest = cands.size() + 1;
        for (unsigned m = 0; m < (1U << cands.size()); ++m) {
            std::vector<deployment_candidate> chosen;
            for (std::size_t j = 0; j < cands.size(); ++j)
                if (m >> j & 1U) chosen.push_back(cands[j]);
            if (union_area(chosen, areas) >= target)
                fewest = std::min<std::size_t>(fewest, static_cast<std::size_t>(__builtin_popcount(m)));
        }
        CHECK(lp_lower_bound(cands, areas, target) <= fewest);
        CHECK(lp_lower_bound(cands, areas, target) >= area_lower_bound(cands, areas, target) - 1);
        const auto exact = plan_exact(cands, areas, target, std::chrono::milliseconds(10000));
        REQUIRE(exact.has_value());
        CHECK(exact->size() == fewest);
        std::vector<deployment_candidate> chosen;
        for (std::size_t j : *exact) chosen.push_back(cands[j]);
        CHECK(union_area(chosen, areas) >= target * (1 - 1e-9));
    }
}

TEST_CASE("GLPK: malformed or missing candidates are errors or empty answers, never an abort") {
    const std::vector<double> areas{1.0, 2.0};
    CHECK_THROWS_AS(lp_lower_bound({{{1, 1}}}, areas, 1.0), invalid_argument);
    CHECK_THROWS_AS(plan_exact({{{0, 7}}}, areas, 1.0, std::chrono::milliseconds(100)), out_of_range);
    CHECK(lp_lower_bound({}, areas, 1.0) == 0);  // nothing to bound with: nothing claimed
    CHECK(!plan_exact({}, areas, 1.0, std::chrono::milliseconds(100)).has_value());
}
