// docs/occlusion.md: classify the paper's Figure 5 box against every facet of the sample part.
#include <certipose/cgal.hpp>

#include <array>
#include <cstddef>
#include <iostream>

int main() {
    using namespace certipose;
    using I = boost_interval;
    static_assert(OcclusionPolicy<aabb_occlusion, I> && OcclusionPolicy<boolean_occlusion, I> &&
                  OcclusionPolicy<no_occlusion, I>);
    static_assert(checks_occlusion<aabb_occlusion> && !checks_occlusion<no_occlusion>);  // no_occlusion: unchecked
    const sample_part part = make_sample_part();

    // Built once per scene (validates the part as a closed solid, caches the AABB tree / an
    // exact copy); both are const and may be shared by threads.
    const aabb_occlusion fast(part.mesh);
    const boolean_occlusion exact(part.mesh);

    const rounding_guard<I> guard;  // interval code holds the rounding mode; the policies cope
    const auto box = position_box<I>::from_bounds({{{-0.1, 0.1}, {-0.1, 0.1}, {0.25, 0.3}}});

    std::array<std::size_t, 3> count{};
    for (std::size_t f = 0; f < part.mesh.num_faces(); ++f)
        ++count[static_cast<std::size_t>(fast.classify(box, f))];
    std::cout << "aabb_occlusion over " << part.mesh.num_faces() << " facets: " << count[0]
              << " visible, " << count[1] << " partial, " << count[2] << " occluded\n";

    const std::size_t foi = part.facet_of_interest;
    std::cout << "facet of interest " << foi << ": aabb " << to_string(fast.classify(box, foi))
              << ", boolean " << to_string(exact.classify(box, foi)) << "\n";
}
