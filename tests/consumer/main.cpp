// A downstream program: uses certipose exactly as a user would, through the package.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/pose/pose_box.hpp>

#include <cstdio>

int main() {
    using I = certipose::boost_interval;
    const certipose::rounding_guard<I> rounding;
    const I third = I(1.0) / I(3.0);
    auto box = certipose::position_box<I>::from_bounds({{{0, 1}, {0, 2}, {0, 3}}});
    const bool ok = certipose::lower(third) < certipose::upper(third) && certipose::widest_dimension(box) == 2;
    std::puts(ok ? "consumer ok" : "consumer FAILED");
    return ok ? 0 : 1;
}
