// The occlusion concept and no_occlusion compile and work without CGAL (the solver includes
// them in builds without certipose::cgal).
#include <certipose/interval/boost_interval.hpp>
#include <certipose/occlusion/concept.hpp>
#include <certipose/occlusion/no_occlusion.hpp>

#if defined(CGAL_VERSION)
#error "occlusion/concept.hpp or no_occlusion.hpp pulled in a CGAL header"
#endif

#include <doctest/doctest.h>

#include <span>
#include <vector>

namespace {

using namespace certipose;

static_assert(OcclusionPolicy<no_occlusion, boost_interval>);
static_assert(!OcclusionPolicy<int, boost_interval>);

/// A user-written policy models the concept without touching library code.
struct everything_hidden {
    explicit everything_hidden(const triangle_mesh&) {}
    everything_hidden(const triangle_mesh&, std::span<const triangle_mesh>) {}
    template <Interval I>
    visibility classify(const position_box<I>&, std::size_t) const {
        return visibility::occluded;
    }
};
static_assert(OcclusionPolicy<everything_hidden, boost_interval>);

triangle_mesh tetrahedron() {
    return triangle_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                         {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

}  // namespace

TEST_CASE("no_occlusion: every box visible, facet index checked") {
    const triangle_mesh t = tetrahedron();
    const std::vector<triangle_mesh> occluders{t};
    const no_occlusion none(t, occluders);
    const rounding_guard<boost_interval> guard;
    const auto box = position_box<boost_interval>::from_bounds({{{-5, -4}, {0, 1}, {0, 1}}});
    for (std::size_t f = 0; f < t.num_faces(); ++f) CHECK(none.classify(box, f) == visibility::visible);
    CHECK_THROWS_AS(none.classify(box, 4), out_of_range);
    CHECK(to_string(visibility::visible) == "visible");
    CHECK(to_string(visibility::partial) == "partial");
    CHECK(to_string(visibility::occluded) == "occluded");
}
