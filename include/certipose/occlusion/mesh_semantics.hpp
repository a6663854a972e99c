// certipose/occlusion/mesh_semantics.hpp — how an occlusion policy reads its scene meshes:
// as closed solids, or as a triangle soup (occlusion/mesh_survey.hpp says what a soup holds).
// Its own header because the solver's setup names it without needing the survey.
#pragma once

#include <cstdint>
#include <string_view>

namespace certipose {

/// How an occlusion policy reads its scene meshes.
enum class mesh_semantics : std::uint8_t {
    solid,     ///< closed, self-intersection-free, outward solids; anything else is refused
    soup,      ///< any triangles: a sight line is blocked when it meets one (CAD exports)
    automatic  ///< `solid` when every mesh is one, `soup` otherwise (see the survey)
};

/// "solid", "soup" or "auto" (command lines, summary.json).
constexpr std::string_view to_string(mesh_semantics s) noexcept {
    switch (s) {
        case mesh_semantics::solid: return "solid";
        case mesh_semantics::soup: return "soup";
        case mesh_semantics::automatic: return "auto";
    }
    return "?";
}

}  // namespace certipose
