// The files of DESIGN.md §6 with CGAL in the loop: the result JSON round trip over both
// interval backends (the CGAL one holds only the SSE rounding mode, which the readers must
// still neutralise), and the PLY picture parsed back by CGAL's own PLY reader (read_mesh) —
// an independent reader, like MeshLab's and ParaView's.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/interval/cgal_interval.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/ply.hpp>
#include <certipose/io/read_mesh.hpp>

#include <doctest/doctest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(CERTIPOSE_BINARY_DIR) / "test_io_cgal";
    fs::create_directories(dir);
    return dir / name;
}

certipose::triangle_mesh tetrahedron() {
    return certipose::triangle_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                    {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}});
}

const char* const camera_json = R"({"camera": {"model": "thin_lens", "focal_length": 0.012,
    "f_stop": 8, "focus_distance": 0.6, "max_blur_circle": 6.9e-6, "pixel_pitch": 3.45e-6,
    "width_px": 2448, "height_px": 2048}, "task": {"min_view_angle": 0.35}})";

}  // namespace

TEST_CASE_TEMPLATE("result JSON and PLY under a held rounding mode, read back exactly", I,
                   certipose::boost_interval, certipose::cgal_interval) {
    const auto mesh = tetrahedron();
    const auto input = certipose::parse_camera_task(camera_json);
    const fs::path json_file = scratch("result.json");
    const fs::path ply_file = scratch("boxes.ply");
    certipose::solve_result<I> result;
    certipose::result_document doc, back;
    {
        const certipose::rounding_guard<I> guard;  // as inside the solver: mode held upward
        const double third = 1.0 / 3.0;            // computed upward: not the nearest double
        result.facet_index = 3;
        result.boxes.push_back(
            {certipose::box_class::valid,
             {certipose::position_box<I>::from_bounds({{{0.1, 0.2}, {third, 0.5}, {0.3, 0.30000000000000004}}}),
              certipose::orientation_box<I>::from_bounds({{{-0.7, 0.7}, {0.1, 0.123456789}, {-third, third}}})}});
        result.boxes.push_back(
            {certipose::box_class::boundary,
             {certipose::position_box<I>::from_bounds({{{-2, -1.5}, {1e-9, 2e-9}, {0.5, 0.75}}}),
              certipose::orientation_box<I>::from_bounds({{{0, 1}, {0, 1}, {0, 1}}})}});
        result.stats.valid = 1;
        result.stats.boundary = 1;
        result.stats.seconds = 0.123456789;

        doc = certipose::make_result_document(result, mesh, input.camera, input.task, {});
        certipose::write_result_json(json_file, doc);
        back = certipose::read_result_json(json_file);
        certipose::write_ply(ply_file, mesh, result);
    }
    REQUIRE(back.boxes.size() == 2);
    for (std::size_t b = 0; b < 2; ++b)
        for (int d = 0; d < 3; ++d) {
            CHECK(std::bit_cast<std::uint64_t>(back.boxes[b].position[d][0]) ==
                  std::bit_cast<std::uint64_t>(certipose::lower(result.boxes[b].box.position[d])));
            CHECK(std::bit_cast<std::uint64_t>(back.boxes[b].orientation[d][1]) ==
                  std::bit_cast<std::uint64_t>(certipose::upper(result.boxes[b].box.orientation[d])));
        }
    CHECK(back.stats.seconds == 0.123456789);
    CHECK(back.camera == doc.camera);

    // CGAL's PLY reader takes the picture: 4 part vertices + 3 facet copies + 8 per box; the
    // part's 3 other faces + the facet + 12 per box, in that order. (Read in round-to-nearest:
    // CGAL's text readers, like strtod, honour the rounding mode.)
    const certipose::triangle_mesh read = certipose::read_mesh(ply_file);
    CHECK(read.num_vertices() == 4 + 3 + 16);
    CHECK(read.num_faces() == 3 + 1 + 24);
    for (int k = 0; k < 3; ++k) CHECK(read.facet(3).v[k] == mesh.facet(3).v[k]);
    CHECK(read.facet(3).normal.isApprox(mesh.facet(3).normal));
    for (std::size_t b = 0; b < 2; ++b) {
        Eigen::AlignedBox3d box;
        for (std::size_t f = 4 + 12 * b; f < 4 + 12 * (b + 1); ++f) box.extend(read.facet(f).bbox);
        for (int d = 0; d < 3; ++d) {
            CHECK(box.min()[d] == certipose::lower(result.boxes[b].box.position[d]));
            CHECK(box.max()[d] == certipose::upper(result.boxes[b].box.position[d]));
        }
    }
}
