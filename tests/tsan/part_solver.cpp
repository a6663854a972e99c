// The threaded whole-part run under ThreadSanitizer (scripts/tsan.sh; not part of CI, whose 30
// minutes it does not fit): every 100th facet of the sample part on 4 threads with the default
// pipeline — one pose_solver, one AABB occlusion scene shared by every worker — into a sink and a
// progress callback that are plain, unsynchronised code, as users write them. Exits 0 when every
// facet reached the sink in order; TSan's exit code 66 reports a race.
#include <certipose/cgal.hpp>
#include <certipose/part/part_solver.hpp>

#include <cstdio>
#include <vector>

namespace {

struct recording_sink {
    std::vector<std::size_t> order;
    std::size_t boxes = 0;
    void facet(const certipose::facet_outcome<certipose::boost_interval>& o) {
        order.push_back(o.record.index);
        boxes += o.boxes.size();
    }
};

}  // namespace

int main() {
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::part_solver<> solver(part.mesh, camera, {.min_view_angle = 0.35});
    certipose::part_options options;
    options.facet = {.position_eps = 0.1, .orientation_eps = 0.38};
    for (std::size_t f = 0; f < part.mesh.num_faces(); f += 100) options.facets.push_back(f);
    options.threads = 4;
    std::size_t calls = 0;
    options.progress = [&](const certipose::part_progress&) { return ++calls > 0; };
    recording_sink sink;
    const auto r = solver.solve(options, sink);
    std::printf("%zu facets, %zu VALID boxes, %zu progress calls, %zu threads\n", sink.order.size(), sink.boxes, calls,
                r.threads);
    return sink.order == options.facets && calls == options.facets.size() ? 0 : 1;
}
