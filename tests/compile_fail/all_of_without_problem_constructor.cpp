// expect: template constraint failure .*ConstructibleConstraintSet<Sets>
// A member set of all_of that cannot be built for a facet (no position_problem constructor):
// the first error names the concept instead of "too many initializers" deep inside std::tuple.
#include <certipose/certipose.hpp>

template <class I>
struct stay_above {
    explicit stay_above(double height) : h(height) {}
    void contract(certipose::position_box<I>&) {}
    certipose::verdict test(const certipose::position_box<I>&) const { return certipose::verdict::undecided; }
    double h;
};

int main() {
    using I = certipose::boost_interval;
    using set = certipose::all_of<certipose::paper_position_constraints<I>, stay_above<I>>;
    return static_cast<int>(sizeof(set));
}
