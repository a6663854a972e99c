// expect: certipose needs .*-ffast-math
// flags: -ffast-math
// -ffast-math lets the compiler reassociate and drop infinities, NaNs and the rounding mode, so
// no interval bound would be safe: including an interval header refuses it and says why. (With
// Clang, the -frounding-math that certipose's targets add after it leaves -ffinite-math-only,
// whose message names -ffast-math as well.)
#include <certipose/interval/boost_interval.hpp>

int main() {
    const certipose::rounding_guard<certipose::boost_interval> guard;
    return upper(certipose::boost_interval(1.0) / 3.0) > 0.0 ? 0 : 1;
}
