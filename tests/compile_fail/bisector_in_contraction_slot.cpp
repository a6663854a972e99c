// expect: template constraint failure .*requires +ContractionPolicy<C
// A bisector given where the contraction policy goes: the first error names the concept.
#include <certipose/cgal.hpp>

int main() {
    using solver = certipose::pose_solver<certipose::with_contraction<certipose::largest_first>>;
    return static_cast<int>(sizeof(solver));
}
