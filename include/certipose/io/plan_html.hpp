// certipose/io/plan_html.hpp — a plan as one self-contained HTML page: the glTF scene of
// io/plan_gltf.hpp, a three.js viewer and a facet picker, opened from a file with no server and
// no network. The viewer (web/src/, bundled with three.js by web/build.mjs) is passed in as text:
// certipose-export embeds the bundle at build time.
//
// The page is the viewer template with three placeholders replaced: the bundled script, the
// title, and the scene block {"title", "glb" (base64), "cameras": [{"index", "name", "position",
// "quaternion", "facets", "colour", "tolerance": {"half_mm", "cone_deg", "roll_deg"}}],
// "facet_cameras": [[k, ...] per facet], "uncovered": {reason: [facet, ...]}}
// (docs/conventions.md#html).
// The scene JSON sits in a <script type="application/json"> element, so every "<" is escaped in it.
#pragma once

#include "certipose/io/json.hpp"
#include "certipose/io/plan_export.hpp"

#include <boost/archive/iterators/base64_from_binary.hpp>
#include <boost/archive/iterators/transform_width.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace certipose {

/// The viewer that plan_html fills in: its HTML template and its bundled script.
struct plan_viewer {
    std::string_view html_template;
    std::string_view script;
};

namespace detail::html {
inline std::string base64(std::string_view bytes) {
    using namespace boost::archive::iterators;
    using it = base64_from_binary<transform_width<std::string_view::const_iterator, 6, 8>>;
    std::string out(it(bytes.begin()), it(bytes.end()));
    out.append((3 - bytes.size() % 3) % 3, '=');
    return out;
}
inline std::string escape_text(std::string_view s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}
/// The template with each placeholder replaced once, in one pass over the template only (so text
/// inserted for one placeholder is never searched for another).
inline std::string fill(std::string_view page, const std::vector<std::pair<std::string_view, std::string>>& values) {
    std::string out;
    for (const auto& [key, value] : values)
        if (page.find(key) == std::string_view::npos)
            throw invalid_argument("viewer", "plan_html: the viewer template has no " + std::string(key) + " placeholder");
    std::size_t from = 0;
    while (true) {
        std::size_t best = std::string_view::npos;
        const std::pair<std::string_view, std::string>* which = nullptr;
        for (const auto& kv : values) {
            const auto at = page.find(kv.first, from);
            if (at < best) best = at, which = &kv;
        }
        if (!which) break;
        out.append(page.substr(from, best - from));
        out += which->second;
        from = best + which->first.size();
    }
    out.append(page.substr(from));
    return out;
}
}  // namespace detail::html

/// The page's bytes, from the plan's glb (plan_glb) and the viewer.
inline std::string plan_html(const plan_document& plan, std::string_view glb, std::size_t num_faces,
                             const plan_viewer& viewer, const std::string& title) {
    const auto exports = camera_exports(plan);
    plan_first_cameras(num_faces, plan);  // throws out_of_range for a facet beyond the part
    const certipose::detail::round_to_nearest_scope nearest;
    nlohmann::json scene;
    scene["title"] = title;
    scene["glb"] = detail::html::base64(glb);
    auto cameras = nlohmann::json::array();
    std::vector<std::vector<std::size_t>> facet_cameras(num_faces);
    for (const auto& e : exports) {
        const rgb c = plan_camera_colour(e.index);
        const fitter_camera fit = fitter_units(e, plan.cameras[e.index]);
        cameras.push_back({{"index", e.index},
                           {"name", "camera " + std::to_string(e.index)},
                           {"position", e.position},
                           {"quaternion", e.quaternion},
                           {"facets", plan.cameras[e.index].facets},
                           {"colour", {c.r, c.g, c.b}},
                           {"tolerance", {{"half_mm", fit.half_mm}, {"cone_deg", fit.axis_cone_deg}, {"roll_deg", fit.roll_deg}}}});
        for (std::size_t f : plan.cameras[e.index].facets) facet_cameras[f].push_back(e.index);
    }
    scene["cameras"] = std::move(cameras);
    scene["facet_cameras"] = facet_cameras;
    auto uncovered = nlohmann::json::object();  // reason -> facets, so the picker can say why
    for (const auto& u : plan.uncovered) uncovered[to_string(u.reason)].push_back(u.facet);
    scene["uncovered"] = std::move(uncovered);
    // A title that is not UTF-8 (a file name, say) is shown with U+FFFD rather than refused.
    std::string json = scene.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    // Inside <script> the HTML parser looks for "</script" and "<!--" (which changes how it finds
    // the end); in JSON '<' occurs only inside strings, where \u003c means the same character.
    for (std::size_t at = 0; (at = json.find('<', at)) != std::string::npos;) json.replace(at, 1, "\\u003c");
    return detail::html::fill(viewer.html_template, {{"/*@CERTIPOSE_VIEWER_JS@*/", std::string(viewer.script)},
                                                     {"@CERTIPOSE_SCENE_JSON@", json},
                                                     {"@CERTIPOSE_TITLE@", detail::html::escape_text(title)}});
}

}  // namespace certipose
