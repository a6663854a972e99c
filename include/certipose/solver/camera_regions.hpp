// certipose/solver/camera_regions.hpp — where a camera may stand: keep-in and keep-out regions
// of camera positions, and the stage that restricts a solve result's VALID boxes to them.
//
//   certipose::camera_regions regions;
//   regions.keep_out.push_back(certipose::camera_region::box({-1, -1, -1}, {1, 1, -0.01}));  // below the table
//   regions.keep_in.push_back(certipose::parse_camera_region("sphere:0.4,0,0.6,0.9"));        // the robot's reach
//   regions.validate();
//   auto result = solver.solve(facet, options);
//   certipose::restrict_to_regions(result, regions, options.position_eps);
//
// A region is a closed box [xmin, xmax]×[ymin, ymax]×[zmin, zmax] or a closed ball (centre,
// radius) in the part's frame, metres (after any --scale). A camera position — the projection
// centre, the position part of a pose — is *allowed* when it lies in no keep-out region and,
// if any keep-in region is given, in at least one keep-in region. Boundaries belong to their
// region: a point on a keep-out's surface is forbidden, one on a keep-in's surface allowed.
//
// `restrict_to_regions` is a stage run after the solve (its orientation intervals untouched):
// every VALID box is classified against the regions —
//   - allowed (inside one keep-in, or there are none, and disjoint from every keep-out): kept;
//   - forbidden (inside one keep-out, or disjoint from every keep-in): dropped, counted in
//     `stats.region_dropped` — decided, like a box the solver proved invalid, so not returned
//     (a BOUNDARY box would claim it undecided);
//   - neither: cut exactly on the faces of the box regions that cross it (a box region leaves
//     nothing undecided, in at most six cuts), then, for spheres, bisected on its widest position
//     axis; the pieces are decided the same way, down to `camera_regions::width(ε_p)` (0 → ε_p / 10,
//     carving's minimal piece); what is still undecided then is returned BOUNDARY with reason
//     `camera_region`, keeping its orientation intervals (only the position is in doubt).
// Any sub-box of a VALID box is VALID (its certificate holds for every pose in it), so the stage
// only removes poses. The box–box tests compare doubles exactly; the box–sphere tests bound the
// squared distance with outward-rounded interval arithmetic (the result's interval type, under
// its rounding guard), so "allowed" and "forbidden" are proofs and a rounding doubt leaves a piece
// undecided. BOUNDARY boxes of the solve are left as they are (they certify nothing).
#pragma once

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/result.hpp"

namespace certipose {

/// A closed region of camera positions: a box or a ball (see the header comment).
struct camera_region {
    enum class shape_type : std::uint8_t { box, sphere };
    shape_type shape = shape_type::box;
    /// box: xmin, ymin, zmin, xmax, ymax, zmax; sphere: x, y, z, r (the last two are 0).
    std::array<double, 6> values{};

    static camera_region box(const std::array<double, 3>& min, const std::array<double, 3>& max) {
        return {shape_type::box, {min[0], min[1], min[2], max[0], max[1], max[2]}};
    }
    static camera_region sphere(const std::array<double, 3>& centre, double radius) {
        return {shape_type::sphere, {centre[0], centre[1], centre[2], radius, 0.0, 0.0}};
    }

    bool is_box() const noexcept { return shape == shape_type::box; }
    /// "box" or "sphere" (the text form's prefix and the JSON key).
    const char* name() const noexcept { return is_box() ? "box" : "sphere"; }
    /// The 6 numbers of a box, the 4 of a sphere.
    std::span<const double> numbers() const noexcept { return {values.data(), is_box() ? 6u : 4u}; }

    /// What is wrong with the region ("xmin 1 is not below xmax 0"), empty when nothing is:
    /// every number finite, min < max on each axis, r > 0.
    std::string problem() const {
        for (double v : numbers())
            if (!std::isfinite(v)) return "every number must be finite, got " + detail::format_double(v);
        if (is_box()) {
            static constexpr const char* axis[] = {"x", "y", "z"};
            for (std::size_t k = 0; k < 3; ++k)
                if (!(values[k] < values[k + 3]))
                    return std::string(axis[k]) + "min " + detail::format_double(values[k]) + " is not below " + axis[k] +
                           "max " + detail::format_double(values[k + 3]);
        } else if (!(values[3] > 0.0)) {
            return "the radius must be positive, got " + detail::format_double(values[3]);
        }
        return {};
    }
    /// Throws invalid_argument(field, "FIELD: <problem> in box:...") unless problem() is empty.
    void validate(const std::string& field = "region") const;

    friend bool operator==(const camera_region&, const camera_region&) = default;
};

/// "box:xmin,ymin,zmin,xmax,ymax,zmax" or "sphere:x,y,z,r", numbers in shortest round-trip form
/// (parse_camera_region reads it back to an equal region).
inline std::string to_string(const camera_region& r) {
    std::string s = r.name();
    s += ':';
    bool first = true;
    for (double v : r.numbers()) {
        if (!first) s += ',';
        first = false;
        detail::append_double(s, v);
    }
    return s;
}

inline void camera_region::validate(const std::string& field) const {
    if (const std::string why = problem(); !why.empty())
        throw invalid_argument(field, field + ": " + why + " in " + to_string(*this));
}

/// Reads "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX" or "sphere:X,Y,Z,R" (metres) and validates it.
/// Throws invalid_argument(field) naming `text` for anything else.
inline camera_region parse_camera_region(std::string_view text, const std::string& field = "region") {
    const std::string quoted = "'" + std::string(text) + "'";
    const auto fail = [&](const std::string& why) -> camera_region {
        throw invalid_argument(field, field + ": " + why + " in " + quoted);
    };
    const std::size_t colon = text.find(':');
    const std::string_view kind = text.substr(0, colon);
    if (colon == std::string_view::npos || (kind != "box" && kind != "sphere"))
        throw invalid_argument(field, field + ": expected box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or sphere:X,Y,Z,R (metres), got " +
                                          quoted);
    camera_region r;
    r.shape = kind == "box" ? camera_region::shape_type::box : camera_region::shape_type::sphere;
    const std::size_t expected = r.is_box() ? 6 : 4;
    const certipose::detail::round_to_nearest_scope nearest;  // from_chars may honour the rounding mode
    std::string_view rest = text.substr(colon + 1);
    std::size_t n = 0;
    while (true) {
        const std::size_t comma = rest.find(',');
        const std::string_view item = rest.substr(0, comma);
        double v = 0.0;
        const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
        if (item.empty() || ec != std::errc{} || end != item.data() + item.size())
            return fail("'" + std::string(item) + "' is not a number");
        if (n < expected) r.values[n] = v;
        ++n;
        if (comma == std::string_view::npos) break;
        rest = rest.substr(comma + 1);
    }
    if (n != expected)
        return fail("expected " + std::to_string(expected) + " numbers after '" + std::string(kind) + ":', got " +
                    std::to_string(n));
    if (const std::string why = r.problem(); !why.empty()) return fail(why);
    return r;
}

/// How a position box lies with respect to a closed region.
enum class region_relation : std::uint8_t {
    inside,    ///< every point of the box is in the region (proven)
    outside,   ///< no point of the box is in the region (proven)
    straddles  ///< neither proven
};

/// The relation of `b` (non-empty) to `r`: exact comparisons for a box region; for a sphere,
/// the squared distances from its centre over `b`, bounded with outward rounding.
template <Interval I>
region_relation relate(const position_box<I>& b, const camera_region& r) {
    if (r.is_box()) {
        bool inside = true;
        for (std::size_t k = 0; k < 3; ++k) {
            const double lo = lower(b[k]), hi = upper(b[k]);
            if (hi < r.values[k] || lo > r.values[k + 3]) return region_relation::outside;
            inside = inside && r.values[k] <= lo && hi <= r.values[k + 3];
        }
        return inside ? region_relation::inside : region_relation::straddles;
    }
    const rounding_guard<I> rounding;
    // Over a box the offsets on the three axes vary independently, so Σ sqr(b_k − c_k) encloses
    // exactly {‖p − c‖² : p ∈ b}, widened only by the outward rounding.
    I d2(0.0);
    for (std::size_t k = 0; k < 3; ++k) d2 = d2 + sqr(b[k] - I(r.values[k]));
    const I r2 = sqr(I(r.values[3]));
    if (lower(d2) > upper(r2)) return region_relation::outside;
    if (upper(d2) <= lower(r2)) return region_relation::inside;
    return region_relation::straddles;
}

/// What the regions say of a whole position box.
enum class region_verdict : std::uint8_t {
    allowed,    ///< every position of the box is allowed (proven)
    forbidden,  ///< no position of the box is allowed (proven)
    undecided   ///< neither proven: the box straddles a region's surface (or a rounding doubt)
};

constexpr const char* to_string(region_verdict v) noexcept {
    switch (v) {
        case region_verdict::allowed: return "allowed";
        case region_verdict::forbidden: return "forbidden";
        case region_verdict::undecided: return "undecided";
    }
    return "?";
}

/// The keep-in and keep-out regions of a run (see the header comment).
struct camera_regions {
    std::vector<camera_region> keep_in{}, keep_out{};
    /// Pieces no wider than this (metres, on their widest position axis) are not bisected
    /// further; 0: ε_p / 10 (carving's minimal piece, solver/paving.hpp).
    double min_width = 0.0;

    bool empty() const noexcept { return keep_in.empty() && keep_out.empty(); }
    /// The width below which pieces are not bisected.
    double width(double position_eps) const noexcept { return min_width > 0.0 ? min_width : position_eps / 10; }

    /// Throws invalid_argument naming the region ("keep_out[1]: xmin 1 is not below xmax 0 in
    /// box:1,0,0,0,1,1") or min_width.
    void validate() const {
        for (std::size_t i = 0; i < keep_in.size(); ++i) keep_in[i].validate("keep_in[" + std::to_string(i) + "]");
        for (std::size_t i = 0; i < keep_out.size(); ++i) keep_out[i].validate("keep_out[" + std::to_string(i) + "]");
        if (!(min_width >= 0.0) || !std::isfinite(min_width))
            throw invalid_argument("min_width", "camera_regions: min_width must be >= 0 and finite, got " +
                                                    detail::format_double(min_width));
    }

    /// Whether the positions of `b` (non-empty) are all allowed, none, or undecided.
    template <Interval I>
    region_verdict classify(const position_box<I>& b) const {
        bool clear = true;  // disjoint from every keep-out
        for (const auto& r : keep_out) {
            const region_relation rel = relate(b, r);
            if (rel == region_relation::inside) return region_verdict::forbidden;
            clear = clear && rel == region_relation::outside;
        }
        if (keep_in.empty()) return clear ? region_verdict::allowed : region_verdict::undecided;
        bool within = false, away = true;  // inside one keep-in; outside all
        for (const auto& r : keep_in) {
            const region_relation rel = relate(b, r);
            within = within || rel == region_relation::inside;
            away = away && rel == region_relation::outside;
        }
        if (away) return region_verdict::forbidden;
        return clear && within ? region_verdict::allowed : region_verdict::undecided;
    }

    friend bool operator==(const camera_regions&, const camera_regions&) = default;
};

/// A position box cut by the regions: the allowed pieces, the undecided ones, and counts.
template <Interval I>
struct region_pieces {
    std::vector<position_box<I>> allowed, undecided;
    std::size_t forbidden = 0, bisections = 0;
};

namespace detail::regions {
/// A cut of an undecided box `q` along a face of a box region that crosses it: the two pieces
/// [lo, below] and [above, hi] on axis `k`, with below < above adjacent doubles, so each piece
/// lies wholly on one side of the face (the closed region holds `above` = its min, or `below` =
/// its max). The reals strictly between the two doubles are given up: only poses are removed.
struct face_cut {
    std::size_t k = 0;
    double below = 0, above = 0;
};

template <Interval I>
std::optional<face_cut> box_face_cut(const position_box<I>& q, const std::vector<camera_region>& regions) {
    for (const auto& r : regions) {
        if (!r.is_box()) continue;
        for (std::size_t k = 0; k < 3; ++k) {
            const double lo = lower(q[k]), hi = upper(q[k]), a = r.values[k], b = r.values[k + 3];
            if (lo < a && a <= hi) return face_cut{k, std::nextafter(a, -INFINITY), a};
            if (lo <= b && b < hi) return face_cut{k, b, std::nextafter(b, INFINITY)};
        }
    }
    return std::nullopt;
}
}  // namespace detail::regions

/// `b` cut into allowed, forbidden and undecided pieces (see the header comment). While a piece
/// is undecided it is cut exactly on a face of a box region that crosses it (at most six cuts a
/// region, leaving nothing undecided by box regions), else bisected on its widest axis while wider
/// than `min_width` (> 0; spheres). Pieces come in a deterministic order (depth first, lower
/// piece first).
template <Interval I>
region_pieces<I> split_by_regions(const position_box<I>& b, const camera_regions& regions, double min_width) {
    if (!(min_width > 0.0) || !std::isfinite(min_width))
        throw invalid_argument("min_width", "split_by_regions: min_width must be positive and finite, got " +
                                                detail::format_double(min_width));
    if (is_empty(b)) throw invalid_argument("box", "split_by_regions: the position box is empty");
    region_pieces<I> out;
    std::vector<position_box<I>> todo{b};
    while (!todo.empty()) {
        const position_box<I> q = todo.back();
        todo.pop_back();
        switch (regions.classify(q)) {
            case region_verdict::allowed: out.allowed.push_back(q); continue;
            case region_verdict::forbidden: ++out.forbidden; continue;
            case region_verdict::undecided: break;
        }
        position_box<I> low = q, high = q;
        auto f = detail::regions::box_face_cut(q, regions.keep_out);
        if (!f) f = detail::regions::box_face_cut(q, regions.keep_in);
        if (f) {
            low[f->k] = I(lower(q[f->k]), f->below);
            high[f->k] = I(f->above, upper(q[f->k]));
        } else {
            const std::size_t k = widest_dimension(q);
            const double cut = split_point(q[k]);
            if (width(q[k]) <= min_width || !(lower(q[k]) < cut && cut < upper(q[k]))) {
                out.undecided.push_back(q);
                continue;
            }
            std::tie(low, high) = bisect_at(q, k, cut);
        }
        ++out.bisections;
        todo.push_back(high);
        todo.push_back(low);  // next: the lower half first
    }
    return out;
}

/// The camera-region stage (see the header comment): `result`'s VALID boxes restricted to the
/// positions `regions` allows, pieces no wider than regions.width(position_eps). Updates the
/// counts, volumes and boundary reasons of result.stats, and region_dropped / region_bisections.
/// Nothing changes when `regions` is empty. Throws invalid_argument for invalid regions or ε_p.
template <Interval I>
void restrict_to_regions(solve_result<I>& result, const camera_regions& regions, double position_eps) {
    regions.validate();
    if (regions.empty()) return;
    if (!(position_eps > 0.0) || !std::isfinite(position_eps))
        throw invalid_argument("position_eps", "restrict_to_regions: position_eps must be positive and finite, got " +
                                                   detail::format_double(position_eps));
    const double min_width = regions.width(position_eps);
    solve_stats& st = result.stats;
    // Position boxes shared by several orientation boxes are cut once; the volumes count each
    // position box once, as the orientation stage does.
    std::map<std::array<double, 6>, region_pieces<I>> cut;
    std::vector<classified_box<I>> boxes;
    boxes.reserve(result.boxes.size());
    constexpr auto reason = boundary_reason::camera_region;
    for (auto& b : result.boxes) {
        if (b.cls != box_class::valid) {
            boxes.push_back(std::move(b));
            continue;
        }
        const auto& p = b.box.position;
        const std::array<double, 6> key{lower(p[0]), lower(p[1]), lower(p[2]), upper(p[0]), upper(p[1]), upper(p[2])};
        auto it = cut.find(key);
        if (it == cut.end()) {
            it = cut.emplace(key, split_by_regions(p, regions, min_width)).first;
            const region_pieces<I>& pieces = it->second;
            st.region_bisections += pieces.bisections;
            if (pieces.allowed.size() != 1 || !pieces.undecided.empty() || pieces.forbidden != 0) {
                double kept = 0.0, doubtful = 0.0;
                for (const auto& q : pieces.allowed) kept += volume(q);
                for (const auto& q : pieces.undecided) doubtful += volume(q);
                st.valid_volume = std::max(0.0, st.valid_volume - std::max(0.0, volume(p) - kept));
                st.boundary_volume += doubtful;
            }
        }
        const region_pieces<I>& pieces = it->second;
        st.region_dropped += pieces.forbidden;
        for (const auto& q : pieces.allowed)
            boxes.push_back(classified_box<I>{box_class::valid, pose_box<I>{q, b.box.orientation}});
        for (const auto& q : pieces.undecided) {
            boxes.push_back(classified_box<I>{box_class::boundary, pose_box<I>{q, b.box.orientation}, reason});
            ++st.boundary;
            ++st.boundary_reasons[static_cast<std::size_t>(reason)];
        }
    }
    result.boxes = std::move(boxes);
    st.valid = static_cast<std::size_t>(std::count_if(result.boxes.begin(), result.boxes.end(),
                                                      [](const classified_box<I>& b) { return b.cls == box_class::valid; }));
}

}  // namespace certipose
