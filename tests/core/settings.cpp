// solver/solve_settings.hpp and solver/occlusion_choice.hpp: the one translation of the solver's
// settings and of the occlusion test's name that the programs and the Python module share.
#include <certipose/solver/occlusion_choice.hpp>
#include <certipose/solver/solve_settings.hpp>

#include <doctest/doctest.h>

#include <chrono>
#include <string>
#include <type_traits>
#include <variant>

using namespace certipose;

namespace {
/// The field an invalid_argument thrown by `f` names ("" when nothing is thrown).
template <class F>
std::string field_of(F&& f) {
    try {
        f();
    } catch (const invalid_argument& e) {
        return e.field();
    }
    return "";
}
}  // namespace

TEST_CASE("solve_settings: the defaults are solve_options' defaults") {
    const solve_options o = to_solve_options({});
    const solve_options d;
    CHECK(o.position_eps == d.position_eps);
    CHECK(o.orientation_eps == d.orientation_eps);
    CHECK(o.max_boxes == d.max_boxes);
    CHECK_FALSE(o.time_limit);
    CHECK_FALSE(o.refine);
    CHECK_FALSE(o.grow);
    REQUIRE(std::holds_alternative<carving>(o.paving));
    CHECK(std::get<carving>(o.paving).corner_depth == carving{}.corner_depth);
    CHECK(std::get<carving>(o.paving).rest_min_pieces == carving{}.rest_min_pieces);
}

TEST_CASE("solve_settings: every setting reaches its option, in its unit") {
    solve_settings s;
    s.position_eps = 0.05;
    s.orientation_eps = 0.2;
    s.max_boxes = 1234;
    s.time_limit = 2.5;
    s.corner_depth = 3;
    s.corner_rest = 2;
    s.refine = 0.25;
    s.grow = true;
    const solve_options o = to_solve_options(s);
    CHECK(o.position_eps == 0.05);
    CHECK(o.orientation_eps == 0.2);
    CHECK(o.max_boxes == 1234u);
    REQUIRE(o.time_limit);
    CHECK(*o.time_limit == std::chrono::milliseconds(2500));
    REQUIRE(std::holds_alternative<carving>(o.paving));
    CHECK(std::get<carving>(o.paving).corner_depth == 3u);
    CHECK(std::get<carving>(o.paving).rest_min_pieces == 2.0);
    REQUIRE(o.refine);
    REQUIRE(o.refine->time_limit);
    CHECK(*o.refine->time_limit == std::chrono::milliseconds(250));
    CHECK(o.grow);

    s = {};
    s.paper_paving = true;
    CHECK(std::holds_alternative<paper_paving>(to_solve_options(s).paving));
}

TEST_CASE("solve_settings: each mistake names the setting as written") {
    const auto with = [](auto change) {
        solve_settings s;
        change(s);
        return field_of([&] { (void)to_solve_options(s); });
    };
    CHECK(with([](solve_settings& s) { s.position_eps = 0; }) == "position_eps");
    CHECK(with([](solve_settings& s) { s.orientation_eps = -1; }) == "orientation_eps");
    CHECK(with([](solve_settings& s) { s.max_boxes = 0; }) == "max_boxes");
    CHECK(with([](solve_settings& s) { s.time_limit = 0.0; }) == "time_limit");
    CHECK(with([](solve_settings& s) { s.refine = -2.0; }) == "refine");
    CHECK(with([](solve_settings& s) { s.corner_depth = 9; }) == "corner_depth");
    CHECK(with([](solve_settings& s) { s.corner_rest = -1.0; }) == "corner_rest");
    // A tuning of carving that the paper's paving would ignore.
    CHECK(with([](solve_settings& s) { s.paper_paving = true, s.corner_depth = 2; }) == "corner_depth");
    CHECK(with([](solve_settings& s) { s.paper_paving = true, s.corner_rest = 2.0; }) == "corner_rest");
    CHECK(with([](solve_settings&) {}) == "");
}

TEST_CASE("occlusion_choice: names read back, and each selects its policy's pipeline") {
    for (const auto name : occlusion_choice_names) CHECK(to_string(parse_occlusion_choice(name)) == name);
    CHECK(parse_occlusion_choice("boolean") == occlusion_choice::boolean);
    CHECK_THROWS_WITH_AS((void)parse_occlusion_choice("fast", "--occlusion"),
                         doctest::Contains("--occlusion must be \"aabb\", \"boolean\" or \"none\", got \"fast\""),
                         invalid_argument);
    CHECK(field_of([] { (void)parse_occlusion_choice("AABB"); }) == "occlusion");

    const auto picked = [](occlusion_choice c) {
        return visit_occlusion(c, []<class O>(std::type_identity<O>) {
            if constexpr (std::is_same_v<O, aabb_occlusion>) return 0;
            else if constexpr (std::is_same_v<O, boolean_occlusion>) return 1;
            else if constexpr (std::is_same_v<O, no_occlusion>) return 2;
            else return -1;
        });
    };
    CHECK(picked(occlusion_choice::aabb) == 0);
    CHECK(picked(occlusion_choice::boolean) == 1);
    CHECK(picked(occlusion_choice::none) == 2);
    // The precompiled pipelines, as exact types.
    static_assert(std::is_same_v<calibrated_pipeline<aabb_occlusion>, with_camera<calibrated_camera>>);
    static_assert(std::is_same_v<calibrated_pipeline<no_occlusion>, with_occlusion<no_occlusion, with_camera<calibrated_camera>>>);
}
