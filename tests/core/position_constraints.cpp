// The paper's position constraints (constraints 1–4 of docs/conventions.md) and the position stage:
// VALID boxes hold only valid positions, discarded regions only invalid ones, by an independent
// plain-double evaluator (verify/point_check.hpp). Occlusion is off here (no CGAL in this
// executable); the occlusion policies have their own suite in tests/cgal.
#include <doctest/doctest.h>

#include <limits>
#include <random>

#include <certipose/camera.hpp>
#include <certipose/constraints/box_triangle_distance.hpp>
#include <certipose/constraints/paper_position_constraints.hpp>
#include <certipose/geometry/sample_part.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/occlusion/no_occlusion.hpp>
#include <certipose/solver/position_stage.hpp>
#include <certipose/verify/point_check.hpp>

using namespace certipose;
using I = boost_interval;

namespace {

const thin_lens_camera& design_camera() {
    static const thin_lens_camera cam(thin_lens_parameters{.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6,
                                                           .max_blur_circle = 6.9e-6, .pixel_pitch = 3.45e-6,
                                                           .width_px = 2448, .height_px = 2048});
    return cam;
}

const sample_part& part() {
    static const sample_part p = make_sample_part();
    return p;
}

Eigen::Vector3d random_point(const position_box<I>& b, std::mt19937& rng) {
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = std::uniform_real_distribution<double>(lower(b[k]), upper(b[k]))(rng);
    return p;
}

bool inside(const position_box<I>& b, const Eigen::Vector3d& p) {
    for (int k = 0; k < 3; ++k)
        if (!contains(b[k], p[k])) return false;
    return true;
}

/// Facets to exercise: the facet of interest and a deterministic spread of others.
std::vector<std::size_t> facets_under_test() {
    std::vector<std::size_t> ids{part().facet_of_interest};
    for (std::size_t i = 7; i < part().mesh.num_faces(); i += 331) ids.push_back(i);
    return ids;
}

/// A user constraint set: the camera must stay above a plane z ≥ 0.4 m (a conveyor guard).
template <class J>
struct above_conveyor {
    static constexpr double height = 0.4;
    explicit above_conveyor(const position_problem&) {}
    void contract(position_box<J>& b) {
        const rounding_guard<J> rounding;
        b[2] = intersect(b[2], J(height, std::numeric_limits<double>::infinity()));
    }
    verdict test(const position_box<J>& b) const {
        if (lower(b[2]) >= height) return verdict::satisfied;
        if (upper(b[2]) < height) return verdict::violated;
        return verdict::undecided;
    }
};

}  // namespace

TEST_CASE("the paper's worked position set models the constraint-set concept") {
    static_assert(PositionConstraintSet<paper_position_constraints<I>, I>);
    static_assert(PositionConstraintSet<above_conveyor<I>, I>);
    static_assert(PositionConstraintSet<all_of<paper_position_constraints<I>, above_conveyor<I>>, I>);
}

TEST_CASE("VALID position boxes hold only valid positions, discarded regions only invalid ones") {
    const auto range = design_camera().distance_range();
    const inspection_task task{.min_view_angle = 0.35};
    std::mt19937 rng(20231878);
    std::size_t valid_samples = 0, discarded_samples = 0, valid_boxes = 0;
    for (std::size_t id : facets_under_test()) {
        CAPTURE(id);
        const facet& f = part().mesh.facet(id);
        const position_problem problem{f, range, task};
        paver_options opt;
        opt.record_tree = true;
        const no_occlusion occ(part().mesh);
        const auto r = pave_positions<I, paper_position_constraints<I>>(problem, id, occ, opt, 0.1);
        REQUIRE(r.boxes.stats.reason == termination::completed);
        valid_boxes += r.boxes.valid.size();
        for (const auto& b : r.boxes.valid)
            for (int k = 0; k < 20; ++k) {
                const Eigen::Vector3d p = random_point(b, rng);
                const auto v = verify::check_position(p, f, range.min, range.max, task.min_view_angle);
                INFO("p = ", p.transpose(), " violates ", v.describe());
                CHECK_FALSE(v.any_position());
                ++valid_samples;
            }
        // Every point the paving removed — a discarded node, or what a contraction cut off a
        // node — must violate at least one constraint.
        for (const auto& node : r.boxes.tree) {
            if (node.classification != box_class::discarded && node.classification != box_class::bisected &&
                node.classification != box_class::valid && node.classification != box_class::boundary)
                continue;
            for (int k = 0; k < 4; ++k) {
                const Eigen::Vector3d p = random_point(node.box, rng);
                const bool removed = node.classification == box_class::discarded || !inside(node.contracted, p);
                if (!removed) continue;
                const auto v = verify::check_position(p, f, range.min, range.max, task.min_view_angle);
                INFO("p = ", p.transpose(), " was discarded but violates nothing");
                CHECK(v.any_position());
                ++discarded_samples;
            }
        }
    }
    MESSAGE(valid_boxes << " VALID boxes, " << valid_samples << " valid samples, " << discarded_samples
                        << " discarded samples checked");
    CHECK(valid_samples >= 10000);
    CHECK(discarded_samples >= 1000);
}

TEST_CASE("the initial search box contains every valid position") {
    const auto range = design_camera().distance_range();
    const facet& f = part().mesh.facet(part().facet_of_interest);
    paper_position_constraints<I> set(position_problem{f, range, inspection_task{}});
    const auto box = set.initial_box();
    REQUIRE_FALSE(is_empty(box));
    // Every valid position is within d_max of the facet, so sampling that ball finds them.
    std::mt19937 rng(7);
    std::size_t found = 0;
    for (int k = 0; k < 200000; ++k) {
        Eigen::Vector3d p = f.centroid;
        for (int d = 0; d < 3; ++d) p[d] += std::uniform_real_distribution<double>(-range.max, range.max)(rng);
        if (verify::check_position(p, f, range.min, range.max, 0.35).any_position()) continue;
        ++found;
        CHECK(inside(box, p));
    }
    CHECK(found > 100);
}

TEST_CASE("a user constraint set combines with the paper's through all_of") {
    const auto range = design_camera().distance_range();
    const std::size_t id = part().facet_of_interest;
    const position_problem problem{part().mesh.facet(id), range, inspection_task{}};
    const no_occlusion occ(part().mesh);
    using combined = all_of<paper_position_constraints<I>, above_conveyor<I>>;
    const auto plain = pave_positions<I, paper_position_constraints<I>>(problem, id, occ, {}, 0.1);
    // above_conveyor cannot contract its complement, so neither can the combination: the default
    // carving paves without inner contraction, as when it is turned off; asked for, it is
    // refused, naming the concept.
    CHECK_THROWS_WITH_AS((pave_positions<I, combined>(problem, id, occ, {}, 0.1, {}, {}, carving{.inner_contraction = true})),
                         doctest::Contains("certipose::ComplementContractingSet"), certipose::invalid_argument);
    CHECK_FALSE(paving_steps<combined, no_occlusion, I>(carving{}).inner_contraction.is_on());
    const auto raised = pave_positions<I, combined>(problem, id, occ, {}, 0.1);
    const auto said_off = pave_positions<I, combined>(problem, id, occ, {}, 0.1, {}, {}, carving{.inner_contraction = false});
    CHECK(raised.boxes.valid.size() == said_off.boxes.valid.size());
    CHECK(raised.boxes.boundary.size() == said_off.boxes.boundary.size());
    REQUIRE_FALSE(raised.boxes.valid.empty());
    for (const auto& b : raised.boxes.valid) CHECK(lower(b[2]) >= above_conveyor<I>::height);
    for (const auto& b : raised.boxes.boundary) CHECK(upper(b[2]) >= above_conveyor<I>::height);
    // Some of the plain set's valid region lies below the plane.
    bool below = false;
    for (const auto& b : plain.boxes.valid) below = below || lower(b[2]) < above_conveyor<I>::height;
    CHECK(below);
}

TEST_CASE("impossible inputs to the position set throw certipose errors naming the field") {
    const facet& f = part().mesh.facet(part().facet_of_interest);
    auto field_of = [&](distance_range r, inspection_task t) -> std::string {
        try {
            paper_position_constraints<I> s(position_problem{f, r, t});
        } catch (const invalid_argument& e) {
            return e.field();
        }
        return "";
    };
    CHECK(field_of({0.5, 0.4}, {}) == "distance_range");
    CHECK(field_of({0.5, std::numeric_limits<double>::infinity()}, {}) == "distance_range");
    CHECK(field_of({std::nan(""), 0.6}, {}) == "distance_range");
    CHECK(field_of({0.4, 0.6}, {.min_view_angle = -0.1}) == "min_view_angle");
    CHECK(field_of({0.4, 0.6}, {.min_view_angle = 2.0}) == "min_view_angle");
    CHECK(field_of({0.4, 0.6}, {.min_view_angle = 0.3, .max_metres_per_pixel = 0.0}) == "max_metres_per_pixel");
}

TEST_CASE("a box touching the facet is never VALID, one far above it at the right distance is") {
    const auto range = design_camera().distance_range();
    const facet& f = part().mesh.facet(part().facet_of_interest);
    paper_position_constraints<I> set(position_problem{f, range, inspection_task{}});
    const Eigen::Vector3d c = f.centroid;
    auto around = [&](Eigen::Vector3d p, double h) {
        return position_box<I>::from_bounds({{{p.x() - h, p.x() + h}, {p.y() - h, p.y() + h}, {p.z() - h, p.z() + h}}});
    };
    CHECK(set.test(around(c, 0.001)) != verdict::satisfied);        // meets the facet
    CHECK(set.test(around(c - 0.3 * f.normal, 0.01)) == verdict::violated);  // behind it
    const double mid_range = 0.5 * (range.min + range.max);
    CHECK(set.test(around(c + mid_range * f.normal, 0.01)) == verdict::satisfied);
    CHECK(set.test(around(c + 2.0 * range.max * f.normal, 0.01)) == verdict::violated);  // too far
}

TEST_CASE("box_triangle_distance_lower: a lower bound of the sampled distance, and early only at `enough`") {
    // The focus constraint d_min ≤ ‖p − q‖ is certified by this bound; the set asks it to stop
    // as soon as it reaches d_min. Both answers must stay below the true box–triangle distance
    // (sampled: box corners and random points against the closest point of the triangle), and
    // the early one must reach `enough` whenever the full one does.
    std::mt19937 rng(2027);
    std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
    std::size_t separated = 0, early = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const Eigen::Vector3d c(0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng));
        const std::array<Eigen::Vector3d, 3> v{c + 0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng)),
                                               c + 0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng)),
                                               c + 0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng))};
        const Eigen::Vector3d n = (v[1] - v[0]).cross(v[2] - v[0]);
        if (!(n.norm() > 1e-6)) continue;
        position_box<I> b;
        for (int k = 0; k < 3; ++k) {
            const double lo = 0.5 * u(rng), w = 0.2 * u01(rng) * u01(rng);
            b[k] = I(lo, lo + w);
        }
        const double enough = 0.3 * u01(rng);
        double full = 0.0, quick = 0.0;
        {
            const rounding_guard<I> rounding;
            full = box_triangle_distance_lower(b, v, n.normalized());
            quick = box_triangle_distance_lower(b, v, n.normalized(), enough);
        }
        CHECK(quick <= full);
        CHECK((full >= enough) == (quick >= enough));
        separated += full > 0.0;
        early += quick < full;
        double nearest = std::numeric_limits<double>::infinity();
        for (int s = 0; s < 24; ++s) {
            Eigen::Vector3d p;
            for (int k = 0; k < 3; ++k)
                p[k] = s < 8 ? ((s >> k) & 1 ? upper(b[k]) : lower(b[k])) : std::uniform_real_distribution<double>(lower(b[k]), upper(b[k]))(rng);
            nearest = std::min(nearest, (p - detail::closest_point_on_triangle(p, v[0], v[1], v[2])).norm());
            ++checked;
        }
        CHECK_MESSAGE(full <= nearest * (1 + 1e-12), "case " << i << ": bound " << full << " above a sampled distance " << nearest);
    }
    MESSAGE("box_triangle_distance_lower: " << separated << " separated pairs, " << early << " answered early, "
                                            << checked << " sampled distances");
    CHECK(separated >= 1000);  // not vacuous
    CHECK(early >= 100);
}
