// Tests of certipose/geometry/triangle_mesh.hpp and sample_part.hpp (no CGAL).
#include <certipose/geometry/sample_part.hpp>
#include <certipose/geometry/triangle_mesh.hpp>
#include <certipose/io/write_mesh.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

using certipose::face_indices;
using certipose::triangle_mesh;
using V = Eigen::Vector3d;

namespace {

// Unit right tetrahedron, faces counter-clockwise seen from outside.
std::vector<V> tetra_vertices() { return {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0, 0, 1)}; }
std::vector<face_indices> tetra_faces() { return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}; }
triangle_mesh tetra() { return triangle_mesh(tetra_vertices(), tetra_faces()); }

template <class F>
std::string mesh_error_message(F&& f) {
    try {
        f();
    } catch (const certipose::mesh_error& e) {
        return e.what();
    }
    return "<no mesh_error thrown>";
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("triangle_mesh: validation errors name the offending vertex or face") {
    SUBCASE("empty") {
        CHECK_THROWS_AS(triangle_mesh({}, {}), certipose::mesh_error);
        CHECK_THROWS_AS(triangle_mesh(tetra_vertices(), {}), certipose::mesh_error);
        CHECK(contains(mesh_error_message([] { triangle_mesh({}, {}); }), "empty"));
    }
    SUBCASE("non-finite coordinate") {
        for (double bad : {std::nan(""), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()}) {
            auto v = tetra_vertices();
            v[2].y() = bad;
            const std::string msg = mesh_error_message([&] { triangle_mesh(v, tetra_faces()); });
            CHECK(contains(msg, "vertex 2"));
            CHECK(contains(msg, " y = "));
            CHECK(contains(msg, std::isnan(bad) ? "nan" : "inf"));
        }
    }
    SUBCASE("face index out of range") {
        auto f = tetra_faces();
        f[3][1] = 4;
        const std::string msg = mesh_error_message([&] { triangle_mesh(tetra_vertices(), f); });
        CHECK(contains(msg, "face 3"));
        CHECK(contains(msg, "vertex 4"));
    }
    SUBCASE("repeated vertex in a face") {
        auto f = tetra_faces();
        f[1] = {1, 3, 1};
        const std::string msg = mesh_error_message([&] { triangle_mesh(tetra_vertices(), f); });
        CHECK(contains(msg, "face 1"));
        CHECK(contains(msg, "repeats"));
    }
    SUBCASE("coincident positions under different indices are degenerate") {
        auto v = tetra_vertices();
        v.push_back(V(1, 0, 0));  // same position as vertex 1
        auto f = tetra_faces();
        f.push_back({0, 1, 4});
        const std::string msg = mesh_error_message([&] { triangle_mesh(v, f); });
        CHECK(contains(msg, "face 4"));
        CHECK(contains(msg, "degenerate"));
    }
    SUBCASE("exactly collinear although the double cross product is not zero") {
        // Three points of one line (a + t·(d1, d2, d3) with integer d and dyadic a, t), all
        // coordinates exact doubles, found by an exact rational search; b − a and c − a round.
        const V a(0x1.cc3b0f2bp+1, 0x1.75b24a4cp+1, 0x1.a590c4p-9);
        const V b(0x1.d89c2d6p+1, 0x1.7b32c98p+1, 0x1.4148598p-4);
        const V c(0x1.8eaeba5e2p+22, 0x1.62627757d6p+21, 0x1.3616140066516p+22);
        REQUIRE((b - a).cross(c - a).norm() > 0.0);  // ... but naive double arithmetic says no
        const std::string msg = mesh_error_message([&] {
            triangle_mesh({a, b, c}, {face_indices{0, 1, 2}});
        });
        CHECK(contains(msg, "face 0"));
        CHECK(contains(msg, "collinear"));
    }
    SUBCASE("a thin but non-collinear sliver is accepted") {
        const triangle_mesh m({V(0, 0, 0), V(1, 0, 0), V(0.5, 1e-12, 0)}, {face_indices{0, 1, 2}});
        CHECK(m.facet(0).normal.isApprox(V(0, 0, 1)));
        CHECK(m.facet(0).area == doctest::Approx(0.5e-12).epsilon(1e-9));
    }
    SUBCASE("a normal that underflows is rejected") {
        const double t = 1e-200;  // cross product ~1e-400 underflows to 0
        const std::string msg = mesh_error_message([&] {
            triangle_mesh({V(0, 0, 0), V(t, 0, 0), V(0, t, 0)}, {face_indices{0, 1, 2}});
        });
        CHECK(contains(msg, "face 0"));
        CHECK(contains(msg, "not representable"));
    }
}

TEST_CASE("exact collinearity: random points of a line, and one ulp off it") {
    // a + t·d with d a small integer vector and a, t dyadic with few bits: exact doubles.
    std::mt19937_64 rng(12345);
    std::uniform_int_distribution<int> small(-9, 9), mant(1, 1 << 20), shift(0, 40);
    int checked = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const V d(small(rng), small(rng), small(rng));
        if (d.isZero()) continue;
        const V a(std::ldexp(mant(rng), -shift(rng)), std::ldexp(mant(rng), -shift(rng)),
                  std::ldexp(-mant(rng), -shift(rng)));
        const double t1 = std::ldexp(mant(rng), -shift(rng)),
                     t2 = -std::ldexp(mant(rng), -shift(rng));
        const V b = a + t1 * d, c = a + t2 * d;
        // Skip the rare case where a + t·d rounded (then the points are not on the line).
        const auto exact = [&](const V& p, double t) {
            for (int k = 0; k < 3; ++k)
                if (p[k] - a[k] != t * d[k] || (p[k] - t * d[k]) != a[k]) return false;
            return true;
        };
        if (!exact(b, t1) || !exact(c, t2)) continue;
        ++checked;
        CHECK(certipose::detail::mesh::exactly_collinear(a, b, c));
        V c_off = c;
        c_off.x() = std::nextafter(c.x(), 1e300);
        if (d.y() != 0 || d.z() != 0)
            CHECK_FALSE(certipose::detail::mesh::exactly_collinear(a, b, c_off));
    }
    CHECK(checked > 500);
}

TEST_CASE("triangle_mesh: facet data of a hand-made tetrahedron") {
    const triangle_mesh m = tetra();
    CHECK(m.num_vertices() == 4);
    CHECK(m.num_faces() == 4);
    CHECK(m.bbox().min() == V(0, 0, 0));
    CHECK(m.bbox().max() == V(1, 1, 1));
    const V normals[4] = {V(0, 0, -1), V(0, -1, 0), V(-1, 0, 0), V(1, 1, 1).normalized()};
    const double areas[4] = {0.5, 0.5, 0.5, std::sqrt(3.0) / 2};
    for (std::size_t i = 0; i < 4; ++i) {
        const auto& f = m.facet(i);
        CAPTURE(i);
        for (int k = 0; k < 3; ++k) CHECK(f.v[k] == m.vertices()[m.faces()[i][k]]);
        CHECK((f.normal - normals[i]).norm() < 1e-15);
        CHECK(f.area == doctest::Approx(areas[i]).epsilon(1e-15));
        CHECK((f.centroid - (f.v[0] + f.v[1] + f.v[2]) / 3).norm() < 1e-15);
        for (int k = 0; k < 3; ++k) CHECK(f.bbox.contains(f.v[k]));
    }
    CHECK(m.facet(3).centroid.isApprox(V(1, 1, 1) / 3));
    CHECK(m.facet(3).bbox.min() == V(0, 0, 0));
    CHECK(m.facet(3).bbox.max() == V(1, 1, 1));
    CHECK(certipose::is_closed_manifold(m));
    CHECK_NOTHROW(certipose::validate_closed_manifold(m));
    CHECK(certipose::signed_volume(m) == doctest::Approx(1.0 / 6).epsilon(1e-15));
    CHECK(certipose::num_edges(m) == 6);
    CHECK(certipose::euler_characteristic(m) == 2);
}

TEST_CASE("triangle_mesh: facet id out of range throws certipose::out_of_range") {
    const triangle_mesh m = tetra();
    CHECK_NOTHROW(m.facet(3));
    try {
        (void)m.facet(4);
        FAIL("no exception");
    } catch (const certipose::out_of_range& e) {
        CHECK(e.field() == "facet");
        CHECK(e.index() == 4);
        CHECK(e.size() == 4);
    }
    CHECK_THROWS_AS((void)m.facet(std::numeric_limits<std::size_t>::max()), certipose::error);
}

TEST_CASE("validate_closed_manifold names the offending edge") {
    SUBCASE("open") {
        auto f = tetra_faces();
        f.pop_back();
        const triangle_mesh m(tetra_vertices(), f);
        CHECK_FALSE(certipose::is_closed_manifold(m));
        const std::string msg = mesh_error_message([&] { certipose::validate_closed_manifold(m); });
        CHECK(contains(msg, "edge (2, 1) of face 0"));
        CHECK(contains(msg, "no opposite face"));
    }
    SUBCASE("inconsistent orientation") {
        auto f = tetra_faces();
        f[3] = {1, 3, 2};
        const triangle_mesh m(tetra_vertices(), f);
        CHECK_FALSE(certipose::is_closed_manifold(m));
        CHECK_THROWS_AS(certipose::validate_closed_manifold(m), certipose::mesh_error);
    }
    SUBCASE("non-manifold edge: two tetrahedra sharing an edge") {
        // The second tetrahedron is the first turned 180° about the x axis (a rotation keeps
        // the faces outward); both use the edge (0, 1).
        auto v = tetra_vertices();
        auto f = tetra_faces();
        v.push_back(V(0, -1, 0));
        v.push_back(V(0, 0, -1));
        for (face_indices t : tetra_faces()) {
            for (auto& i : t) i = i == 2 ? 4 : i == 3 ? 5 : i;
            f.push_back(t);
        }
        const triangle_mesh m(v, f);
        CHECK(certipose::signed_volume(m) == doctest::Approx(2.0 / 6));
        const std::string msg = mesh_error_message([&] { certipose::validate_closed_manifold(m); });
        CHECK(contains(msg, "edge (1, 0) of face 0"));
        CHECK(contains(msg, "more than one face"));
    }
}

TEST_CASE("welded merges an STL-style soup and refuses to collapse faces silently") {
    // The tetrahedron as a soup: every face has its own three vertices.
    certipose::triangle_soup soup;
    for (const auto& t : tetra_faces()) {
        const auto base = static_cast<std::uint32_t>(soup.vertices.size());
        for (auto i : t) soup.vertices.push_back(tetra_vertices()[i]);
        soup.faces.push_back({base, base + 1, base + 2});
    }
    const triangle_mesh as_soup(soup);
    CHECK(as_soup.num_vertices() == 12);
    CHECK_FALSE(certipose::is_closed_manifold(as_soup));

    const triangle_mesh exact = certipose::welded(soup, 0.0);
    CHECK(exact.num_vertices() == 4);
    CHECK(certipose::is_closed_manifold(exact));
    CHECK(certipose::signed_volume(exact) == doctest::Approx(1.0 / 6));
    // Faces keep their order and vertices keep the coordinates of the first occurrence.
    for (std::size_t i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) CHECK(exact.facet(i).v[k] == as_soup.facet(i).v[k]);
    CHECK(certipose::welded(as_soup, 0.0).num_vertices() == 4);

    // Perturb the copies by up to 1e-9: exact welding keeps them apart, 1e-6 merges them.
    certipose::triangle_soup noisy = soup;
    for (std::size_t i = 0; i < noisy.vertices.size(); ++i)
        noisy.vertices[i] += V(1e-9, -1e-9, 0.5e-9) * static_cast<double>(i % 3);
    CHECK(certipose::welded(noisy, 0.0).num_vertices() > 4);
    const triangle_mesh merged = certipose::welded(noisy, 1e-6);
    CHECK(merged.num_vertices() == 4);
    CHECK(certipose::is_closed_manifold(merged));

    // A tolerance as large as an edge collapses faces: reported, never dropped.
    const std::string msg = mesh_error_message([&] { certipose::welded(soup, 1.5); });
    CHECK(contains(msg, "collapses 4 face(s)"));
    CHECK(contains(msg, "face 0"));

    for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        try {
            certipose::welded(soup, bad);
            FAIL("no exception");
        } catch (const certipose::invalid_argument& e) {
            CHECK(e.field() == "tolerance");
        }
    }
    CHECK_THROWS_AS(certipose::welded(soup, 1e-300), certipose::invalid_argument);
}

TEST_CASE("scaled, translated and rescaled_to_diagonal") {
    const triangle_mesh m = tetra();
    const triangle_mesh s = certipose::scaled(m, 0.25);
    CHECK(s.bbox().max() == V(0.25, 0.25, 0.25));
    CHECK(certipose::signed_volume(s) == doctest::Approx(0.25 * 0.25 * 0.25 / 6));
    const triangle_mesh d = certipose::rescaled_to_diagonal(m, 0.3);
    CHECK(d.bbox().diagonal().norm() == doctest::Approx(0.3).epsilon(1e-15));
    const triangle_mesh t = certipose::translated(m, V(1, 2, 3));
    CHECK(t.bbox().min() == V(1, 2, 3));
    CHECK(t.faces() == m.faces());
    for (double bad : {0.0, -1.0, std::nan("")}) {
        CHECK_THROWS_AS(certipose::scaled(m, bad), certipose::invalid_argument);
        CHECK_THROWS_AS(certipose::rescaled_to_diagonal(m, bad), certipose::invalid_argument);
    }
    CHECK_THROWS_AS(certipose::translated(m, V(0, std::nan(""), 0)), certipose::invalid_argument);
}

TEST_CASE("sample part: closed, outward, the paper's size and genus") {
    const certipose::sample_part part = certipose::make_sample_part();
    const triangle_mesh& m = part.mesh;
    CHECK(m.num_faces() >= 2000);
    CHECK(m.num_faces() <= 2600);
    CHECK(m.num_faces() == 2300);
    CHECK(m.num_vertices() == 1146);
    CHECK(certipose::is_closed_manifold(m));

    // Bounding box: 0.30 × 0.20 block centred in x, y, bottom at 0, protrusions to 0.08.
    CHECK((m.bbox().min() - V(-0.15, -0.10, 0.0)).norm() < 1e-15);
    CHECK((m.bbox().max() - V(0.15, 0.10, 0.08)).norm() < 1e-15);

    // Expected volume from the documented layout: block − holes · thickness + bosses · height.
    const double block = 0.30 * 0.20 * 0.05;
    const double holes = (0.04 * 0.04 + 0.02 * 0.04 + 0.03 * 0.03) * 0.05;
    const double bosses = (0.04 * 0.06 + 0.09 * 0.02 + 0.04 * 0.04) * 0.03;
    const double expected = block - holes + bosses;
    const double vol = certipose::signed_volume(m);
    CHECK(vol > 0.0);
    CHECK(std::abs(vol - expected) < 1e-9);
    CHECK(std::abs(part.volume - expected) < 1e-12);

    // One connected component, so closed + consistently oriented + positive volume = outward.
    std::vector<std::size_t> parent(m.num_vertices());
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    auto find = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (const auto& t : m.faces()) {
        parent[find(t[1])] = find(t[0]);
        parent[find(t[2])] = find(t[0]);
    }
    std::set<std::size_t> roots;
    for (std::size_t i = 0; i < m.num_vertices(); ++i) roots.insert(find(i));
    CHECK(roots.size() == 1);

    // Euler characteristic of a closed connected orientable surface: 2 − 2·genus.
    CHECK(part.genus == 3);
    CHECK(certipose::euler_characteristic(m) == 2 - 2 * part.genus);

    // Every face axis-aligned: the height field has only ±x, ±y, ±z normals.
    for (const auto& f : m.facets()) CHECK(std::abs(f.normal.cwiseAbs().maxCoeff() - 1.0) < 1e-15);
}

TEST_CASE("sample part: no T-junctions, deterministic") {
    const certipose::sample_part part = certipose::make_sample_part();
    const triangle_mesh& m = part.mesh;
    // No vertex lies strictly inside any edge (a T-junction would also break manifoldness
    // checks in CGAL's booleans).
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& t : m.faces())
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    // Vertices sorted by x, so each edge only looks at those within its x range.
    std::vector<std::uint32_t> by_x(m.num_vertices());
    std::iota(by_x.begin(), by_x.end(), 0u);
    const auto x_of = [&](std::uint32_t i) { return m.vertices()[i].x(); };
    std::sort(by_x.begin(), by_x.end(), [&](auto i, auto j) { return x_of(i) < x_of(j); });
    std::size_t t_junctions = 0;
    for (const auto& [a, b] : edges) {
        const V p = m.vertices()[a], d = m.vertices()[b] - p;
        const double lo = std::min(p.x(), p.x() + d.x()) - 1e-12;
        const double hi = std::max(p.x(), p.x() + d.x()) + 1e-12;
        auto it = std::lower_bound(by_x.begin(), by_x.end(), lo,
                                   [&](std::uint32_t i, double x) { return x_of(i) < x; });
        for (; it != by_x.end() && x_of(*it) <= hi; ++it) {
            const V& q = m.vertices()[*it];
            const double s = (q - p).dot(d) / d.squaredNorm();
            if (s > 1e-9 && s < 1 - 1e-9 && (p + s * d - q).norm() < 1e-12) ++t_junctions;
        }
    }
    CHECK(t_junctions == 0);

    const certipose::sample_part again = certipose::make_sample_part();
    CHECK(again.mesh.vertices() == m.vertices());
    CHECK(again.mesh.faces() == m.faces());
    CHECK(again.facet_of_interest == part.facet_of_interest);
}

TEST_CASE("sample part: the facet of interest is on the top surface next to a protrusion") {
    const certipose::sample_part part = certipose::make_sample_part();
    const triangle_mesh& m = part.mesh;
    const auto& foi = m.facet(part.facet_of_interest);
    CHECK((foi.normal - V(0, 0, 1)).norm() < 1e-15);
    for (const auto& v : foi.v) CHECK(v.z() == 0.05);
    // Under the paper's Figure-5 box [−0.1, 0.1]² × [0.25, 0.3].
    CHECK(std::abs(foi.centroid.x()) < 0.1);
    CHECK(std::abs(foi.centroid.y()) < 0.1);

    // It shares an edge with a vertical wall that rises above the top surface (a protrusion).
    const auto& t = m.faces()[part.facet_of_interest];
    bool next_to_protrusion = false;
    for (std::size_t i = 0; i < m.num_faces(); ++i) {
        if (i == part.facet_of_interest) continue;
        const auto& u = m.faces()[i];
        int shared = 0;
        for (auto a : t)
            for (auto b : u) shared += a == b;
        const auto& f = m.facet(i);
        const double top = std::max({f.v[0].z(), f.v[1].z(), f.v[2].z()});
        if (shared == 2 && std::abs(f.normal.z()) < 1e-15 && top > 0.05 + 1e-6)
            next_to_protrusion = true;
    }
    CHECK(next_to_protrusion);
}

TEST_CASE("sample part: options are validated and scale the layout") {
    for (const char* field :
         {"length", "width", "thickness", "protrusion_height", "max_cell_size"}) {
        certipose::sample_part_options o;
        const std::string f = field;
        (f == "length"              ? o.length
         : f == "width"             ? o.width
         : f == "thickness"         ? o.thickness
         : f == "protrusion_height" ? o.protrusion_height
                                    : o.max_cell_size) = -1.0;
        try {
            certipose::make_sample_part(o);
            FAIL("no exception for " << f);
        } catch (const certipose::invalid_argument& e) {
            CHECK(e.field() == f);
        }
    }
    CHECK_THROWS_AS(certipose::make_sample_part({.max_cell_size = 1e-5}),
                    certipose::invalid_argument);

    const certipose::sample_part big = certipose::make_sample_part({.length = 0.6,
                                                                    .width = 0.4,
                                                                    .thickness = 0.1,
                                                                    .protrusion_height = 0.06,
                                                                    .max_cell_size = 0.028});
    CHECK(big.mesh.num_faces() == 2300);
    CHECK(certipose::is_closed_manifold(big.mesh));
    CHECK(std::abs(certipose::signed_volume(big.mesh) - big.volume) < 1e-9);
    CHECK(big.volume == doctest::Approx(8 * certipose::make_sample_part().volume));

    const certipose::sample_part fine = certipose::make_sample_part({.max_cell_size = 0.007});
    CHECK(fine.mesh.num_faces() > 2300);
    CHECK(certipose::euler_characteristic(fine.mesh) == -4);
    CHECK(fine.mesh.facet(fine.facet_of_interest).normal.z() == 1.0);
}

TEST_CASE("write_mesh_off: writes OFF text and reports unwritable paths") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(CERTIPOSE_BINARY_DIR) / "test_mesh_core";
    fs::create_directories(dir);
    const fs::path file = dir / "tetra.off";
    certipose::write_mesh_off(file, tetra());
    std::ifstream in(file);
    std::string header;
    std::size_t nv = 0, nf = 0, ne = 1;
    in >> header >> nv >> nf >> ne;
    CHECK(header == "OFF");
    CHECK(nv == 4);
    CHECK(nf == 4);
    CHECK(ne == 0);

    const fs::path bad = dir / "no_such_dir" / "x.off";
    try {
        certipose::write_mesh_off(bad, tetra());
        FAIL("no exception");
    } catch (const certipose::io_error& e) {
        CHECK(e.path() == bad.string());
    }
}
