// certipose/io/plan_sheet.hpp — a plan as a printable installation sheet: one HTML page per
// camera, with the view from its nominal pose and the numbers a fitter sets (the CSV's, in
// millimetres and degrees, rounded as plan_csv rounds them: positions to 0.1 mm, tolerances
// inward). Self-contained: no script, no font, no request; each page is an A4 landscape sheet
// when printed (CSS break-after), and the same sections one under the other on screen.
//
// The view is an SVG in the camera's image coordinates (pixels, the image's own size): every
// facet facing the camera and in front of it, projected through K at the nominal pose and drawn
// far to near (a painter's order by centroid depth; a picture, not a visibility certificate).
// The facets this camera certifies are in its plan colour, the ones other cameras certify light
// grey, those no camera certifies darker, the occluders slate; the aim point is marked.
//
// Every number sits in a cell with a data-field named after the CSV column it equals
// (docs/conventions.md#sheet), so a test can hold the two against each other.
#pragma once

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/plan_export.hpp"
#include "certipose/io/plan_html.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

namespace certipose {

/// What plan_sheet draws besides the plan and its part.
struct sheet_options {
    std::string title = "certipose installation sheet";
    /// The plan's occluder meshes (read_plan_occluders), drawn in the views; none: not drawn.
    std::span<const triangle_mesh> occluders{};
};

namespace detail::sheet {
inline std::string hex(rgb c, double shade) {
    const auto s = [&](std::uint8_t v) { return static_cast<int>(std::clamp(std::lround(v * shade), 0L, 255L)); };
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", s(c.r), s(c.g), s(c.b));
    return buf;
}

struct drawn {
    double depth;
    std::array<double, 6> uv;
    std::string fill;
};

/// The SVG view from camera `e` (see the header comment).
inline std::string view_svg(const triangle_mesh& mesh, const plan_document& plan, const camera_export& e,
                            const std::vector<std::size_t>& first, std::span<const triangle_mesh> occluders) {
    const auto& K = plan.camera.K;
    const double W = plan.camera.width_px, H = plan.camera.height_px;
    const Eigen::Vector3d p(e.position[0], e.position[1], e.position[2]);
    const Eigen::Matrix3d Rt = e.rotation.transpose();
    const double near = std::max(1e-4, plan.camera.d_min / 20);
    std::vector<char> mine(mesh.num_faces(), 0);
    for (std::size_t f : plan.cameras[e.index].facets) mine[f] = 1;
    const std::vector<char> unseen = plan_unseen_facets(mesh.num_faces(), plan);
    std::vector<drawn> out;
    const auto add = [&](const facet& fa, rgb colour, bool two_sided) {
        std::array<Eigen::Vector3d, 3> c;
        for (int i = 0; i < 3; ++i) {
            c[i] = Rt * (fa.v[i] - p);
            if (!(c[i].z() > near)) return;  // behind the camera or too close to project
        }
        const Eigen::Vector3d n = Rt * fa.normal, centre = (c[0] + c[1] + c[2]) / 3;
        const double facing = -n.dot(centre.normalized());
        if (!two_sided && !(facing > 0)) return;  // the back of a facet
        drawn d{centre.z(), {}, hex(colour, 0.5 + 0.5 * std::abs(facing))};
        bool left = true, right = true, above = true, below = true;
        for (int i = 0; i < 3; ++i) {
            const double x = c[i].x() / c[i].z(), y = c[i].y() / c[i].z();
            d.uv[2 * i] = K[0][0] * x + K[0][1] * y + K[0][2];
            d.uv[2 * i + 1] = K[1][1] * y + K[1][2];
            left = left && d.uv[2 * i] < 0, right = right && d.uv[2 * i] > W;
            above = above && d.uv[2 * i + 1] < 0, below = below && d.uv[2 * i + 1] > H;
        }
        if (!(left || right || above || below)) out.push_back(std::move(d));
    };
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
        const rgb colour = mine[f]                        ? plan_camera_colour(e.index)
                           : first[f] < plan.cameras.size() ? rgb{205, 208, 214}
                           : unseen[f]                      ? plan_unseen_colour
                                                            : plan_uncovered_colour;
        add(mesh.facet(f), colour, false);
    }
    for (const auto& m : occluders)
        for (std::size_t f = 0; f < m.num_faces(); ++f) add(m.facet(f), rgb{120, 126, 138}, true);
    std::stable_sort(out.begin(), out.end(), [](const drawn& a, const drawn& b) { return a.depth > b.depth; });

    std::string s;
    char buf[160];
    std::snprintf(buf, sizeof buf, "<svg class=\"view\" viewBox=\"0 0 %.0f %.0f\" xmlns=\"http://www.w3.org/2000/svg\">", W, H);
    s += buf;
    std::snprintf(buf, sizeof buf, "<rect width=\"%.0f\" height=\"%.0f\" fill=\"#f4f5f7\"/><g stroke-linejoin=\"round\">", W, H);
    s += buf;
    for (const auto& d : out) {
        std::snprintf(buf, sizeof buf, "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" stroke=\"%s\"/>", d.uv[0],
                      d.uv[1], d.uv[2], d.uv[3], d.uv[4], d.uv[5], d.fill.c_str(), d.fill.c_str());
        s += buf;
    }
    s += "</g>";
    // The aim point lies on the optical axis: the principal point.
    const double r = 0.02 * std::min(W, H);
    std::snprintf(buf, sizeof buf,
                  "<g class=\"aim\" stroke=\"#d0021b\" stroke-width=\"%.1f\" fill=\"none\"><circle cx=\"%.1f\" cy=\"%.1f\" "
                  "r=\"%.1f\"/>",
                  r / 5, K[0][2], K[1][2], r);
    s += buf;
    std::snprintf(buf, sizeof buf, "<path d=\"M%.1f %.1fh%.1fM%.1f %.1fv%.1f\"/></g>", K[0][2] - 2 * r, K[1][2], 4 * r, K[0][2],
                  K[1][2] - 2 * r, 4 * r);
    s += buf;
    std::snprintf(buf, sizeof buf, "<rect width=\"%.0f\" height=\"%.0f\" fill=\"none\" stroke=\"#1d2330\" stroke-width=\"%.1f\"/>",
                  W, H, std::max(W, H) / 400);
    s += buf;
    return s + "</svg>";
}
}  // namespace detail::sheet

/// The sheet's bytes (see the header comment). Throws out_of_range for a plan facet beyond `mesh`.
inline std::string plan_sheet(const triangle_mesh& mesh, const plan_document& plan, const sheet_options& o = {}) {
    using detail::html::escape_text;
    using detail::plan_export::fixed;
    const auto exports = camera_exports(plan);
    const auto first = plan_first_cameras(mesh.num_faces(), plan);
    const certipose::detail::round_to_nearest_scope nearest;
    const std::string title = escape_text(o.title);
    std::string s =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<link rel=\"icon\" href=\"data:,\">\n<title>" +
        title + "</title>\n" +
        R"(<style>
  @page { size: A4 landscape; margin: 10mm; }
  body { margin: 0; font: 11pt/1.35 system-ui, sans-serif; color: #1d2330; background: #e9ebef; }
  .page { box-sizing: border-box; width: 277mm; height: 190mm; margin: 8mm auto; padding: 8mm; background: #fff;
          display: grid; grid-template-columns: 1fr 92mm; grid-template-rows: auto 1fr auto; gap: 3mm 6mm;
          break-after: page; overflow: hidden; }
  .page:last-child { break-after: auto; }
  header { grid-column: 1 / 3; display: flex; justify-content: space-between; align-items: baseline;
           border-bottom: 2px solid #1d2330; }
  header h1 { font-size: 16pt; margin: 0; }
  .swatch { display: inline-block; width: 10pt; height: 10pt; border-radius: 2pt; margin-right: 4pt;
            border: 1px solid rgba(0,0,0,.3); vertical-align: -1pt; }
  .view { width: 100%; max-height: 140mm; }
  table { border-collapse: collapse; width: 100%; font-size: 9pt; line-height: 1.2; font-variant-numeric: tabular-nums;
          align-self: start; }
  th { text-align: left; font-weight: 600; padding: 1pt 6pt 1pt 0; white-space: nowrap; }
  td { text-align: right; padding: 1pt 0 1pt 6pt; }
  tr.group th { padding-top: 4pt; border-bottom: 1px solid #c9ced8; }
  footer { grid-column: 1 / 3; font-size: 8.5pt; color: #5b6475; }
  @media print { body { background: #fff; } .page { margin: 0; width: auto; height: 190mm; } }
</style>
</head>
<body>
)";
    const auto& cam = plan.camera;
    for (const auto& e : exports) {
        const auto& box = plan.cameras[e.index];
        const fitter_camera f = fitter_units(e, box);
        const rgb colour = plan_camera_colour(e.index);
        const std::string k = std::to_string(e.index);
        s += "<section class=\"page\" data-camera=\"" + k + "\">\n<header><h1><span class=\"swatch\" style=\"background:" +
             detail::sheet::hex(colour, 1.0) + "\"></span>Camera " + k + "</h1><span>" + title + " · camera " +
             std::to_string(e.index + 1) + " of " + std::to_string(exports.size()) + "</span></header>\n";
        s += "<div>" + detail::sheet::view_svg(mesh, plan, e, first, o.occluders) + "</div>\n<table>\n";
        const auto row = [&](const std::string& label, const std::string& field, const std::string& value, const char* unit) {
            s += "<tr><th>" + label + "</th><td data-field=\"" + field + "\">" + value + "</td><td>" + unit + "</td></tr>\n";
        };
        const auto group = [&](const char* label) { s += std::string("<tr class=\"group\"><th colspan=\"3\">") + label + "</th></tr>\n"; };
        static constexpr const char* axes[] = {"x", "y", "z"};
        group("Projection centre (nominal)");
        for (int i = 0; i < 3; ++i) row(axes[i], std::string(axes[i]) + "_mm", fixed(f.position_mm[i], 1), "mm");
        group("Mount point");
        for (int i = 0; i < 3; ++i) row(axes[i], std::string("mount_") + axes[i] + "_mm", fixed(f.mount_mm[i], 1), "mm");
        group("Orientation (quaternion)");
        static constexpr const char* q[] = {"qx", "qy", "qz", "qw"};
        for (int i = 0; i < 4; ++i) row(q[i], q[i], fixed(e.quaternion[i], 9), "");
        group("Installation tolerance");
        for (int i = 0; i < 3; ++i) row(std::string("± ") + axes[i], std::string("half_") + axes[i] + "_mm", fixed(f.half_mm[i], 1), "mm");
        row("optical axis within", "axis_cone_half_angle_deg", fixed(f.axis_cone_deg, 2), "°");
        row("roll ±", "roll_half_range_deg", fixed(f.roll_deg, 2), "°");
        group("Aim point on the part");
        if (f.aim_mm) {
            for (int i = 0; i < 3; ++i) row(axes[i], std::string("aim_") + axes[i] + "_mm", fixed((*f.aim_mm)[i], 1), "mm");
            row("distance", "aim_distance_mm", fixed(f.aim_distance_mm, 1), "mm");
        } else {
            s += "<tr><th colspan=\"3\">not recorded (a plan made before aim points)</th></tr>\n";
        }
        group("Certifies");
        row("facets", "facets", std::to_string(box.facets.size()), "");
        row("area", "certified_area_mm2", fixed(1e6 * box.certified_area, 1), "mm²");
        s += "</table>\n<footer>Image " + fixed(cam.width_px, 0) + " × " + fixed(cam.height_px, 0) + " px, f = " +
             fixed(cam.K[0][0], 1) + " px, in focus from " + fixed(1000 * cam.d_min, 1) + " mm" +
             (std::isfinite(cam.d_max) ? " to " + fixed(1000 * cam.d_max, 1) + " mm" : std::string()) +
             ". Every pose within these tolerances of the nominal is certified (the tolerances are rounded inward; "
             "positions to 0.1 mm, angles to 0.01°). Part frame, millimetres; the view is from the nominal pose, the "
             "red mark is the aim point. Part: " +
             escape_text(plan.mesh.path) + " (" + std::to_string(plan.mesh.faces) + " facets, digest " +
             escape_text(plan.mesh.digest) + ").</footer>\n</section>\n";
    }
    if (exports.empty()) s += "<p>This plan has no camera.</p>\n";
    return s + "</body>\n</html>\n";
}

}  // namespace certipose
