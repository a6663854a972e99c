// certipose/expr/vector.hpp — 3-vectors of expressions: dot, cross, sums, scaling.
//
// A `vec3` is not a node: it is three expressions side by side, and `dot`/`cross` expand into
// ordinary trees (`dot(u, v)` is `u.x*v.x + u.y*v.y + u.z*v.z`). That keeps forward/backward
// exactly the scalar rules, and lets constraints such as the viewing angle
// `(p − c)·n ≥ sin(θ_v)·‖p − c‖` (constraint 4, docs/conventions.md) be written as in the paper.
#pragma once

#include <utility>

#include "certipose/expr/expression.hpp"

namespace certipose::expr {

template <Expression X, Expression Y, Expression Z>
struct vec3 {
    X x;
    Y y;
    Z z;
};

/// (a, b, c) as a vector of expressions; numbers become constants.
template <Operand A, Operand B, Operand C>
auto vec(const A& a, const B& b, const C& c) {
    return vec3<expr_t<A>, expr_t<B>, expr_t<C>>{as_expr(a), as_expr(b), as_expr(c)};
}

template <class X1, class Y1, class Z1, class X2, class Y2, class Z2>
auto operator+(const vec3<X1, Y1, Z1>& u, const vec3<X2, Y2, Z2>& v) {
    return vec(u.x + v.x, u.y + v.y, u.z + v.z);
}
template <class X1, class Y1, class Z1, class X2, class Y2, class Z2>
auto operator-(const vec3<X1, Y1, Z1>& u, const vec3<X2, Y2, Z2>& v) {
    return vec(u.x - v.x, u.y - v.y, u.z - v.z);
}
template <class X, class Y, class Z>
auto operator-(const vec3<X, Y, Z>& u) {
    return vec(-u.x, -u.y, -u.z);
}
template <Operand S, class X, class Y, class Z>
auto operator*(const S& s, const vec3<X, Y, Z>& u) {
    return vec(s * u.x, s * u.y, s * u.z);
}
template <Operand S, class X, class Y, class Z>
auto operator*(const vec3<X, Y, Z>& u, const S& s) {
    return vec(u.x * s, u.y * s, u.z * s);
}

template <class X1, class Y1, class Z1, class X2, class Y2, class Z2>
auto dot(const vec3<X1, Y1, Z1>& u, const vec3<X2, Y2, Z2>& v) {
    return u.x * v.x + u.y * v.y + u.z * v.z;
}

template <class X1, class Y1, class Z1, class X2, class Y2, class Z2>
auto cross(const vec3<X1, Y1, Z1>& u, const vec3<X2, Y2, Z2>& v) {
    return vec(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
}

/// ‖u‖² written with sqr (tighter than dot(u, u): sqr knows its result is non-negative).
template <class X, class Y, class Z>
auto sqr_norm(const vec3<X, Y, Z>& u) {
    return sqr(u.x) + sqr(u.y) + sqr(u.z);
}

/// ‖u‖.
template <class X, class Y, class Z>
auto norm(const vec3<X, Y, Z>& u) {
    return sqrt(sqr_norm(u));
}

}  // namespace certipose::expr

namespace certipose {
using expr::cross;
using expr::dot;
using expr::norm;
using expr::sqr_norm;
using expr::vec;
using expr::vec3;
}  // namespace certipose
