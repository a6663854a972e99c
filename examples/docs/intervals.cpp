// docs/intervals.md — interval arithmetic with the rounding mode held, named comparisons, the
// empty set, boxes and Eigen.
#include <certipose/certipose.hpp>

#include <cstdio>

int main() {
    using I = certipose::boost_interval;  // or certipose::cgal_interval (needs certipose::cgal)
    using namespace certipose;

    I third, c, d2, y;
    Eigen::Matrix<I, 3, 1> v;
    {
        const rounding_guard<I> guard;  // held upward for this block; restores the caller's mode
        third = I(1.0) / 3.0;                      // [0.33333333333333331, 0.33333333333333337]
        c = cos(I(0.7935));                        // widened outward: libm ignores the mode
        const I x(0.9, 1.1);
        d2 = sqr(x - 0.5) + sqr(I(-0.2, 0.1));     // a squared distance over a box
        y = atan2(I(1.0, 2.0), I(-1.0, 1.0));      // [π/4, 3π/4] widened

        Eigen::Matrix3d rotation;                  // a double matrix times an interval vector
        rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
        v = rotation * Eigen::Matrix<I, 3, 1>(x, I(2.0), I(-1.0, 1.0));
    }
    // Reading bounds needs no guard; printing must happen outside it (printf rounds too).
    std::printf("1/3         = [%.17g, %.17g], width %.3g\n", lower(third), upper(third), width(third));
    std::printf("cos(0.7935) = [%.17g, %.17g]\n", lower(c), upper(c));
    std::printf("d2          = [%g, %g]\n", lower(d2), upper(d2));
    std::printf("atan2       = [%.6f, %.6f]\n", lower(y), upper(y));
    std::printf("R v         = [%g, %g] x [%g, %g] x [%g, %g]\n", lower(v(0)), upper(v(0)), lower(v(1)),
                upper(v(1)), lower(v(2)), upper(v(2)));

    // Named comparisons: never raw `<` on intervals.
    const I a(1.0, 2.0), b(1.5, 3.0);
    std::printf("certainly_less(a, b) = %d, possibly_less(a, b) = %d\n", certainly_less(a, b), possibly_less(a, b));
    std::printf("d2 certainly <= 0.5: %d\n", certainly_leq(d2, 0.5));

    // The empty set is a value: what a contractor returns when it proves a box infeasible.
    const I none = intersect(a, I(5.0, 6.0));
    std::printf("intersect is empty: %d, hull = [%g, %g]\n", is_empty(none), lower(hull(a, b)), upper(hull(a, b)));

    // Boxes: the unit a paver bisects.
    const auto box = interval_box<I, 3>::from_bounds({{{0.0, 1.0}, {-2.0, 2.0}, {5.0, 5.5}}});
    const std::size_t k = widest_dimension(box);
    const auto [left, right] = bisect_at(box, k, mid(box[k]));
    std::printf("widest dimension %zu, volume %g, halves [%g, %g] and [%g, %g]\n", k, volume(box), lower(left[k]),
                upper(left[k]), lower(right[k]), upper(right[k]));
    return certainly_less(third, 0.34) && !is_empty(c) && is_empty(none) ? 0 : 1;
}
