// certipose/interval/eigen.hpp — certipose intervals as Eigen scalars.
//
// Modelled on CGAL's own block at the end of CGAL/Interval_nt.h: `NumTraits` with
// `Literal = double` (so `Matrix<I,3,3>::Identity()`, `setZero()` and literals work),
// `ScalarBinaryOpTraits` with `double` both ways (so a `Matrix3d` times an interval vector
// is an interval vector, with no copy of the double matrix into intervals), and a
// `scalar_score_coeff_op` so that pivot search (LU, full-pivoting QR) ranks candidates without
// comparing overlapping intervals. `abs2` is specialised to `sqr`, which is tight where Eigen's
// default `x*x` is not (x ∋ 0), so `squaredNorm()` of a vector straddling zero starts at 0.
// Math functions Eigen calls unqualified (`abs`, `sqrt`, `abs2`, `conj`, `real`, `imag`) are
// found by ADL in namespace certipose.
//
// This header covers `boost_interval` and needs no CGAL. The
// same traits for `cgal_interval` are in certipose/interval/cgal_eigen.hpp, which needs
// certipose::cgal. A user-written backend gets them by specialising the three Eigen templates
// with the `certipose::eigen_interval_*` bases below, exactly as those two headers do.
//
// Eigen algorithms that compare scalars with raw `<` (PartialPivLU's l1 norm, isApprox, ...)
// do not compile with certipose intervals: that is deliberate (operations.hpp). Products, sums,
// `dot`, `cross`, `squaredNorm` and `norm` do. The rounding protocol is unchanged: hold a
// `rounding_guard<I>` while Eigen evaluates an interval expression (Eigen evaluates lazily, so
// the guard must be alive where the expression is assigned, not only where it is written).
#pragma once

#include <limits>

#include <Eigen/Core>

#include "certipose/interval/boost_interval.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

// ---- ADL math for Eigen (real scalars: conj is the identity, imag is zero) ------------------

template <Interval I>
I abs2(const I& a) { return sqr(a); }
template <Interval I>
I conj(const I& a) { return a; }
template <Interval I>
I real(const I& a) { return a; }
template <Interval I>
I imag(const I&) { return I(0.0); }

// ---- bases for the Eigen specialisations -----------------------------------------------------

/// `Eigen::NumTraits` body for an interval type.
template <class I>
struct eigen_interval_num_traits {
    using Real = I;
    using NonInteger = I;
    using Nested = I;
    using Literal = double;

    // Tolerances are for algorithms that compare; intervals answer exactly or not at all.
    static I epsilon() { return I(0.0); }
    static I dummy_precision() { return I(0.0); }
    // Enclosures of "the largest/lowest value", as CGAL gives them.
    static I highest() { return I(std::numeric_limits<double>::max(), std::numeric_limits<double>::infinity()); }
    static I lowest() { return I(-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::lowest()); }
    static int digits() { return std::numeric_limits<double>::digits; }
    static int digits10() { return std::numeric_limits<double>::digits10; }
    static int max_digits10() { return std::numeric_limits<double>::max_digits10; }

    enum {
        IsInteger = 0,
        IsSigned = 1,
        IsComplex = 0,
        RequireInitialization = 1,  // the default constructor sets [0, 0]
        ReadCost = 2,
        AddCost = 4,
        MulCost = 10
    };
};

/// `Eigen::internal::scalar_score_coeff_op` body: the score of a pivot candidate is |x| wrapped
/// in a type with a total order that never compares overlapping intervals. Candidates that
/// are certainly non-zero beat those that may be zero (dividing by the latter gives the whole
/// line); among the former the largest guaranteed magnitude (lower bound of |x|) wins, which is
/// partial pivoting's rule for point intervals; among the latter the largest upper bound.
/// Empty scores rank lowest. `== Score(0)` (Eigen's "pivot is exactly zero") is set equality,
/// i.e. true only for [0, 0].
template <class I>
struct eigen_interval_score {
    struct result_type {
        I i;
        result_type() : i(0.0) {}
        result_type(const I& j) : i(j) {}  // NOLINT(implicit): Eigen writes Score(0)

        // (rank, key): rank 0 empty, 1 possibly zero, 2 certainly non-zero.
        int rank() const { return is_empty(i) ? 0 : (lower(i) > 0.0 ? 2 : 1); }
        double key() const { return rank() == 2 ? lower(i) : (rank() == 1 ? upper(i) : 0.0); }

        friend bool operator<(const result_type& x, const result_type& y) {
            const int rx = x.rank(), ry = y.rank();
            return rx != ry ? rx < ry : x.key() < y.key();
        }
        friend bool operator>(const result_type& x, const result_type& y) { return y < x; }
        friend bool operator<=(const result_type& x, const result_type& y) { return !(y < x); }
        friend bool operator>=(const result_type& x, const result_type& y) { return !(x < y); }
        friend bool operator==(const result_type& x, const result_type& y) { return x.i == y.i; }
        friend bool operator!=(const result_type& x, const result_type& y) { return !(x.i == y.i); }
    };
    result_type operator()(const I& x) const { return result_type(abs(x)); }
};

}  // namespace certipose

namespace Eigen {

template <>
struct NumTraits<certipose::boost_interval>
    : certipose::eigen_interval_num_traits<certipose::boost_interval> {};

template <class BinaryOp>
struct ScalarBinaryOpTraits<certipose::boost_interval, double, BinaryOp> {
    using ReturnType = certipose::boost_interval;
};
template <class BinaryOp>
struct ScalarBinaryOpTraits<double, certipose::boost_interval, BinaryOp> {
    using ReturnType = certipose::boost_interval;
};

namespace internal {

template <>
struct scalar_score_coeff_op<certipose::boost_interval>
    : certipose::eigen_interval_score<certipose::boost_interval> {};
template <>
struct functor_traits<scalar_score_coeff_op<certipose::boost_interval>> {
    enum { Cost = 10, PacketAccess = false };
};

template <>
struct abs2_impl<certipose::boost_interval> {
    static certipose::boost_interval run(const certipose::boost_interval& x) {
        return sqr(x);
    }
};

}  // namespace internal
}  // namespace Eigen
