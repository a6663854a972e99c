// docs/io.md — read the camera/task JSON, write a result JSON and a PLY, read the result back.
#include <certipose/certipose.hpp>
#include <certipose/io/json.hpp>  // needs nlohmann_json::nlohmann_json

#include <cstdio>
#include <filesystem>
#include <string>

int main() {
    using I = certipose::boost_interval;
    // The camera/task input JSON of docs/io.md (certipose::read_camera_task reads it from a file).
    const certipose::camera_task input = certipose::parse_camera_task(R"({
        "camera": {"model": "thin_lens", "focal_length": 0.012, "f_stop": 8,
                   "focus_distance": 0.6, "max_blur_circle": 6.9e-6, "pixel_pitch": 3.45e-6,
                   "width_px": 2448, "height_px": 2048},
        "task": {"min_view_angle": 0.35}})");

    const certipose::sample_part part = certipose::make_sample_part();
    certipose::solve_options options{.position_eps = 0.1, .orientation_eps = 0.38};

    // Whatever model the file names, the solver can take it as one type (one instantiation):
    // certipose::pose_solver<certipose::with_camera<certipose::calibrated_camera>>.
    const certipose::calibrated_camera camera = input.calibrated();
    std::printf("%s camera, d in [%.6f, %.6f] m\n", camera.model().c_str(), camera.distance_range().min,
                camera.distance_range().max);

    // A stand-in for what the solver returns: one VALID box above the facet, one BOUNDARY box
    // left undecided by the distance constraint.
    certipose::solve_result<I> result;
    result.facet_index = part.facet_of_interest;
    result.boxes.push_back(
        {certipose::box_class::valid,
         {certipose::position_box<I>::from_bounds({{{-0.05, 0.05}, {-0.05, 0.05}, {0.55, 0.6}}}),
          certipose::orientation_box<I>::from_bounds({{{-0.2, 0.2}, {-0.2, 0.2}, {-0.19, 0.19}}})}});
    result.boxes.push_back(
        {certipose::box_class::boundary,
         {certipose::position_box<I>::from_bounds({{{-0.05, 0.05}, {-0.05, 0.05}, {0.75, 0.8}}}),
          certipose::orientation_box<I>::from_bounds({{{-3.1416, 3.1416}, {0.0, 3.1416}, {-3.1416, 3.1416}}})},
         certipose::boundary_reason::distance});
    result.stats.valid = 1;
    result.stats.boundary = 1;
    result.stats.boundary_reasons[static_cast<std::size_t>(certipose::boundary_reason::distance)] = 1;

    const certipose::result_document doc = certipose::make_result_document(
        result, part.mesh, input.camera, input.task, options);
    const auto dir = std::filesystem::temp_directory_path();
    certipose::write_result_json(dir / "certipose_result.json", doc);  // atomic: all or nothing
    certipose::write_ply(dir / "certipose_boxes.ply", part.mesh, doc, {.aim = true});

    const certipose::result_document back = certipose::read_result_json(dir / "certipose_result.json");
    std::printf("facet %zu, d in [%.6f, %.6f] m, %zu box(es); first box x in [%g, %g]\n",
                back.facet.index, back.camera.d_min, back.camera.d_max, back.boxes.size(),
                back.boxes[0].position[0][0], back.boxes[0].position[0][1]);
    std::printf("exact round trip: %s; second box undecided on %s\n", back.boxes == doc.boxes ? "yes" : "no",
                std::string(certipose::to_string(*back.boxes[1].reason)).c_str());
}
