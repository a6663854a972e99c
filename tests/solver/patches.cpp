// Patches (part/patches.hpp): facets certified at once. The regions keep their cone, extent,
// size and CAD faces; work plans are stable under regrouping (resume, MPI chunks); a patch box
// passes the sampling check for every member (completed, budget-stopped, with camera regions and
// keep-largest); the output does not depend on threads or chunks; and members keep most of what
// they would certify alone.
#include "solver_support.hpp"

#include <certipose/part/part_solver.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

using namespace solver_test;

namespace {

const thin_lens_camera& camera() {
    static const thin_lens_camera c(design_camera_parameters());
    return c;
}

const part_solver<>& whole() {
    static const part_solver<> p(part().mesh, camera(), {.min_view_angle = 0.35});
    return p;
}

part_options patched(std::vector<std::size_t> facets, std::size_t threads = 2) {
    part_options o;
    o.facet = {.position_eps = 0.1, .orientation_eps = 0.38};
    o.facets = std::move(facets);
    o.threads = threads;
    o.patches.enabled = true;
    return o;
}

/// Facets of the first `count` regions of at least `min_members` facets whose first facet faces
/// up or sideways (normal z > −0.2): patches a camera above or beside the part can inspect.
std::vector<std::size_t> facets_of_regions(const patch_regions& regions, std::size_t count, std::size_t min_members) {
    std::map<std::uint32_t, std::vector<std::size_t>> members;
    for (std::size_t f = 0; f < regions.region_of.size(); ++f) members[regions.region_of[f]].push_back(f);
    std::vector<std::size_t> out;
    std::size_t taken = 0;
    for (const auto& [r, m] : members) {
        if (m.size() < min_members || part().mesh.facet(m.front()).normal.z() < -0.2) continue;
        out.insert(out.end(), m.begin(), m.end());
        if (++taken == count) break;
    }
    return out;
}

using outcome_list = std::vector<facet_outcome<boost_interval>>;

bool same_outcomes(const outcome_list& a, const outcome_list& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].record.index != b[i].record.index || a[i].record.patch != b[i].record.patch ||
            a[i].boxes.size() != b[i].boxes.size())
            return false;
        for (std::size_t k = 0; k < a[i].boxes.size(); ++k)
            if (!(a[i].boxes[k].box == b[i].boxes[k].box)) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("patches: regions keep their cone, extent, member cap and CAD faces, and cover the part") {
    const triangle_mesh& mesh = part().mesh;
    patch_options o;
    o.max_cone = 0.17;
    o.max_members = 8;
    const double extent = 0.05;
    std::vector<std::uint32_t> faces(mesh.num_faces());
    for (std::size_t f = 0; f < faces.size(); ++f) faces[f] = static_cast<std::uint32_t>((f / 7) % 3);  // any labelling
    for (const bool with_faces : {false, true}) {
        CAPTURE(with_faces);
        o.faces = with_faces ? faces : std::vector<std::uint32_t>{};
        const patch_regions r = patch_regions::grow(mesh, o, extent);
        REQUIRE(r.region_of.size() == mesh.num_faces());
        std::map<std::uint32_t, std::vector<std::size_t>> members;
        for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
            REQUIRE(r.region_of[f] < r.count);
            members[r.region_of[f]].push_back(f);
        }
        CHECK(members.size() == r.count);
        std::size_t multi = 0;
        for (const auto& [region, m] : members) {
            CHECK(m.size() <= o.max_members);
            multi += m.size() > 1;
            const facet& seed = mesh.facet(m.front());  // the lowest index grows the region
            for (const std::size_t f : m) {
                CHECK(mesh.facet(f).normal.dot(seed.normal) >= std::cos(o.max_cone));
                if (f != m.front())  // the seed is in its region whatever its size
                    for (const auto& v : mesh.facet(f).v) CHECK((v - seed.centroid).norm() <= extent / 2);
                if (with_faces) CHECK(faces[f] == faces[m.front()]);
            }
        }
        CHECK(multi > 20);  // regions of several facets exist
        CHECK(r.count < mesh.num_faces());
    }
    patch_options bad;
    bad.max_members = 0;
    CHECK_THROWS_WITH_AS(bad.validate(10), doctest::Contains("patches.max_members"), certipose::invalid_argument);
    bad = {};
    bad.max_cone = -1;
    CHECK_THROWS_WITH_AS(bad.validate(10), doctest::Contains("-1"), certipose::invalid_argument);
    bad = {};
    bad.faces = {0, 1};
    CHECK_THROWS_WITH_AS(bad.validate(10), doctest::Contains("patches.faces"), certipose::invalid_argument);
}

TEST_CASE("patches: work plans group by region, and grouping a plan's order or a chunk of whole items again is the same") {
    patch_regions r;
    r.region_of = {0, 1, 0, 2, 1, 0, 2, 3};
    r.count = 4;
    const std::vector<std::size_t> selection{7, 3, 0, 1, 2, 4, 6};
    const work_plan p = work_plan::grouped(selection, r);
    CHECK(p.order == std::vector<std::size_t>{7, 3, 6, 0, 2, 1, 4});
    CHECK(p.ends == std::vector<std::size_t>{1, 3, 5, 7});
    const work_plan again = work_plan::grouped(p.order, r);
    CHECK(again.order == p.order);
    CHECK(again.ends == p.ends);
    // A chunk of whole items (items 1 and 2), as an MPI rank or a resumed run gets it.
    const std::vector<std::size_t> chunk(p.order.begin() + 1, p.order.begin() + 5);
    const work_plan c = work_plan::grouped(chunk, r);
    CHECK(c.order == chunk);
    CHECK(c.ends == std::vector<std::size_t>{2, 4});
    const work_plan single = work_plan::per_facet(selection);
    CHECK(single.items() == selection.size());
    CHECK(std::vector<std::size_t>(single.members(2).begin(), single.members(2).end()) == std::vector<std::size_t>{0});
}

TEST_CASE("patches: every VALID box of a patch passes the sampling check for every member, completed and budget-stopped") {
    const auto regions = whole().patches(patched({}));
    REQUIRE(regions);
    const std::vector<std::size_t> facets = facets_of_regions(*regions, 8, 4);
    REQUIRE(facets.size() >= 32);
    part_options complete = patched(facets);
    collecting_sink<boost_interval> full;
    const part_result r = whole().solve(complete, full);
    REQUIRE(r.reason == termination::completed);
    CHECK(r.patched >= 10);  // facets took their patch's boxes
    part_options stopped = complete;
    stopped.max_boxes = std::max<std::size_t>(1, r.valid / 2);
    collecting_sink<boost_interval> cut;
    const part_result rc = whole().solve(stopped, cut);
    CHECK(rc.reason == termination::box_budget);
    // Camera regions and keep-largest with patches: a keep-in box above the part, 3 boxes kept.
    part_options combined = complete;
    combined.regions.keep_in.push_back(parse_camera_region("box:-1,-1,0.05,1,1,1"));
    combined.keep_largest = 3;
    collecting_sink<boost_interval> limited;
    const part_result rl = whole().solve(combined, limited);
    REQUIRE(rl.reason == termination::completed);

    std::uint32_t seed = 5100;
    for (const auto* run : {&full, &cut, &limited}) {
        std::size_t members_checked = 0, violations = 0, samples = 0;
        std::set<std::size_t> seeds;
        for (const auto& o : run->outcomes) {
            if (!o.record.patch || o.boxes.empty()) continue;
            seeds.insert(*o.record.patch);
            // Every member holds its patch's boxes, so checking each member's list checks
            // each box against every member of its patch.
            const auto rep = check_valid_boxes(as_result(o.record.index, o.boxes, o.record.valid), part().mesh, camera(),
                                               whole().solver().range(), 0.35, 2, seed++, true, 12);
            ++members_checked;
            samples += rep.samples;
            violations += rep.violations;
            if (run == &limited) {
                CHECK(o.boxes.size() <= 3);
                for (const auto& b : o.boxes) CHECK(lower(b.box.position[2]) >= 0.05);
            }
        }
        MESSAGE(std::string(run == &full ? "completed" : run == &cut ? "budget-stopped" : "regions + keep-largest")
                << ": " << seeds.size() << " patches, " << members_checked << " members checked, " << samples
                << " poses, " << violations << " violations");
        CHECK(seeds.size() >= 2);
        CHECK(members_checked >= 4);
        CHECK(violations == 0);
    }
}

TEST_CASE("patches: the same boxes with 1 and 2 threads and solved in chunks of whole items") {
    const auto regions = whole().patches(patched({}));
    REQUIRE(regions);
    const std::vector<std::size_t> facets = facets_of_regions(*regions, 5, 3);
    collecting_sink<boost_interval> one, two;
    (void)whole().solve(patched(facets, 1), one);
    (void)whole().solve(patched(facets, 2), two);
    CHECK(same_outcomes(one.outcomes, two.outcomes));
    // The plan's order, cut after its third item, solved as two runs (an MPI rank's chunks, or
    // a run and its resumption).
    const work_plan plan = work_plan::grouped(facets, *regions);
    REQUIRE(plan.items() >= 4);
    const std::vector<std::size_t>& order = plan.order;
    const auto cut = static_cast<std::ptrdiff_t>(plan.ends[2]);
    collecting_sink<boost_interval> chunks;
    (void)whole().solve(patched({order.begin(), order.begin() + cut}), chunks);
    (void)whole().solve(patched({order.begin() + cut, order.end()}), chunks);
    CHECK(same_outcomes(one.outcomes, chunks.outcomes));
    // Every facet reaches the sink once, in the plan's order.
    std::vector<std::size_t> seen;
    for (const auto& o : one.outcomes) seen.push_back(o.record.index);
    CHECK(seen == plan.order);
}

TEST_CASE("patches: members keep most of what they certify alone, and a run keeping BOUNDARY boxes solves facet by facet") {
    const auto regions = whole().patches(patched({}));
    REQUIRE(regions);
    const std::vector<std::size_t> facets = facets_of_regions(*regions, 5, 4);
    collecting_sink<boost_interval> together, alone;
    const part_result rp = whole().solve(patched(facets), together);
    part_options per_facet = patched(facets);
    per_facet.patches.enabled = false;
    const part_result rf = whole().solve(per_facet, alone);
    CHECK(rf.patched == 0);
    std::map<std::size_t, std::size_t> own;
    for (const auto& o : alone.outcomes) own[o.record.index] = o.record.valid;
    double area_alone = 0, area_together = 0;
    for (const auto& o : together.outcomes) {
        const double a = part().mesh.facet(o.record.index).area;
        area_together += o.record.valid > 0 ? a : 0;
        area_alone += own[o.record.index] > 0 ? a : 0;
    }
    MESSAGE("facets " << facets.size() << ": area with a VALID box " << area_together << " (patches) vs " << area_alone
                      << " (alone); " << rp.patched << " facets patched; " << rp.seconds << " s vs " << rf.seconds << " s");
    CHECK(area_alone > 0);
    CHECK(area_together >= 0.9 * area_alone);  // the fallback rule keeps the certified share

    part_options boundary = patched(facets);
    boundary.keep_boundary = true;
    CHECK(whole().patches(boundary) == nullptr);
    collecting_sink<boost_interval> kept;
    const part_result rb = whole().solve(boundary, kept);
    CHECK(rb.patched == 0);
}

TEST_CASE("patches: with a placement tolerance, a patch's boxes hold for every member under every admitted placement") {
    inspection_task task{.min_view_angle = 0.35};
    task.placement = placement_tolerance{.translation = {0.002, 0.002, 0.0}, .rotation = 0.005};
    const part_solver<> placed(part().mesh, camera(), task);
    const auto regions = placed.patches(patched({}));
    REQUIRE(regions);
    const std::vector<std::size_t> facets = facets_of_regions(*regions, 4, 4);
    collecting_sink<boost_interval> sink;
    const part_result r = placed.solve(patched(facets), sink);
    REQUIRE(r.reason == termination::completed);
    std::size_t members = 0, violations = 0, samples = 0;
    std::uint32_t seed = 5200;
    for (const auto& o : sink.outcomes) {
        if (!o.record.patch || o.boxes.empty()) continue;
        ++members;
        const auto rep = check_placed(as_result(o.record.index, o.boxes, o.record.valid), part().mesh, placed.solver().camera(),
                                      placed.solver().range(), task.min_view_angle, *placed.solver().placement(), {}, 2, 2,
                                      seed++, 8);
        samples += rep.samples;
        violations += rep.violations;
    }
    MESSAGE("placement: " << r.patched << " facets patched, " << members << " checked, " << samples << " poses, "
                          << violations << " violations");
    CHECK(members >= 2);
    CHECK(samples > 0);
    CHECK(violations == 0);
}
