// certipose/interval/cgal_eigen.hpp — `cgal_interval` as an Eigen scalar (needs certipose::cgal).
//
// The same NumTraits / ScalarBinaryOpTraits (double both ways) / scalar_score_coeff_op / abs2
// specialisations that certipose/interval/eigen.hpp gives `boost_interval`, for the CGAL
// backend; kept apart so that eigen.hpp never pulls in CGAL. CGAL's own traits in
// CGAL/Interval_nt.h are for `CGAL::Interval_nt<b>`, not for this wrapper (which adds the empty
// set), so they do not apply here.
#pragma once

#include "certipose/interval/cgal_interval.hpp"
#include "certipose/interval/eigen.hpp"

namespace Eigen {

template <>
struct NumTraits<certipose::cgal_interval> : certipose::eigen_interval_num_traits<certipose::cgal_interval> {};

template <class BinaryOp>
struct ScalarBinaryOpTraits<certipose::cgal_interval, double, BinaryOp> {
    using ReturnType = certipose::cgal_interval;
};
template <class BinaryOp>
struct ScalarBinaryOpTraits<double, certipose::cgal_interval, BinaryOp> {
    using ReturnType = certipose::cgal_interval;
};

namespace internal {

template <>
struct scalar_score_coeff_op<certipose::cgal_interval> : certipose::eigen_interval_score<certipose::cgal_interval> {};
template <>
struct functor_traits<scalar_score_coeff_op<certipose::cgal_interval>> {
    enum { Cost = 10, PacketAccess = false };
};

template <>
struct abs2_impl<certipose::cgal_interval> {
    static certipose::cgal_interval run(const certipose::cgal_interval& x) { return sqr(x); }
};

}  // namespace internal
}  // namespace Eigen
