// docs/part.md: every facet of a part (here every 25th of the sample part) with part_solver,
// streamed to a sink in facet order.
#include <certipose/cgal.hpp>
#include <certipose/part.hpp>

#include <cstdio>

namespace {

/// A sink sees each finished facet once, in facet order, from one thread at a time.
struct count_sink {
    std::size_t facets = 0, valid_boxes = 0;
    void facet(const certipose::facet_outcome<certipose::boost_interval>& o) {
        ++facets;
        valid_boxes += o.boxes.size();  // VALID boxes (BOUNDARY ones too with keep_boundary)
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
    options.facet = {.position_eps = 0.1, .orientation_eps = 0.38, .max_boxes = 20000};  // per facet
    for (std::size_t f = 0; f < part.mesh.num_faces(); f += 25) options.facets.push_back(f);
    options.threads = 2;                                   // 0: every core
    options.progress = [](const certipose::part_progress& p) {
        return p.facets_done < p.facets_total;             // return false to cancel
    };
    count_sink sink;
    const certipose::part_result r = solver.solve(options, sink);

    std::printf("%zu facets (%zu skipped): %zu VALID boxes in %.2f s on %zu threads; %s\n", r.facets.size(), r.skipped,
                r.valid, r.seconds, r.threads, certipose::to_string(r.reason));
    for (const certipose::facet_record& rec : r.facets)
        if (rec.termination == certipose::facet_termination::skipped)
            std::printf("facet %zu skipped: %s\n", rec.index, rec.reason.c_str());
    return sink.facets == r.facets.size() && sink.valid_boxes == r.valid ? 0 : 1;
}
