// The covering program of coverage/glpk_deployment.hpp against brute force: the LP bound never
// exceeds the fewest boxes certifying a target, and the exact answer is that fewest number.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <cstddef>
#include <random>
#include <vector>

#include <certipose/coverage/glpk_deployment.hpp>

using namespace certipose;

namespace {
/// The fewest candidates whose union certifies `target` (every subset tried); candidates + 1 if none does.
std::size_t fewest_by_brute_force(const std::vector<deployment_candidate>& cands, const std::vector<double>& areas,
                                  double target) {
    std::size_t fewest = cands.size() + 1;
    for (unsigned m = 0; m < (1U << cands.size()); ++m) {
        std::vector<deployment_candidate> chosen;
        for (std::size_t j = 0; j < cands.size(); ++j)
            if (m >> j & 1U) chosen.push_back(cands[j]);
        if (union_area(chosen, areas) >= target)
            fewest = std::min<std::size_t>(fewest, static_cast<std::size_t>(__builtin_popcount(m)));
    }
    return fewest;
}

/// `count` candidates, each certifying each of `facets` facets with `take`'s probability.
std::vector<deployment_candidate> random_candidates(std::mt19937& rng, std::bernoulli_distribution& take,
                                                    std::size_t count, std::size_t facets) {
    std::vector<deployment_candidate> cands(count);
    for (auto& c : cands)
        for (std::size_t f = 0; f < facets; ++f)
            if (take(rng)) c.facets.push_back(f);
    return cands;
}
}  // namespace

TEST_CASE("GLPK: the LP bound is a lower bound and the exact plan is optimal (brute force)") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> area(0.1, 1.0);
    std::bernoulli_distribution take(0.3);
    for (int trial = 0; trial < 25; ++trial) {
        std::vector<double> areas;
        for (int f = 0; f < 12; ++f) areas.push_back(area(rng));
        const std::vector<deployment_candidate> cands = random_candidates(rng, take, 9, areas.size());
        const double target = 0.8 * union_area(cands, areas);
        const std::size_t fewest = fewest_by_brute_force(cands, areas, target);
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

TEST_CASE("GLPK: facets certified by the same candidates count as one, with the same bound and plan") {
    // Each facet of a random instance split into three with the same candidates: the program
    // merges them back (glpk_deployment.hpp), so the answers must equal the unsplit instance's.
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> area(0.1, 1.0), share(0.1, 0.8);
    std::bernoulli_distribution take(0.35);
    for (int trial = 0; trial < 15; ++trial) {
        std::vector<double> areas, split;
        for (int f = 0; f < 10; ++f) {
            areas.push_back(area(rng));
            const double a = share(rng), b = share(rng) * (1 - a);
            split.insert(split.end(), {areas.back() * a, areas.back() * b, areas.back() * (1 - a - b)});
        }
        std::vector<deployment_candidate> whole(8), parts(8);
        for (std::size_t j = 0; j < whole.size(); ++j)
            for (std::size_t f = 0; f < areas.size(); ++f)
                if (take(rng)) {
                    whole[j].facets.push_back(f);
                    parts[j].facets.insert(parts[j].facets.end(), {3 * f, 3 * f + 1, 3 * f + 2});
                }
        const double target = 0.85 * union_area(whole, areas);
        CAPTURE(trial);
        CHECK(lp_lower_bound(parts, split, target) == lp_lower_bound(whole, areas, target));
        const auto a = plan_exact(whole, areas, target, std::chrono::milliseconds(10000));
        const auto b = plan_exact(parts, split, target, std::chrono::milliseconds(10000));
        REQUIRE(a.has_value());
        REQUIRE(b.has_value());
        CHECK(a->size() == b->size());
    }
}

TEST_CASE("GLPK: malformed or missing candidates are errors or empty answers, never an abort") {
    const std::vector<double> areas{1.0, 2.0};
    CHECK_THROWS_AS(lp_lower_bound({{{1, 1}}}, areas, 1.0), invalid_argument);
    CHECK_THROWS_AS(plan_exact({{{0, 7}}}, areas, 1.0, std::chrono::milliseconds(100)), out_of_range);
    CHECK(lp_lower_bound({}, areas, 1.0) == 0);  // nothing to bound with: nothing claimed
    // A time limit that is ample changes nothing.
    const std::vector<deployment_candidate> two{{{0}}, {{1}}};
    CHECK(lp_lower_bound(two, areas, 3.0) == 2);
    CHECK(lp_lower_bound(two, areas, 3.0, {.time_limit = std::chrono::milliseconds(10000)}) == 2);
    // A limit too short for a larger program: GLPK stops, and nothing is claimed, or it finished
    // in time and the bound is the unlimited one; never anything else.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> a(0.1, 1.0);
    std::bernoulli_distribution take(0.05);
    std::vector<double> many(3000);
    for (double& x : many) x = a(rng);
    std::vector<deployment_candidate> cands(400);
    for (auto& c : cands)
        for (std::size_t f = 0; f < many.size(); ++f)
            if (take(rng)) c.facets.push_back(f);
    const double target = 0.9 * union_area(cands, many);
    const std::size_t unlimited = lp_lower_bound(cands, many, target);
    REQUIRE(unlimited > 0);
    const std::size_t hurried = lp_lower_bound(cands, many, target, {.time_limit = std::chrono::milliseconds(1)});
    CHECK((hurried == 0 || hurried == unlimited));
    CHECK(!plan_exact({}, areas, 1.0, std::chrono::milliseconds(100)).has_value());
}

TEST_CASE("GLPK: the relaxed LP, with classes left out, is still a lower bound (brute force)") {
    // Many small classes and a few rows allowed: the relaxation leaves out as much as its share
    // lets it. Without lowering the target by what it left out, its optimum could exceed the
    // fewest boxes (or the program be infeasible): brute force says it does not.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> area(0.01, 1.0);
    std::bernoulli_distribution take(0.3);
    std::size_t relaxed_below = 0;  // instances where leaving out classes lowered the bound
    for (int trial = 0; trial < 40; ++trial) {
        std::vector<double> areas;
        for (int f = 0; f < 14; ++f) areas.push_back(area(rng) * area(rng));  // many small facets
        const std::vector<deployment_candidate> cands = random_candidates(rng, take, 9, areas.size());
        const double target = 0.95 * union_area(cands, areas);
        const std::size_t fewest = fewest_by_brute_force(cands, areas, target);
        CAPTURE(trial);
        const std::size_t whole = lp_lower_bound(cands, areas, target, {.relaxation = {.max_left_out = 0.0}});
        for (double share : {0.05, 0.2, 0.5}) {
            const std::size_t relaxed =
                lp_lower_bound(cands, areas, target, {.relaxation = {.max_classes = 1, .max_left_out = share}});
            CHECK(relaxed <= fewest);
            CHECK(relaxed <= whole);  // a relaxation never bounds higher than the whole program
            if (whole > 0) CHECK(relaxed > 0);  // and stays feasible: the target was lowered with it
            if (relaxed < whole) ++relaxed_below;
        }
        // Few enough classes: nothing is left out, whatever the share.
        CHECK(lp_lower_bound(cands, areas, target, {.relaxation = {.max_classes = 1000, .max_left_out = 0.5}}) == whole);
    }
    CHECK(relaxed_below > 0);  // the instances did exercise leaving classes out
}

TEST_CASE("GLPK: bad relaxation options are refused with their field") {
    const std::vector<double> areas{1.0, 2.0};
    const std::vector<deployment_candidate> two{{{0}}, {{1}}};
    for (double bad : {-0.1, 1.0, std::nan("")}) {
        try {
            (void)lp_lower_bound(two, areas, 3.0, {.relaxation = {.max_left_out = bad}});
            FAIL("accepted max_left_out " << bad);
        } catch (const invalid_argument& e) {
            CHECK(e.field() == "max_left_out");
        }
    }
    CHECK_THROWS_AS(lp_lower_bound(two, areas, 3.0, {.relaxation = {.max_classes = 0}}), invalid_argument);
    // A negative or non-finite area would raise the relaxed target: refused, naming the facet.
    for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        try {
            (void)lp_lower_bound(two, {1.0, bad}, 0.5);
            FAIL("accepted area " << bad);
        } catch (const invalid_argument& e) {
            CHECK(e.field() == "areas");
            CHECK(std::string(e.what()).find("facet 1") != std::string::npos);
        }
    }
}
