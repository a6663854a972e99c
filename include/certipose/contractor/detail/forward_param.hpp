// certipose/contractor/detail/forward_param.hpp — how a contractor or box test that wraps
// others forwards `set_param<Id>(lo, hi)` to what it wraps.
//
// Not for users. Every wrapper's `set_param<Id>` is one call of `forward_set_param`, on the
// object it wraps or on its tuple of parts (each element then in order). Constraints always
// have set_param, so wrappers of constraints forward to `all` their targets (a target without
// one does not compile); a contractor need not have one, so wrappers of contractors forward to
// `those_having_one` and skip the others.
#pragma once

#include <cstddef>
#include <tuple>

namespace certipose::contractor_detail {

/// Whether `T` has a parameter setter for parameter `Id`.
template <class T, std::size_t Id>
concept has_set_param = requires(T& t, double v) { t.template set_param<Id>(v, v); };

enum class param_targets {
    all,               ///< every target must have set_param
    those_having_one,  ///< targets without set_param are skipped
};

template <std::size_t Id, param_targets Which = param_targets::all, class T>
void forward_set_param(T& target, double lo, double hi) {
    if constexpr (Which == param_targets::all || has_set_param<T, Id>) target.template set_param<Id>(lo, hi);
}

template <std::size_t Id, param_targets Which = param_targets::all, class... Ts>
void forward_set_param(std::tuple<Ts...>& parts, double lo, double hi) {
    std::apply([&](auto&... part) { (forward_set_param<Id, Which>(part, lo, hi), ...); }, parts);
}

}  // namespace certipose::contractor_detail
