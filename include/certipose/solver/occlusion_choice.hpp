// certipose/solver/occlusion_choice.hpp — the occlusion test chosen by name at run time, and the
// pipeline type it selects, in one place.
//
// An occlusion policy is a type of the pipeline, so choosing one from text (the programs'
// --occlusion, the Python module's occlusion=) is a dispatch from a value to a type. It is
// written once, here: `parse_occlusion_choice` reads the name (an invalid_argument naming the
// text and the names there are), and `visit_occlusion(choice, f)` calls
// `f(std::type_identity<Occlusion>{})` with the policy chosen, as std::visit calls a visitor
// with the alternative held, so every branch must return the same type:
//
//   certipose::visit_occlusion(choice, [&]<class O>(std::type_identity<O>) {
//       return certipose::pose_solver<certipose::calibrated_pipeline<O>>(mesh, camera, task).solve(facet, options);
//   });
//
// `calibrated_pipeline<O>` is the pipeline the programs run: the default policies with a
// `calibrated_camera` (whichever model a file names) and the occlusion policy O. The three are
// the ones certipose::precompiled compiles once (detail/precompiled.hpp); with aabb_occlusion it
// is the very type `with_camera<calibrated_camera>`, not an equal one spelled differently.
// Needs CGAL for aabb_occlusion and boolean_occlusion (certipose::cgal or certipose::precompiled).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <type_traits>

#include "certipose/camera/calibrated_camera.hpp"
#include "certipose/error.hpp"
#include "certipose/occlusion/aabb_occlusion.hpp"
#include "certipose/occlusion/boolean_occlusion.hpp"
#include "certipose/occlusion/no_occlusion.hpp"
#include "certipose/solver/policies.hpp"

namespace certipose {

/// The occlusion tests a front end offers by name.
enum class occlusion_choice {
    aabb,     ///< aabb_occlusion: exact predicates on CGAL's AABB tree (the default)
    boolean,  ///< boolean_occlusion: the paper's test
    none,     ///< no_occlusion: occlusion not checked (VALID boxes say so)
};

/// The names, in the order of the enumeration (for a command line's list of choices).
inline constexpr std::array<std::string_view, 3> occlusion_choice_names{"aabb", "boolean", "none"};

constexpr std::string_view to_string(occlusion_choice c) noexcept {
    return occlusion_choice_names[static_cast<std::size_t>(c)];
}

/// The choice `text` names; invalid_argument(field) naming the text and the names otherwise.
inline occlusion_choice parse_occlusion_choice(std::string_view text, const std::string& field = "occlusion") {
    for (std::size_t i = 0; i < occlusion_choice_names.size(); ++i)
        if (text == occlusion_choice_names[i]) return static_cast<occlusion_choice>(i);
    throw invalid_argument(field, field + " must be \"aabb\", \"boolean\" or \"none\", got \"" + std::string(text) + "\"");
}

/// The policies the programs run under occlusion policy `Occlusion` (see the header comment).
template <class Occlusion>
using calibrated_pipeline =
    std::conditional_t<std::is_same_v<Occlusion, aabb_occlusion>, with_camera<calibrated_camera>,
                       with_occlusion<Occlusion, with_camera<calibrated_camera>>>;

/// `f(std::type_identity<O>{})` for the occlusion policy O that `choice` names.
template <class F>
decltype(auto) visit_occlusion(occlusion_choice choice, F&& f) {
    switch (choice) {
        case occlusion_choice::boolean: return f(std::type_identity<boolean_occlusion>{});
        case occlusion_choice::none: return f(std::type_identity<no_occlusion>{});
        case occlusion_choice::aabb: break;
    }
    return f(std::type_identity<aabb_occlusion>{});
}

}  // namespace certipose
