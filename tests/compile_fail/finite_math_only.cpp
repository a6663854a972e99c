// expect: certipose needs infinities and NaNs, and -ffinite-math-only
// flags: -ffinite-math-only
// Unbounded intervals have infinite bounds and the empty interval NaN bounds; a compiler told
// there are none could fold away the tests on them, so an interval header refuses the option.
#include <certipose/interval/boost_interval.hpp>

int main() {
    const certipose::rounding_guard<certipose::boost_interval> guard;
    return certipose::is_empty(certipose::boost_interval(2.0, 1.0)) ? 0 : 1;
}
