// certipose/part/selection.hpp — facet selections written as text: "0,5,17-30".
//
// Comma-separated indices and inclusive ranges `a-b` (a ≤ b), in the order given; duplicates are
// dropped (the first occurrence keeps its place), so a selection never solves a facet twice.
// Every malformed token or index outside the part is an invalid_argument naming the token.
#pragma once

#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_set>
#include <vector>

#include "certipose/error.hpp"

namespace certipose {

namespace detail::selection {

inline std::size_t index(std::string_view token, std::string_view whole, std::size_t num_faces) {
    std::size_t v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (token.empty() || r.ec != std::errc{} || r.ptr != token.data() + token.size())
        throw invalid_argument("facets", "facet selection \"" + std::string(whole) + "\": \"" + std::string(token) +
                                             "\" is not a facet index (expected e.g. 0,5,17-30)");
    if (v >= num_faces)
        throw invalid_argument("facets", "facet selection \"" + std::string(whole) + "\": facet " + std::to_string(v) +
                                             " is out of range (the part has " + std::to_string(num_faces) +
                                             " faces: 0.." + std::to_string(num_faces - 1) + ")");
    return v;
}

}  // namespace detail::selection

/// The facets of `text` (see the header comment) for a part of `num_faces` faces.
inline std::vector<std::size_t> parse_facet_selection(std::string_view text, std::size_t num_faces) {
    std::vector<std::size_t> out;
    std::unordered_set<std::size_t> seen;
    const auto add = [&](std::size_t f) {
        if (seen.insert(f).second) out.push_back(f);
    };
    if (text.empty()) throw invalid_argument("facets", "facet selection is empty (expected e.g. 0,5,17-30)");
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = text.find(',', start);
        const std::string_view token = text.substr(start, comma == std::string_view::npos ? text.size() - start : comma - start);
        if (const std::size_t dash = token.find('-'); dash != std::string_view::npos) {
            const std::size_t a = detail::selection::index(token.substr(0, dash), text, num_faces);
            const std::size_t b = detail::selection::index(token.substr(dash + 1), text, num_faces);
            if (a > b)
                throw invalid_argument("facets", "facet selection \"" + std::string(text) + "\": range \"" +
                                                     std::string(token) + "\" runs backwards");
            for (std::size_t f = a; f <= b; ++f) add(f);
        } else {
            add(detail::selection::index(token, text, num_faces));
        }
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return out;
}

}  // namespace certipose
