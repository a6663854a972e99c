// certipose/pose/rotation.hpp — the ZXZ camera rotation, world→camera transform and pixel
// projection of docs/conventions.md, for points (double) and for boxes (any certipose Interval).
//
// R(φ, γ, β) = Rz(φ)·Rx(γ)·Rz(β) (paper Eq. 25) maps camera-frame vectors to world vectors; its
// columns are the image x axis, the image y axis (pointing down the image) and the optical axis
// R·ẑ = (sin φ sin γ, −cos φ sin γ, cos γ). A world point q seen from p is q_c = Rᵀ(q − p),
// in front iff q_c.z > 0, at pixel (u, v) with (u, v, 1)ᵀ ∝ K q_c. Every function is one
// template over the scalar (double or an interval), written out entry by entry: an interval
// result therefore encloses the double result at every point of the box — the double
// evaluation is the same expression tree rounded to nearest — which is what the tests check.
// Interval overloads need the caller's `rounding_guard<I>` (Debug asserts it); include
// certipose/interval/cgal_eigen.hpp too when using cgal_interval. `zxz_angles_from_axis`
// inverts the optical axis for the nominal aim of paper §6.4 (β = 0).
#pragma once

#include <cmath>
#include <concepts>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/eigen.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

/// The scalars the rotation functions accept: double, or any certipose interval type.
template <class T>
concept RotationScalar = std::same_as<T, double> || Interval<T>;

template <class T>
using matrix3 = Eigen::Matrix<T, 3, 3>;
template <class T>
using vector3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using vector2 = Eigen::Matrix<T, 2, 1>;

/// R(φ, γ, β) = Rz(φ)·Rx(γ)·Rz(β), multiplied out (paper Eq. 25; docs/conventions.md#zxz-angles).
template <RotationScalar T>
matrix3<T> zxz_rotation(const T& phi, const T& gamma, const T& beta) {
    using std::cos;
    using std::sin;
    const T sp = sin(phi), cp = cos(phi), sg = sin(gamma), cg = cos(gamma), sb = sin(beta), cb = cos(beta);
    matrix3<T> r;
    r << cp * cb - sp * (cg * sb), -(cp * sb) - sp * (cg * cb), sp * sg,
         sp * cb + cp * (cg * sb), cp * (cg * cb) - sp * sb,    -(cp * sg),
         sg * sb,                  sg * cb,                     cg;
    return r;
}

/// R over an orientation box [φ]×[γ]×[β]: encloses R(e) for every e in the box.
template <Interval I>
matrix3<I> zxz_rotation(const orientation_box<I>& e) {
    return zxz_rotation(e[0], e[1], e[2]);
}

/// The optical axis R·ẑ = (sin φ sin γ, −cos φ sin γ, cos γ); it does not depend on β.
template <RotationScalar T>
vector3<T> optical_axis(const T& phi, const T& gamma) {
    using std::cos;
    using std::sin;
    const T sg = sin(gamma);
    return vector3<T>(sin(phi) * sg, -(cos(phi) * sg), cos(gamma));
}

/// Camera-frame coordinates q_c = Rᵀ(q − p) of a world point q seen from the camera at p.
/// Mixed scalars work as Eigen allows them (an interval R and p with a double q, ...); the
/// result's scalar is the interval one if any is.
template <class DR, class DP, class DQ>
auto world_to_camera(const Eigen::MatrixBase<DR>& r, const Eigen::MatrixBase<DP>& p, const Eigen::MatrixBase<DQ>& q) {
    using T = decltype(std::declval<typename DR::Scalar>() *
                       (std::declval<typename DQ::Scalar>() - std::declval<typename DP::Scalar>()));
    static_assert(DR::RowsAtCompileTime == 3 && DR::ColsAtCompileTime == 3, "R must be 3x3");
    const T d0 = q(0) - p(0), d1 = q(1) - p(1), d2 = q(2) - p(2);
    vector3<T> c;
    for (int i = 0; i < 3; ++i) c(i) = r(0, i) * d0 + r(1, i) * d1 + r(2, i) * d2;  // column i of R
    return c;
}

/// In front of the camera: q_c.z > 0 (for an interval: certainly, for every point of the box).
inline bool in_front(const Eigen::Vector3d& qc) { return qc.z() > 0.0; }
template <Interval I>
bool in_front(const vector3<I>& qc) {
    return !is_empty(qc.z()) && certainly_greater(qc.z(), 0.0);
}

namespace detail {
inline void require_pinhole_k(const Eigen::Matrix3d& k) {
    if (!(k(2, 0) == 0.0 && k(2, 1) == 0.0 && k(2, 2) == 1.0) || !k.allFinite())
        throw invalid_argument("K", "project: K must be finite with last row (0, 0, 1), got (" +
                                        std::to_string(k(2, 0)) + ", " + std::to_string(k(2, 1)) + ", " +
                                        std::to_string(k(2, 2)) + ")");
}
}  // namespace detail

/// Pixel coordinates (u, v) of a camera-frame point: (u, v, 1)ᵀ ∝ K q_c with
/// K = [[f_px, s, c_x], [0, δ f_px, c_y], [0, 0, 1]], i.e. u = K₀₀ x/z + K₀₁ y/z + K₀₂ and
/// v = K₁₁ y/z + K₁₂ (x/z and y/z computed once each, the tightest form for intervals).
/// Meaningful only in front of the camera (see in_front); for an interval z containing 0 the
/// result is unbounded or empty, never wrong. Throws invalid_argument("K") if K's last row is
/// not (0, 0, 1) or K has a NaN/inf entry.
template <RotationScalar T>
vector2<T> project(const Eigen::Matrix3d& k, const vector3<T>& qc) {
    detail::require_pinhole_k(k);
    const T x = qc(0) / qc(2), y = qc(1) / qc(2);
    return vector2<T>(k(0, 0) * x + k(0, 1) * y + k(0, 2), k(1, 0) * x + k(1, 1) * y + k(1, 2));
}

/// The ZXZ angles of a camera orientation, radians (β = 0 for an orientation given by its
/// optical axis alone).
struct zxz_angles {
    double phi = 0.0;
    double gamma = 0.0;
    double beta = 0.0;
};

/// φ, γ (β = 0) with optical_axis(φ, γ) = direction / |direction|: the nominal aim of paper
/// §6.4 when `direction` runs from the position box centre to the facet centre.
/// γ = atan2(√(x² + y²), z) ∈ [0, π] and φ = atan2(x, −y) ∈ (−π, π]; along ±z (sin γ = 0)
/// φ is free and set to 0. Throws invalid_argument("direction") for a zero, NaN or inf vector.
inline zxz_angles zxz_angles_from_axis(const Eigen::Vector3d& direction) {
    if (!direction.allFinite() || direction.squaredNorm() == 0.0)
        throw invalid_argument("direction", "zxz_angles_from_axis: direction must be a finite non-zero vector, got (" +
                                                certipose::detail::format_double(direction.x()) + ", " + certipose::detail::format_double(direction.y()) +
                                                ", " + certipose::detail::format_double(direction.z()) + ")");
    const double x = direction.x(), y = direction.y(), z = direction.z();
    const double horizontal = std::hypot(x, y);
    zxz_angles a;
    a.gamma = std::atan2(horizontal, z);
    a.phi = horizontal == 0.0 ? 0.0 : std::atan2(x, -y);
    return a;
}

}  // namespace certipose
