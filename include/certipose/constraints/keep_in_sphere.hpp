// certipose/constraints/keep_in_sphere.hpp — "the camera stays within reach": every position of
// a box lies in the closed ball ‖p − centre‖ ≤ radius (a robot's reach about its base, a cell's
// safe zone). A position constraint set with run-time parameters, to combine with the paper's:
//
//   template <class I>
//   using reachable = certipose::all_of<certipose::paper_position_constraints<I>, certipose::keep_in_sphere<I>>;
//   certipose::pose_solver<certipose::with_constraints<reachable>> solver(
//       mesh, camera, task, {.constraints = {{}, {.centre = base, .radius = 1.2}}});
//
// It is also the model of a user-written set: a class template over the interval type with a
// nested `parameters` type, a constructor from (position_problem, parameters), HC4 for `contract`
// (outer constant: never loses a position inside the ball) and an interval test (inner constant:
// never certifies a position outside it). No CGAL.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "certipose/constraints/concept.hpp"
#include "certipose/contractor/hc4.hpp"
#include "certipose/contractor/not_in.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/expr/constraint.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

template <Interval I>
class keep_in_sphere {
public:
    /// The ball, in the mesh's frame and units (metres).
    struct parameters {
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        double radius = std::numeric_limits<double>::infinity();  ///< > 0; +inf: no restriction
    };

    /// Throws invalid_argument("centre") for a non-finite centre, invalid_argument("radius")
    /// unless radius > 0 (NaN rejected).
    keep_in_sphere(const position_problem&, const parameters& p)
        : p_(validated(p)), r2_(squared_radius(p.radius)), hc4_(make_hc4(p.centre, r2_.hi)),
          outside_(make_outside(p.centre, r2_.lo)) {}

    void contract(position_box<I>& box) { hc4_.contract(box); }

    /// Keeps the positions of `box` that may lie outside the ball (ComplementContractingSet).
    void contract_complement(position_box<I>& box) const { outside_.contract(box); }

    /// satisfied: the whole box is in the ball; violated: none of it is.
    verdict test(const position_box<I>& b) const {
        if (is_empty(b)) return verdict::violated;
        const rounding_guard<I> rounding;
        const I d2 = sqr(b[0] - I(p_.centre.x())) + sqr(b[1] - I(p_.centre.y())) + sqr(b[2] - I(p_.centre.z()));
        if (lower(d2) > r2_.hi) return verdict::violated;
        if (upper(d2) <= r2_.lo) return verdict::satisfied;
        return verdict::undecided;
    }

    const parameters& params() const noexcept { return p_; }

private:
    struct bounds {
        double lo, hi;  ///< radius² rounded down and up
    };

    static const parameters& validated(const parameters& p) {
        if (!p.centre.allFinite())
            throw invalid_argument("centre", "keep_in_sphere: centre must be finite, got (" +
                                                 detail::format_double(p.centre.x()) + ", " +
                                                 detail::format_double(p.centre.y()) + ", " +
                                                 detail::format_double(p.centre.z()) + ")");
        if (!(p.radius > 0.0))
            throw invalid_argument("radius", "keep_in_sphere: radius must be > 0, got " + detail::format_double(p.radius));
        return p;
    }

    static bounds squared_radius(double r) {
        const rounding_guard<I> rounding;
        const I r2 = sqr(I(r));
        return {lower(r2), upper(r2)};
    }

    static auto make_hc4(const Eigen::Vector3d& c, double r2_hi) {
        constexpr var<0> x;
        constexpr var<1> y;
        constexpr var<2> z;
        return hc4(sqr(x - c.x()) + sqr(y - c.y()) + sqr(z - c.z()) <= r2_hi);
    }

    // Inside when d² ≤ radius² rounded down: the complement kept is d² ≥ that bound.
    static auto make_outside(const Eigen::Vector3d& c, double r2_lo) {
        constexpr var<0> x;
        constexpr var<1> y;
        constexpr var<2> z;
        return not_in(sqr(x - c.x()) + sqr(y - c.y()) + sqr(z - c.z()) <= r2_lo);
    }

    parameters p_;
    bounds r2_;
    decltype(make_hc4(Eigen::Vector3d::Zero(), 0.0)) hc4_;
    decltype(make_outside(Eigen::Vector3d::Zero(), 0.0)) outside_;
};

}  // namespace certipose
