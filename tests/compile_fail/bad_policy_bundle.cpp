// expect: static assertion failed: certipose::pose_solver: Policies::bisector must model certipose::PositionBisector
// A user bundle derived from the defaults with a contraction policy where the bisector goes:
// pose_solver checks every member of the bundle against its concept, in order.
#include <certipose/cgal.hpp>

struct my_policies : certipose::default_policies {
    using bisector = certipose::contraction::set_only;
};

int main() {
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::pose_solver<my_policies> solver(part.mesh, camera, {});
    return static_cast<int>(solver.solve(0).stats.valid);
}
